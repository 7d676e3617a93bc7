"""Export where users work: every scene's "Figure SVG / PNG" is the scene as drawn (its Bokeh
models' data redrawn server side, no browser) and its "Notebook" runs top to bottom in a fresh
kernel and prints the numbers on screen; "Hold" keeps curves over slider moves until "Clear"."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

pytest.importorskip("panel")
pytest.importorskip("matplotlib")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from app.views.export import code_cells  # noqa: E402
from fpucore import qc  # noqa: E402
from fpucore.law import CubicLaw  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}
SVG = "{http://www.w3.org/2000/svg}"
LAW = CubicLaw(a=-1.0, b=10.0)


def scene(key: str, discrete: bool = False, **state):
    """A scene rendered once (the profiles scene: QC only unless ``discrete``)."""
    sc = BY_KEY[key](ExplorerState(**state))
    if key == "profiles":
        sc.show_discrete.value = discrete
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return sc


def download(widget) -> tuple[str, bytes | str]:
    buf = widget.callback()
    return widget.filename, buf.getvalue()


def group_vertices(svg: bytes, gid: str) -> list[int]:
    """Number of vertices of each path in the SVG group ``gid``."""
    root = ET.fromstring(svg)
    groups = [g for g in root.iter(f"{SVG}g") if g.get("id") == gid]
    assert groups, f"no group {gid!r} in the SVG"
    return [len(re.findall(r"[ML]", p.get("d", ""))) for p in groups[0].iter(f"{SVG}path")]


def test_the_figure_svg_is_valid_xml_with_the_drawn_curve():
    sc = scene("profiles")
    name, svg = download(sc.fig_svg)
    assert name == "profiles.svg"
    assert ET.fromstring(svg).tag == f"{SVG}svg"
    # the QC curve as drawn: one path through all 1601 samples of the scene's source
    xi = sc.r_qc[1].data["x"]
    assert len(xi) == 1601
    assert max(group_vertices(svg, "profile-qc")) == len(xi)
    name, png = download(sc.fig_png)
    assert name == "profiles.png" and png[:8] == b"\x89PNG\r\n\x1a\n"


def test_every_figure_of_a_multi_figure_scene_is_exported():
    sc = scene("diagram")  # (a), (b) in the main pane, (c) in its own pane
    svg = sc.export_figure("svg")
    titles = [t for t in re.findall(rb"<!-- (.*?) -->", svg)]
    text = b" ".join(titles)
    for title in (b"(a) amplitude", b"(b) renormalized energy", b"(c) where solitary"):
        assert title in text, title
    # the existence diagram's current point is where the state is
    assert group_vertices(svg, "diagram-current")


def test_no_export_while_a_message_is_shown():
    sc = BY_KEY["profiles"](ExplorerState(V=99.0))
    sc.refresh()
    assert sc.last_message
    assert sc.fig_svg.disabled and sc.fig_png.disabled and sc.notebook.disabled
    name, text = download(sc.notebook)
    assert name == "profiles-unavailable.txt" and "nothing shown" in text
    sc.state.V = 5.0
    sc.refresh()
    assert not (sc.fig_svg.disabled or sc.fig_png.disabled or sc.notebook.disabled)


def test_the_notebook_cells_are_the_copy_as_python_code():
    sc = scene("profiles", N=128)
    nb = json.loads(sc.export_notebook())
    code = [c for c in nb["cells"] if c["cell_type"] == "code"]
    src = ["".join(c["source"]) for c in code]
    assert "\n".join(src[:-1]) == sc.python_code().rstrip("\n")  # exactly the copied code
    assert src[0].rstrip().endswith("law = CubicLaw(a=-1.0, b=10.0)")  # imports and the law
    assert src[1].startswith("q = qc.solitary(law, 1.0, 5.0)")  # one computation per cell
    assert "plt" in src[-1]  # the plot cell
    md = "".join(nb["cells"][0]["source"])
    assert "tab=profiles" in md and "amplitude" in md  # the state and what was on screen


def test_code_cells_keep_a_comment_with_its_computation():
    code = "import x\nlaw = L()\n# the family\nfam = f(law)\nprint(fam)\nd = g(law)\n"
    assert code_cells(code) == ["import x\nlaw = L()", "# the family\nfam = f(law)\nprint(fam)",
                                "d = g(law)"]  # fmt: skip


def test_held_profiles_survive_slider_moves_and_clear():
    sc = scene("profiles")
    assert sc.held.hold()  # V = 5.0; the hold re-renders in the scene's worker
    assert sc.wait_idle()
    sc.state.V = 5.2
    sc.refresh()
    assert sc.held.hold() and sc.wait_idle()
    sc.state.V = 4.8
    sc.refresh()
    srcs = [sc.held.lines[k][1] for k in range(2)]
    for src, V in zip(srcs, (5.0, 5.2)):
        x = np.asarray(src.data["x"])
        exact = qc.solitary(LAW, 1.0, V).profile(x)  # the closed form at the held V
        assert np.max(np.abs(np.asarray(src.data["y"]) - exact)) < 1e-12
    assert [r.visible for r in (sc.held.lines[0][0], sc.held.lines[1][0])] == [True, True]
    assert not sc.held.lines[2][0].visible
    # the current curve moved on; the held ones are in the code, the CSV and the figure
    assert "held.append((qc.solitary(law, 1.0, 5.2), None))" in sc.python_code()
    _, csv = sc.download_data()
    assert "held V = 5.2, w₊ = 1 y" in csv.getvalue()
    svg = sc.export_figure("svg")
    assert max(group_vertices(svg, "profile-held-1")) == 1601
    sc.held.clear_btn.clicks += 1  # "Clear held"
    sc.wait_idle()
    assert not sc.held.items
    assert all(not ln[0].visible for ln in sc.held.lines)
    assert "held" not in sc.python_code()


def test_held_orbits_on_the_phase_plane():
    sc = scene("phase")
    orbit = np.asarray(sc.r_orbits[0][1].data["x"])
    sc.held.hold_btn.clicks += 1  # "Hold curve"
    sc.wait_idle()
    sc.state.V = 5.2
    sc.refresh()
    held = np.asarray(sc.held.lines[0][1].data["x"])
    assert np.array_equal(held[: len(orbit)], orbit)  # the orbit drawn at V = 5, kept
    assert "held.append(phase.phase_plane(law, 1.0, 5.0, n_grid=241))" in sc.python_code()


def _outputs(nb) -> str:
    out = []
    for cell in nb.cells:
        for o in cell.get("outputs", []):
            out.append(o.get("text", ""))
            if o.get("output_type") == "error":
                out.append(f"ERROR {o.get('ename')}: {o.get('evalue')}")
    return "\n".join(out)


def run_notebook(sc, tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = nbformat.reads(sc.export_notebook(), as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()  # fmt: skip
    text = _outputs(nb)
    assert "ERROR" not in text, text[-2000:]
    assert any(o.get("output_type") == "display_data" for o in nb.cells[-1].outputs)  # the plot
    return text


def test_a_phase_plane_notebook_reproduces_the_screen(tmp_path):
    sc = scene("phase", V=5.2)
    text = run_notebook(sc, tmp_path)
    pp = sc._pp
    printed = repr([(c.kind, c.w) for c in pp.critical_points]).replace("np.float64(", "")
    line = next(ln for ln in text.splitlines() if ln.startswith(pp.regime))
    got = [float(v) for v in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", line)]
    want = [float(v) for v in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", printed)]
    assert got == pytest.approx(want, rel=1e-13, abs=1e-13) and len(got) == 3


def test_a_discrete_wave_notebook_reproduces_the_screen(tmp_path):
    sc = scene("profiles", N=128, discrete=True)
    assert sc.held.hold() and sc.wait_idle()
    sc.state.V = 5.2
    sc.refresh()
    r = sc._discrete
    assert r is not None and r.converged
    text = run_notebook(sc, tmp_path)
    line = next(ln for ln in text.splitlines() if ln.startswith("True "))
    _, residual, amplitude = line.split()
    assert float(amplitude) == pytest.approx(r.amplitude, rel=1e-12)  # on screen: the amplitude
    assert float(residual) < 1e-9


@pytest.mark.parametrize("key", ["force", "phase", "profiles", "diagram"])
def test_every_notebook_cell_is_python_and_every_figure_exports(key):
    sc = scene(key)
    nb = json.loads(sc.export_notebook())
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            compile("".join(cell["source"]), f"{key} cell", "exec")  # a SyntaxError fails
    assert any(True for _ in ET.fromstring(sc.export_figure("svg")).iter(f"{SVG}path"))


NUM = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def numbers(text: str) -> list[float]:
    """The numbers of a printed line (NumPy scalars print as np.float64(x))."""
    return [float(v) for v in re.findall(NUM, text.replace("np.float64", ""))]


def printed_line(text: str, start: str) -> str:
    return next(ln for ln in text.splitlines() if ln.startswith(start))


@pytest.mark.slow
def test_a_floquet_notebook_reproduces_the_spectrum_and_the_sweep(tmp_path):
    """The Floquet scene at N = 64 with a 4-velocity superkink sweep: the notebook's max|μ|,
    its error bar and class, and every swept max|μ| are the screen's (to 1e-12)."""
    sc = scene("floquet", N=64, mode="superkink", w_plus=0.6327161199294542)
    sc.n_sweep.value = 4
    sc._want_sweep = True  # "Run sweep"
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    fr, sw = sc._fr, sc._sweep_result
    assert sw is not None and len(sw.V) == 4
    text = run_notebook(sc, tmp_path)
    n, mm, err, cls = printed_line(text, f"{2 * 64} ").split()
    assert int(n) == len(fr.multipliers) and cls == fr.classification
    assert float(mm) == pytest.approx(fr.max_modulus, abs=1e-12)
    assert float(err) == pytest.approx(fr.error, rel=1e-6, abs=1e-15)
    line = printed_line(text, "[")
    got = numbers(line)
    assert got[:4] == pytest.approx(list(sw.V), abs=1e-15)
    assert got[4:8] == pytest.approx(list(sw.max_modulus), abs=1e-12)
    assert [c for c in sw.classification] == re.findall(r"'(\w+)'", line)


@pytest.mark.slow
def test_a_simulation_notebook_reproduces_the_run(tmp_path):
    """A short seeded run (L = 400, t_end = 5): the notebook's energy drift and tracked wave
    velocity are the screen's (the integrator is deterministic: to 1e-12)."""
    sc = BY_KEY["simulation"](ExplorerState(N=64))
    sc.L.value, sc.t_end.value = 400, 5.0
    sc._want_run = True  # "Run simulation"
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    sim = sc._sim[-1]
    assert sim.waves
    text = run_notebook(sc, tmp_path)
    line = next(ln for ln in text.splitlines() if "[('" in ln)  # drift, [(kind, V, error)]
    got = numbers(line)
    assert got[0] == pytest.approx(sim.energy_drift, rel=1e-9, abs=0)
    want = [x for w in sim.waves for x in (w.velocity, w.velocity_error)]
    assert got[1:] == pytest.approx(want, rel=1e-12, abs=1e-15)


@pytest.mark.slow
def test_an_atlas_notebook_reproduces_the_map(tmp_path):
    """A tiny atlas (2 w₊ rows × 3 V, N = 80) run from the scene: the notebook prints the
    quantity on screen (max|μ|), equal cell by cell to the scene's image."""
    sc = BY_KEY["atlas"](ExplorerState())
    sc.n_w.value, sc.n_V.value, sc.N_run.value = 2, 3, 80
    sc._want_run = True  # "Run a small atlas"
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    z = np.asarray(sc.last_z, float) + 1.0  # the scene draws max|μ| − 1
    assert z.shape == (2, 3) and np.isfinite(z).all()
    text = run_notebook(sc, tmp_path)
    got = np.array(numbers(printed_line(text, "[[")), float).reshape(2, 3)
    assert np.max(np.abs(got - z)) < 1e-12


@pytest.mark.slow
def test_a_diagrams_notebook_reproduces_the_dots_and_the_branch_view(tmp_path):
    """The Diagrams scene with discrete dots and both branch views (4 velocities each, N = 64):
    the notebook's c₊, V_SK, c₋, the dots' amplitude and E_ren, the solitary sweep's classes and
    the superkink sweep's amplitudes, max|μ| and classes are the screen's."""
    sc = BY_KEY["diagram"](ExplorerState(N=64))
    sc.n_discrete.value = 2
    sc._want_discrete = sc._want_branch = True  # both buttons
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    # superkink mode (V = V_SK(1)): the button sweeps the superkinks (d); the solitary family's
    # dots and branch (same w₊, cached) stay
    sc.state.mode = "superkink"
    assert sc.wait_idle(600)
    sc.classify_btn.clicks += 1
    assert sc.wait_idle(600)
    assert sc.last_message is None, sc.last_message
    fam, rows, sw = sc._fam, sc._rows, sc._branch
    assert len(rows) == 4 and sw is not None and sc._sk_branch is not None
    sk, amp, _ = sc._sk_branch
    text = run_notebook(sc, tmp_path)
    line = [ln for ln in text.splitlines() if ln.startswith("[(") and "np.float64" not in ln][-1]
    assert re.findall(r"'(\w+)'", line) == list(sk.classification)
    got = np.array(numbers(line), float).reshape(len(sk.V), 3)  # V, |w₋ − w₊|, max|μ|
    assert np.max(np.abs(got[:, 0] - sk.V)) == 0.0 and np.max(np.abs(got[:, 1] - amp)) < 1e-12
    assert np.max(np.abs(got[:, 2] - sk.max_modulus)) < 1e-12
    got = numbers(printed_line(text, f"{fam.c_plus!r}"[:5]))
    assert got == pytest.approx([fam.c_plus, fam.V_SK, fam.c_minus], abs=1e-14)
    dots = numbers(printed_line(text, "[(4."))
    want = [x for r in rows for x in (r.V, r.amplitude, r.energy)]
    assert dots == pytest.approx(want, rel=1e-12, abs=1e-12)
    line = printed_line(text, "[(np.float64(")
    assert re.findall(r"'(\w+)'", line) == list(sw.classification)
    branch = numbers(line)
    assert branch[1::2] == pytest.approx(list(sw.energy), rel=1e-12)
