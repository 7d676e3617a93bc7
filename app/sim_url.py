"""The Simulation scene's inputs in a link: ``sim=`` holds the initial data and the run's
options, ``run=1`` says the run was on screen (a fresh page runs it again).

Form: ``kind:name=value,…`` with the names of
:meth:`app.views.simulation.SimulationScene.show_scenario` — for example
``riemann:L=3600,t_end=300.0,guard=convex,w_left=4.6,w_right=0.0,probes=100;200;3000``; floats
exact (repr).  Only the initial data of the kind are written (w_left, w_right for Riemann data;
w_B, A for a Gaussian; the seeding wave is the state's own: mode, w_plus, V, N, tol).  Every
value is checked like the scene's widgets (the same ranges); the run itself checks the rest
(a strain outside the law's interval is named by fpucore when it starts).
"""

from __future__ import annotations

import math

from fpucore.errors import ParameterError
from fpucore.simulate import GUARDS

KINDS = ("seeded", "riemann", "gaussian")
#: the initial data each kind takes (beyond L, t_end, guard, probes)
DATA = {"seeded": (), "riemann": ("w_left", "w_right"), "gaussian": ("w_B", "A")}
#: the widgets' ranges (app.views.simulation)
L_RANGE = (50, 20000)
T_RANGE = (0.1, 2000.0)
MAX_SITES = 3
MAX_URL_SIM = 300
FORM = "kind:L=…,t_end=…,guard=…[,w_left=…,w_right=… | ,w_B=…,A=…][,probes=n;n;n]"


def format_sim(kind: str, L: int, t_end: float, guard: str, probes=(), **data) -> str:
    """The ``sim`` value of the scene's inputs (only the initial data ``kind`` uses)."""
    parts = [f"L={int(L)}", f"t_end={float(t_end)!r}", f"guard={guard}"]
    parts += [f"{k}={float(data[k])!r}" for k in DATA[kind]]
    if probes:
        parts.append("probes=" + ";".join(str(int(p)) for p in probes))
    return f"{kind}:" + ",".join(parts)


def sc_inputs(scenario: dict) -> dict:
    """The inputs of a scenario dict (app.paper_figures FIGURE_SCENARIO, a parsed ``sim``):
    without its "run" and "run_s" entries."""
    return {k: v for k, v in scenario.items() if k not in ("run", "run_s")}


def _float(name: str, raw: str, lo: float | None = None, hi: float | None = None) -> float:
    valid = "a finite number" if lo is None else f"[{lo:g}, {hi:g}]"
    try:
        x = float(raw)
    except ValueError:
        raise ParameterError(f"sim {name}", raw, valid, "not a number") from None
    if not math.isfinite(x) or (lo is not None and not lo <= x <= hi):
        raise ParameterError(f"sim {name}", raw, valid)
    return x


def parse_sim(raw: str) -> dict:
    """A ``sim`` value → the scene's inputs {kind, L, t_end, guard, probes, data…} (the
    keywords of show_scenario); ParameterError naming the entry and its valid form."""
    text = raw.strip()
    if len(text) > MAX_URL_SIM:
        raise ParameterError("sim", text[:12] + "…", f"at most {MAX_URL_SIM} characters")
    kind, sep, rest = text.partition(":")
    if not sep or kind not in KINDS:
        raise ParameterError("sim", text, FORM, f"the kind is one of {', '.join(KINDS)}")
    names = ("L", "t_end", "guard", "probes", *DATA[kind])
    out: dict = {"kind": kind, "probes": ()}
    for item in filter(None, rest.split(",")):
        name, eq, value = item.partition("=")
        name = name.strip()
        if not eq or name not in names or name in out and name != "probes":
            raise ParameterError("sim", item, f"one each of {', '.join(names)}")
        value = value.strip()
        if name == "L":
            x = _float("L", value, *L_RANGE)
            if x != int(x):
                raise ParameterError("sim L", value, f"an integer in [{L_RANGE[0]}, {L_RANGE[1]}]")
            out["L"] = int(x)
        elif name == "t_end":
            out["t_end"] = _float("t_end", value, *T_RANGE)
        elif name == "guard":
            if value not in GUARDS:
                raise ParameterError("sim guard", value, " or ".join(GUARDS))
            out["guard"] = value
        elif name == "probes":
            sites = [s for s in value.split(";") if s.strip()]
            if len(sites) > MAX_SITES or not all(s.strip().isdigit() for s in sites):
                raise ParameterError("sim probes", value, f"at most {MAX_SITES} site numbers n;n;n")
            out["probes"] = tuple(int(s) for s in sites)
        else:
            out[name] = _float(name, value)
    missing = [n for n in names if n not in out]
    if missing:
        raise ParameterError("sim", text, FORM, "missing " + ", ".join(missing))
    return out
