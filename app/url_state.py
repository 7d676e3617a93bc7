"""The explorer's state in a link: each URL value parsed and checked like any input (an invalid
value is named with its valid range, the rest kept), held curves (``hold=``), paper figures
(``fig=``), atlas stores (only below :func:`app.data_dir.atlas_root`, the server's data
directory), and the URL query of a state.

Separate from :mod:`app.state` (the state owner itself), which it reads and never changes
except through the state's own parameters.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from fpucore import qc
from fpucore.errors import ParameterError

from . import compute, paper_figures
from .data_dir import DATA_DIR_NAME, atlas_root, hide_server_paths
from .scene_registry import TABS
from .sim_url import MAX_URL_SIM, format_sim, parse_sim, sc_inputs
from .state import (
    A_RANGE,
    B_RANGE,
    FIGURE_PARAMS,
    MAX_HELD,
    MAX_URL_HOLD,
    MAX_URL_LAW,
    MAX_URL_VALUE,
    MODES,
    N_RANGE,
    STATE_PARAMS,
    TOL_OPTIONS,
    URL_ATTRS,
    URL_LAW_WAIT_S,
    URL_PARAMS,
    ExplorerState,
    HeldWave,
)


# ---------------------------------------------------------------------- URL values
def _float(name: str, raw: str, valid: str, lo: float | None = None, hi: float | None = None):
    try:
        x = float(raw)
    except ValueError:
        raise ParameterError(name, raw, valid, "not a number") from None
    if not math.isfinite(x):  # the text as typed: "1e400", not the "inf" it rounds to
        raise ParameterError(name, raw.strip(), valid, "not a finite double (beyond ±1.8e308)")
    if lo is not None and not lo <= x <= hi:
        raise ParameterError(name, x, valid)
    return x


def resolve_atlas_store(name: str, raw: str) -> Path:
    """The store ``raw`` (relative to :func:`atlas_root`, or absolute below it) as an absolute
    path; ParameterError naming ``name`` for a path that leaves the root."""
    root = atlas_root()
    text = raw.strip()
    valid = f"a path below {DATA_DIR_NAME}"  # never the server's absolute path
    if len(text) > MAX_URL_LAW:  # also typed in the box (a URL value is cut before)
        raise ParameterError(name, text[:12] + "…", valid, f"longer than {MAX_URL_LAW} characters")
    try:  # a NUL byte, "~nosuchuser", a name past the file system's limit: refused, not raised
        path = (root / Path(text).expanduser()).resolve()
        path.is_dir()
    except (OSError, ValueError, RuntimeError) as exc:
        why = f"{type(exc).__name__}: {hide_server_paths(exc)}"  # OSError: it names the path
        raise ParameterError(name, raw, valid, why) from None
    if not text or not path.is_relative_to(root):
        raise ParameterError(name, raw, valid, "stores are read only there")
    return path


def parse_url_value(name: str, raw: str):
    """One URL query value → the state's value (raises ParameterError naming the value and
    the valid range; the same ranges the sliders have)."""
    limits = {"law": MAX_URL_LAW, "atlas": MAX_URL_LAW, "hold": MAX_URL_HOLD, "sim": MAX_URL_SIM}
    limit = limits.get(name, MAX_URL_VALUE)
    if len(raw) > limit:
        raise ParameterError(name, raw[:12] + "…", f"at most {limit} characters")
    if name == "law":
        text = raw.strip()
        if not text or text == "cubic":
            return ""  # the cubic (a, b)
        # built in the law worker; a page build (on the server's event loop) waits for it at
        # most URL_LAW_WAIT_S — a law still being built then is kept, and the explorer
        # re-renders (or names it in the URL message) once its outcome is known
        fut = compute.laws.request_law(text)
        try:
            outcome = fut.result(timeout=URL_LAW_WAIT_S)
        except TimeoutError:
            return text
        if isinstance(outcome, ParameterError):  # fpucore names it "expression"; the URL: law
            raise ParameterError(name, outcome.value, outcome.valid, outcome.reason)
        return text
    if name == "a":
        return _float(name, raw, f"[{A_RANGE[0]:g}, {A_RANGE[1]:g}]", *A_RANGE)
    if name == "b":
        return _float(name, raw, f"[{B_RANGE[0]:g}, {B_RANGE[1]:g}]", *B_RANGE)
    if name in ("w_plus", "V"):
        return _float(name, raw, "a finite number")
    if name == "mode":
        if raw not in MODES:
            raise ParameterError(name, raw, " or ".join(MODES))
        return raw
    if name == "tab":
        if raw not in TABS:
            raise ParameterError(name, raw, ", ".join(TABS))
        return raw
    if name == "N":
        valid = f"an even integer in [{N_RANGE[0]}, {N_RANGE[1]}]"
        try:
            N = int(raw.strip())
        except ValueError:
            raise ParameterError(name, raw, valid, "not an integer") from None
        if N % 2 or not N_RANGE[0] <= N <= N_RANGE[1]:
            raise ParameterError(name, N, valid)
        return N
    if name == "atlas":
        resolve_atlas_store(name, raw)
        return raw.strip()
    if name == "hold":  # its entries are read against the law and w₊: parse_hold
        return raw.strip()
    if name == "fig":
        if raw not in paper_figures.FIGURE_STATE:
            raise ParameterError(name, raw, "one of " + ", ".join(paper_figures.FIGURE_STATE))
        return raw
    if name == "sim":  # the canonical form of the Simulation scene's inputs
        return format_sim(**parse_sim(raw))
    if name == "run":
        if raw.strip() not in ("0", "1"):
            raise ParameterError(name, raw, "1 (the simulation was on screen) or 0")
        return raw.strip() == "1"
    if name == "tol":
        x = _float(name, raw, "one of " + ", ".join(f"{t:g}" for t in TOL_OPTIONS))
        for t in TOL_OPTIONS:
            if abs(x - t) <= 1e-9 * t:
                return t
        raise ParameterError(name, x, "one of " + ", ".join(f"{t:g}" for t in TOL_OPTIONS))
    raise ParameterError(name, raw, "one of " + ", ".join(URL_PARAMS))


HOLD_FORMS = "V, V@w_plus or sk@w_plus"
_HOLD_ENTRY = re.compile(r"^\s*(?:(sk)|([^@\s]+))\s*(?:@\s*([^@\s]+))?\s*$")


def parse_hold(text: str, law, w_plus: float) -> tuple[list[HeldWave], list[str]]:
    """A link's ``hold`` (comma-separated ``V`` — a solitary wave at the state's w₊ —, ``V@w₊``
    or ``sk@w₊`` — a superkink) → (the held waves, one message per entry refused).  Each wave
    must exist for the law (``law`` None: an invalid law, whose message the page shows; the
    entries are kept unchecked); more than MAX_HELD: the oldest (first) go, named."""
    held, errors = [], []
    entries = [e for e in text.split(",") if e.strip()]
    for entry in entries:
        m = _HOLD_ENTRY.match(entry)
        try:
            if m is None or (m.group(1) and m.group(3) is None):
                raise ParameterError("hold", entry.strip(), HOLD_FORMS)
            w = w_plus if m.group(3) is None else _float("hold", m.group(3), "a finite w₊")
            if m.group(1):
                wave = HeldWave("superkink", w)
                if law is not None:
                    _check_held(law, wave)
            else:
                V = _float("hold", m.group(2), "a finite V")
                wave = HeldWave("solitary", w, V)
                if law is not None:
                    _check_held(law, wave)
        except ParameterError as exc:
            errors.append(f"URL value ignored: {exc}")
            continue
        if wave not in held:
            held.append(wave)
    if len(held) > MAX_HELD:
        gone = ", ".join(h.url(w_plus) for h in held[:-MAX_HELD])
        errors.append(
            f"URL value ignored: hold has {len(held)} curves, at most {MAX_HELD} are held: "
            f"the first {len(held) - MAX_HELD} ({gone}) let go"
        )
        held = held[-MAX_HELD:]
    return held, errors


def _check_held(law, wave: HeldWave) -> None:
    """ParameterError (named ``hold``, with the valid range) if ``wave`` is no wave of ``law``."""
    try:
        if wave.mode == "superkink":
            qc.superkink_from_w_plus(law, wave.w_plus)
            return
        cp, vsk, cm = qc.sound_speeds(law, wave.w_plus)
        if wave.V == vsk:
            raise ParameterError(
                "V",
                wave.V,
                f"({cp:.10g}, {vsk:.10g}) or ({vsk:.10g}, {cm:.10g})",
                "V = V_SK is the superkink: sk@w_plus holds it",
            )
        qc.solitary(law, wave.w_plus, wave.V)
    except ParameterError as exc:
        why = f"the held wave's {exc.name}" + (f": {exc.reason}" if exc.reason else "")
        raise ParameterError("hold", exc.value, exc.valid, why) from None


def format_hold(state) -> str:
    """The URL's ``hold`` of the state's held curves (see :func:`parse_hold`)."""
    return ",".join(h.url(state.w_plus) for h in state.held)


def parse_url(query: dict[str, str]) -> tuple[dict, list[str]]:
    """(valid values, one message per invalid value) of a URL query; unknown names are
    ignored, every valid value is kept even when another one is invalid."""
    values, errors = {}, []
    for name in URL_PARAMS:
        if name not in query:
            continue
        try:
            values[URL_ATTRS.get(name, name)] = parse_url_value(name, str(query[name]))
        except ParameterError as exc:
            errors.append(f"URL value ignored: {exc}")
    return values, errors


def state_from_url(query: dict[str, str]) -> tuple[ExplorerState, list[str]]:
    """The state a link describes, and one message per value it could not take.

    Beyond :func:`parse_url`'s per-value checks, the values must fit together: a w_plus outside
    the law's range of w₊ is refused (the slider could not show it) and the law's default kept;
    in superkink mode V and w₊ are tied (V = V_SK(w₊)), so a link that gives V alone sets w₊
    from it (as typing V does), and one that gives both, inconsistently, keeps w₊ and says so.
    """
    values, errors = parse_url(query)
    hold = values.pop("held", None)
    fig = values.pop("figure", "")
    sim, run = values.pop("simulation", ""), values.pop("sim_shown", False)
    figure = figure_state(fig) if fig else None
    if figure is not None:  # the figure's state first; the link's own values (checked) win
        base = {"a": -1.0, "b": 10.0, "expression": ""}
        base.update({n: getattr(figure, n) for n in ("mode", "tab", "N", "tol", "w_plus")})
        if figure.mode == "solitary":
            base["V"] = figure.V
        values = base | values
    st = ExplorerState(**{k: v for k, v in values.items() if k not in ("w_plus", "V")})
    try:
        lo, w_star, hi = st.w_plus_range()
    except ParameterError:  # an invalid law: the page explains it
        lo = w_star = hi = None
    w = values.get("w_plus")
    if w is not None and lo is not None and not (lo < w < hi and w != w_star):
        errors.append(
            "URL value ignored: "
            + str(ParameterError("w_plus", w, f"({lo:.10g}, {hi:.10g}) without w* = {w_star:.10g}"))
        )
        w = None
    V = values.get("V")
    if st.mode == "superkink" and w is not None and V is not None:
        vsk = qc.sound_speeds(st.law(), w)[1] if lo is not None else None
        if vsk is not None and abs(V - vsk) > 1e-9 * vsk:
            errors.append(
                f"URL value ignored: V = {V!r} (in superkink mode V = V_SK(w_plus) = {vsk:.10g} "
                f"for w_plus = {w!r})"
            )
            V = None
    if w is not None:
        st.w_plus = w
    if V is not None:
        st.V = V  # in superkink mode this moves w₊ along its branch (ExplorerState._tie)
    if hold is not None:
        try:
            law = st.law()
        except ParameterError:
            law = None  # an invalid law (or one still being built): the page names it
        st.held, more = parse_hold(hold, law, st.w_plus)
        errors += more
    elif figure is not None:
        st.held = list(figure.held)
    if figure is not None:
        # the figure's simulation; the figure itself only while the state is the figure's
        st.scenario = figure.scenario
        st.simulation = figure.simulation
        same = [getattr(st, n) == getattr(figure, n) for n in FIGURE_PARAMS]
        st.figure = fig if all(same) else ""
    if sim:  # the link's simulation (run again if it was on screen); not the figure's: no fig
        inputs = parse_sim(sim)
        keep = figure is not None and inputs == sc_inputs(figure.scenario or {})
        st.simulation, st.sim_shown = sim, run
        if keep:
            st.scenario = inputs | {"run": run or figure.scenario["run"]}
        else:
            st.figure = ""
            st.scenario = inputs | {"run": run}
    return st, errors


def figure_state(label: str) -> ExplorerState:
    """The state paper figure ``label`` sets (app.paper_figures), from the default state."""
    st = ExplorerState()
    st.show_figure(label)
    return st


def url_value(x) -> str:
    """The URL form of a state value (floats exact: repr)."""
    return repr(x) if isinstance(x, float) else str(x)


def url_query(state: ExplorerState) -> dict[str, str]:
    """The URL query of the state, {URL name: value} in URL_PARAMS order; ``law`` only when it
    is an expression (a cubic link stays as it was: a, b); ``hold`` and ``fig`` when set."""
    out = {}
    for name, attr in zip(URL_PARAMS, STATE_PARAMS):
        value = getattr(state, attr)
        if name in ("law", "atlas", "hold", "fig", "sim", "run") and not value:
            continue
        if name == "run":
            if state.simulation:  # the simulation's run was on screen
                out[name] = "1"
            continue
        out[name] = format_hold(state) if name == "hold" else url_value(value)
    return out
