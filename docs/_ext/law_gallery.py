"""Sphinx extension: a worked-example page per non-polynomial preset law, executed at build time.

For each preset of :data:`fpucore.law.presets.PRESETS` that is not a polynomial (exponential,
tanh, rational) :func:`compute` runs five routes — the force law with α, w*, β and the
represented interval, the QC existence diagram, a discrete superkink, a discrete solitary wave
with its Floquet verdict (finite-size window on), and a Riemann run with wave tracking — at a
small size (N = 200, L = 400, t until the fastest signal could reach the ends: a few seconds
a law).  The numbers are pickled in
``$FPU_CACHE_DIR/laws`` keyed by the sha256 of fpucore's source (the same key as the paper
gallery), the figures drawn with Matplotlib beside them, and one MyST page per law written into
``docs/laws/`` (generated, not committed) with the figures, the numbers with their error bars and
run times, and the code that made them (``compute``'s source by ``literalinclude``).  A route
that raises fails the build (ExtensionError naming the law and the route).
"""

from __future__ import annotations

import pickle
import shutil
import time
from pathlib import Path

from sphinx.application import Sphinx
from sphinx.errors import ExtensionError
from sphinx.util import logging

logger = logging.getLogger(__name__)

PAGES = "laws"
N_WAVE = 200  # sites of the discrete waves (their tails decay within ~40 sites)
L_RIEMANN = 400  # the run stops before the fastest signal, speed √f′(w*), reaches a wall


def smooth_presets() -> list[str]:
    """The presets that are not polynomials (built as :class:`fpucore.law.SmoothLaw`)."""
    from fpucore.law import SmoothLaw
    from fpucore.law.presets import PRESETS, preset_law

    return [n for n in PRESETS if isinstance(preset_law(n), SmoothLaw)]


def compute(name: str) -> dict:
    """Every route for the preset ``name``, at docs size; plain numbers and arrays."""
    import numpy as np

    from fpucore import floquet, qc, simulate, wave
    from fpucore.law.presets import PRESETS, preset_law
    from fpucore.qc.diagram import existence_diagram

    out: dict = {"name": name, "text": PRESETS[name].text, "constants": PRESETS[name].constants}
    t0 = time.perf_counter()
    law = preset_law(name)  # parse, class check, Chebyshev representation
    lo, hi = law.interval
    w = np.linspace(lo, hi, 801)
    out["law"] = dict(alpha=law.alpha, alpha_error=law.alpha_error, w_star=law.w_star,
                      w_star_error=law.w_star_error, beta=law.beta, beta_error=law.beta_error,
                      interval=law.interval, representation=str(law.representation_error),
                      w=w, f=law.f(w), elapsed_s=time.perf_counter() - t0)  # fmt: skip

    d = existence_diagram(law, n=80)
    out["diagram"] = dict(w_plus=d.w_plus, c_plus=d.c_plus, V_SK=d.V_SK, c_minus=d.c_minus,
                          elapsed_s=d.elapsed_s)  # fmt: skip

    v_lo, v_hi = qc.superkink_velocity_bounds(law, "lower")
    V = v_lo + 0.6 * (v_hi - v_lo)
    sk = wave.solve_superkink(law, V, N=N_WAVE)
    sk_qc = qc.superkink_from_V(law, V)  # the QC superkink at the same V: its end states
    out["superkink"] = dict(V=V, n=sk.n, w=sk.w, converged=sk.converged, residual=sk.residual,
                            profile_error=sk.profile_error, w_plus_qc=sk_qc.w_plus,
                            w_minus_qc=sk_qc.w_minus, elapsed_s=sk.elapsed_s)  # fmt: skip

    wp_lo = qc.superkink_w_plus_range(law, "lower")[0]
    w_plus = wp_lo + 0.5 * (law.w_star - wp_lo)
    c_plus, v_sk, _ = qc.sound_speeds(law, w_plus)
    Vs = c_plus + 0.5 * (v_sk - c_plus)
    sw = wave.solve_solitary(law, w_plus, Vs, N=N_WAVE)
    fl = floquet.spectrum(sw, finite_size=True)
    out["solitary"] = dict(w_plus=w_plus, V=Vs, c_plus=c_plus, V_SK=v_sk, n=sw.n, w=sw.w,
                           converged=sw.converged, residual=sw.residual,
                           profile_error=sw.profile_error, energy=sw.energy,
                           energy_error=sw.energy_error, elapsed_s=sw.elapsed_s)  # fmt: skip
    out["floquet"] = dict(multipliers=fl.multipliers, max_modulus=fl.max_modulus, error=fl.error,
                          classification=fl.classification, verdict=fl.verdict,
                          elapsed_s=fl.elapsed_s)  # fmt: skip

    w_left = law.w_star + 0.5 * (law.beta - law.w_star)  # behind: softening side
    w_right = 0.5 * law.w_star  # ahead: hardening side (0.2 w* leaves the exponential's α)
    t_end = 0.8 * (L_RIEMANN / 2) / float(np.sqrt(law.df(law.w_star)))
    res = simulate.riemann(law, w_left, w_right, L=L_RIEMANN, t_end=t_end)
    out["riemann"] = dict(w_left=w_left, w_right=w_right, t_end=t_end, t=res.t, sites=res.sites,
                          snapshots=res.snapshots, status=res.status, message=res.message,
                          energy_drift=res.energy_drift, error_estimate=res.error_estimate,
                          waves=[(x.kind, x.velocity, x.velocity_error, x.amplitude)
                                 for x in res.waves],
                          elapsed_s=res.elapsed_s)  # fmt: skip
    return out


def cached(name: str, version: str) -> dict:
    """:func:`compute`'s result, from ``$FPU_CACHE_DIR/laws/<version>/<name>.pickle`` if there."""
    from fpucore.paper.report import cache_dir

    path = cache_dir().parent / PAGES / version / f"{name}.pickle"
    if path.exists():
        try:
            return pickle.loads(path.read_bytes())
        except Exception:  # a torn or stale file: recompute
            pass
    data = compute(name)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_bytes(pickle.dumps(data))
    tmp.replace(path)
    return data


def draw(data: dict, folder: Path) -> list[str]:
    """The five figures of one law as PNGs in ``folder``; their file names."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    name = data["name"]
    names = []

    def save(fig, what):
        fn = f"{name}_{what}.png"
        fig.tight_layout()
        fig.savefig(folder / fn, dpi=80)
        plt.close(fig)
        names.append(fn)

    lw = data["law"]
    fig, ax = plt.subplots(figsize=(6, 3.2))
    ax.axvspan(*lw["interval"], color="0.93", label="represented interval")
    ax.plot(lw["w"], lw["f"], "k-", lw=1.5, label="f(w)")
    for x, lab, c in ((lw["alpha"], "α", "tab:blue"), (lw["w_star"], "w*", "tab:green"),
                      (lw["beta"], "β", "tab:red")):  # fmt: skip
        ax.axvline(x, color=c, ls="--", lw=1, label=lab)
    ax.set(xlabel="strain w", ylabel="force f(w)")
    ax.legend(fontsize=7, loc="best")
    save(fig, "force")

    d = data["diagram"]
    fig, ax = plt.subplots(figsize=(6, 3.2))
    ax.plot(d["w_plus"], d["c_plus"], "b-", label="c₊")
    ax.plot(d["w_plus"], d["V_SK"], "k-", lw=2, label="V_SK (superkinks)")
    ax.plot(d["w_plus"], d["c_minus"], "r-", label="c₋")
    ax.axvline(lw["w_star"], color="tab:green", ls="--", lw=1, label="w*")
    ax.set(xlabel="state ahead w₊", ylabel="velocity V")
    ax.legend(fontsize=7)
    save(fig, "diagram")

    for key in ("superkink", "solitary"):
        s = data[key]
        fig, ax = plt.subplots(figsize=(6, 3.0))
        ax.plot(s["n"], s["w"], "k.-", ms=3, lw=0.8)
        ax.set(xlabel="site n", ylabel="strain w_n(0)", title=f"V = {s['V']:.6g}")
        c = len(s["n"]) // 2
        ax.set_xlim(s["n"][max(0, c - 40)], s["n"][min(len(s["n"]) - 1, c + 40)])
        save(fig, key)

    mu = np.asarray(data["floquet"]["multipliers"])
    fig, ax = plt.subplots(figsize=(3.4, 3.4))
    th = np.linspace(0, 2 * np.pi, 400)
    ax.plot(np.cos(th), np.sin(th), color="0.7", lw=1)
    ax.plot(mu.real, mu.imag, "k.", ms=3)
    ax.set(xlabel="Re μ", ylabel="Im μ", aspect="equal", title="Floquet multipliers")
    save(fig, "floquet")

    r = data["riemann"]
    fig, ax = plt.subplots(figsize=(6, 3.4))
    im = ax.pcolormesh(r["sites"], r["t"], r["snapshots"], shading="auto", cmap="viridis")
    fig.colorbar(im, ax=ax, label="strain w_n(t)")
    ax.set(xlabel="site n", ylabel="time t")
    save(fig, "riemann")
    return names


def _pm(x: float, e: float) -> str:
    return f"{x:.10g} ± {e:.2g}"


def law_page(data: dict, version: str) -> str:
    """The MyST source of one law's page."""
    from paper_gallery import md_text

    name, lw, d = data["name"], data["law"], data["diagram"]
    sk, sw, fl, r = data["superkink"], data["solitary"], data["floquet"], data["riemann"]
    mu_max = _pm(fl["max_modulus"], fl["error"])
    consts = ", ".join(f'"{k}": {v:g}' for k, v in data["constants"])
    waves = "; ".join(f"{k} at V = {v:.6g} ± {e:.2g} (amplitude {a:.4g})" for k, v, e, a
                      in r["waves"]) or "none tracked"  # fmt: skip
    return f"""(laws-{name})=
# The {name} law

f(w) = `{data["text"]}` with {md_text(", ".join(f"{k} = {v:g}" for k, v in data["constants"]))}.
Every number and figure below was computed by fpucore when this page was built (fpucore source
`{version}`), each with its error bar and its run time.

## Force law

![force law of the {name} preset]({name}_force.png)

| quantity | value | |
|---|---|---|
| α (f′ = 0 below 0) | {_pm(lw["alpha"], lw["alpha_error"])} | |
| w* (f″ = 0, + to −) | {_pm(lw["w_star"], lw["w_star_error"])} | |
| β (f′ = 0 above 0) | {_pm(lw["beta"], lw["beta_error"])} | |
| represented interval | [{lw["interval"][0]:.6g}, {lw["interval"][1]:.6g}] | |
| representation error | {md_text(lw["representation"])} | |
| first use (parse, class check, representation) | {lw["elapsed_s"]:.3f} s | |

## Existence diagram (QC)

Sonic speeds c₊, c₋ and the superkink velocity V_SK over the state ahead w₊ ({len(d["w_plus"])}
points, {d["elapsed_s"]:.2f} s).  Between c₊ and V_SK, and between V_SK and c₋, live solitary
waves; on V_SK the superkinks.

![existence diagram of the {name} preset]({name}_diagram.png)

## A discrete superkink

Lower branch at V = {sk["V"]:.10g} (60 % into its velocity range), N = {len(sk["n"])} sites:
converged {sk["converged"]}, residual {sk["residual"]:.2g}, profile error bound
{sk["profile_error"]:.2g}, {sk["elapsed_s"]:.2f} s.  QC end states at this V: w₊ =
{sk["w_plus_qc"]:.10g}, w₋ = {sk["w_minus_qc"]:.10g}.

![discrete superkink of the {name} preset]({name}_superkink.png)

## A solitary wave and its Floquet verdict

State ahead w₊ = {sw["w_plus"]:.10g} (c₊ = {sw["c_plus"]:.10g}, V_SK = {sw["V_SK"]:.10g}),
V = {sw["V"]:.10g}, N = {len(sw["n"])}: converged {sw["converged"]}, residual
{sw["residual"]:.2g}, E_ren = {_pm(sw["energy"], sw["energy_error"])}, {sw["elapsed_s"]:.2f} s.

Floquet ({fl["elapsed_s"]:.2f} s, finite-size window on): max|μ| = {mu_max},
**{md_text(fl["classification"])}** — {md_text(fl["verdict"])}

![discrete solitary wave of the {name} preset]({name}_solitary.png)
![Floquet multipliers of the solitary wave]({name}_floquet.png)

## A Riemann run

w_n(0) = {r["w_left"]:.6g} for n ≤ {L_RIEMANN // 2}, {r["w_right"]:.6g} beyond, at rest; L =
{L_RIEMANN}, t = 0 … {r["t_end"]:.4g} (0.8 of the time the fastest signal, speed √f′(w*), needs
to reach a wall): {r["status"]} ({md_text(r["message"])}), relative energy
drift {r["energy_drift"]:.2g}, {r["elapsed_s"]:.2f} s.  Tracked waves: {md_text(waves)}.

![Riemann run of the {name} preset]({name}_riemann.png)

## The code that computes this page

```python
from fpucore.law.presets import preset_law
law = preset_law("{name}")   # = fpucore.law_from_expression("{data["text"]}", {{{consts}}})
```

and then, route by route (`docs/_ext/law_gallery.py`):

```{{literalinclude}} ../_ext/law_gallery.py
:language: python
:pyobject: compute
```
"""


def index_page(names: list[str]) -> str:
    lines = [
        "(laws)=",
        "# Worked examples: smooth laws",
        "",
        "One page per non-polynomial preset of `fpucore.law.presets`: its force law, existence",
        "diagram, a discrete superkink, a solitary wave with its Floquet verdict and a Riemann",
        "run, computed by fpucore when this site was built (`make docs`; the grammar of laws is",
        "in {doc}`../guide/laws`).",
        "",
        "```{toctree}",
        ":maxdepth: 1",
        "",
        *names,
        "```",
        "",
    ]
    return "\n".join(lines)


def build_law_pages(app: Sphinx) -> None:
    from paper_gallery import write_if_changed

    from fpucore.paper.report import cache_dir, code_version

    t0 = time.perf_counter()
    version = code_version()
    out = Path(app.srcdir) / PAGES
    png_cache = cache_dir().parent / PAGES / version / "png"
    names = smooth_presets()
    keep = {"index.md"}
    for name in names:
        try:
            data = cached(name, version)
            if not (png_cache / f"{name}_force.png").exists():
                png_cache.mkdir(parents=True, exist_ok=True)
                draw(data, png_cache)
        except Exception as exc:
            raise ExtensionError(f"law pages: {name}: {type(exc).__name__}: {exc}") from exc
        for png in sorted(png_cache.glob(f"{name}_*.png")):
            write_if_changed(out / png.name, png.read_bytes())
            keep.add(png.name)
        write_if_changed(out / f"{name}.md", law_page(data, version).encode())
        keep.add(f"{name}.md")
    write_if_changed(out / "index.md", index_page(names).encode())
    for stale in out.iterdir():
        if stale.name not in keep:
            shutil.rmtree(stale) if stale.is_dir() else stale.unlink()
    logger.info(f"law pages: {len(names)} laws in {time.perf_counter() - t0:.1f} s")


def setup(app: Sphinx) -> dict:
    app.connect("builder-inited", build_law_pages)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
