"""Audit of the stability words against the numbers printed beside them (paper §6).

A physicist reading a verdict checks the word against its own evidence: "decays" over numbers
that fall, "comes and goes" over a ring where the excess is gone or dips, "unstable" over an
excess present on every ring and converged, "stable" over an excess within its error bar, "not
determined" with what would decide it, no fit whose error bar exceeds its value (or "± 0" from a
two-point line), no negative |…|, counts equal to the rows they count.  The rules here read the
*printed text* (the sentence, the headline, a CLI line, a CSV row, the explorer's status) and
re-derive each claim from the numbers printed in it; they never trust the record that wrote it.

    python -m benchmarks.verdict_audit FILE.csv|FILE.txt ...   # audit `fpu floquet sweep` output

Every problem is one line "surface: what is wrong"; no output means every word agrees.
The cheap cases run as tests (tests/floquet/test_verdict_audit.py); the paper's cases, timed:
benchmarks/verdict_acceptance.py; the paper comparisons: benchmarks/comparison_audit.py.
"""

from __future__ import annotations

import csv
import math
import re
import sys

CONVERGED = 0.10  # a converged mode changes by at most 10 % over the window (finite_size.py)
DIP = 0.5
DECAY_P = 0.5
TINY = 1e-9  # largest error bar of a real spectrum's point (measured ≤ 3e-10): "on the circle"

#: a printed number
NUM = r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
_PTS = re.compile(r"max\|mu\|-1 at N = ((?:\d+: " + NUM + r"(?:, )?)+)")
_FIT = re.compile(r"p = (" + NUM + r")\s*(?:\+/-|±)\s*(" + NUM + r")")
#: "|…| = −x": an absolute value printed negative
NEGATIVE_ABS = re.compile(r"\|[^|]{1,40}\|\s*=\s*[-−]")


def points(text: str) -> list[tuple[int, float]]:
    """The (N, max|mu|-1) pairs a sentence prints ("max|mu|-1 at N = 250: 7.60e-03, …")."""
    m = _PTS.search(text)
    if not m:
        return []
    out = []
    for item in m.group(1).split(", "):
        n, x = item.split(": ")
        out.append((int(n), float(x)))
    return out


def _first_word(text: str) -> str:
    return text.split(":")[0].split("(")[0].strip()


def audit_sentence(s: str, headline: str | None = None, classification: str | None = None,
                   tiny: float = TINY) -> list[str]:  # fmt: skip
    """Problems of one decision sentence (and its headline / class if printed beside it)."""
    bad: list[str] = []
    pts = points(s)
    N = [n for n, _ in pts]
    e = [x for _, x in pts]
    if NEGATIVE_ABS.search(s):
        bad.append(f"a negative absolute value: {NEGATIVE_ABS.search(s).group(0)!r}")
    for p, dp in _FIT.findall(s):
        if float(dp) >= abs(float(p)):
            bad.append(f"a fit whose error bar exceeds its value: p = {p} +/- {dp}")
        if float(dp) == 0.0:
            bad.append(f"a fit with a zero error bar (p = {p} +/- {dp})")
    m = re.search(r"leave the unit circle by (" + NUM + r") at N = (\d+)", s)
    if m and pts and (int(m.group(2)) != N[-1] or not _close(float(m.group(1)), e[-1])):
        bad.append(f"the excess at N ({m.group(0)}) is not the last printed point {pts[-1]}")
    if pts and N != sorted(N):
        bad.append(f"points not in order of N: {N}")
    word = _first_word(s)
    cls_of = {"stable": "stable", "finite-size artefact": "finite_size", "unstable": "unstable"}
    cls = cls_of.get(word, "undetermined" if word.startswith("not determined at N") else "?")
    if cls == "?":
        bad.append(f"sentence starts with no class: {s[:60]!r}")
    if classification is not None and classification != cls:
        bad.append(f"class {classification!r} beside a sentence saying {word!r}")
    if headline is not None:
        bad += _audit_headline(headline, cls, s, N, e, tiny)
    if cls == "stable":
        m = re.search(r"max\|mu\|-1 = (" + NUM + r") <= (" + NUM + r")", s)
        if not m or not float(m.group(1)) <= float(m.group(2)):
            bad.append(f"'stable' without an excess within its error bar: {s!r}")
    elif cls == "finite_size":
        bad += _audit_finite_size(s, N, e, tiny)
    elif cls == "unstable":
        if len(e) < 2 or min(e) <= tiny:
            bad.append(f"'unstable' without an excess on every ring: {pts}")
        elif (max(e) - min(e)) > CONVERGED * e[-1] * 1.01:
            bad.append(
                f"'unstable' over an excess that changes by "
                f"{100 * (max(e) - min(e)) / e[-1]:.0f} % (not converged): {pts}"
            )
        m = re.search(r"stays within (" + NUM + r") %", s)
        if m and e and not _pct_close(float(m.group(1)), (max(e) - min(e)) / e[-1]):
            bad.append(
                f"'stays within {m.group(1)} %' but the points spread "
                f"{100 * (max(e) - min(e)) / e[-1]:.2g} %"
            )
    elif cls == "undetermined":
        if not re.search(r"compute at N >= \d+|run the finite-size test", s):
            bad.append(f"'not determined' without what would decide it: {s!r}")
        m = re.search(r"changes by (" + NUM + r") %", s)
        if m and e and not _pct_close(float(m.group(1)), (max(e) - min(e)) / e[-1]):
            bad.append(
                f"'changes by {m.group(1)} %' but the points spread "
                f"{100 * (max(e) - min(e)) / e[-1]:.2g} %"
            )
        if m and float(m.group(1)) <= 100 * CONVERGED:
            bad.append(f"'neither converged' over a spread of {m.group(1)} %")
        if "nor decays" in s and "nor decays like" not in s and e and e[-1] < max(e):
            bad.append(
                f"'nor decays' over points that fall {100 * (1 - e[-1] / max(e)):.0f} % "
                f"from their largest value: {pts}"
            )
        m = re.search(r"it falls (" + NUM + r") % from its largest value at N = (\d+)", s)
        if m and e:
            k = N.index(int(m.group(2)))
            if e[k] != max(e) or not _pct_close(float(m.group(1)), 1 - e[-1] / e[k]):
                bad.append(f"'{m.group(0)}' does not match the points {pts}")
        if re.search(r"N >= (\d+)", s):
            n_next = int(re.search(r"N >= (\d+)", s).group(1))
            n_here = int(re.search(r"not determined at N = (\d+)", s).group(1))
            if n_next <= n_here:
                bad.append(f"'compute at N >= {n_next}' is not beyond N = {n_here}")
    return bad


def _pct_close(printed: float, ratio: float) -> bool:
    """A printed percentage against a ratio of printed (3-digit) numbers."""
    return abs(printed - 100 * ratio) <= 0.6 + 0.02 * abs(100 * ratio)


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= 6e-3 * max(abs(a), abs(b)) + 1e-300


def _dips(e: list[float]) -> list[int]:
    return [k for k in range(1, len(e) - 1)
            if e[k] < DIP * min(max(e[:k]), max(e[k + 1 :]))]  # fmt: skip


def _audit_headline(h: str, cls: str, s: str, N, e, tiny) -> list[str]:
    bad = []
    words = {"stable": "stable", "finite_size": "finite-size artefact",
             "unstable": "unstable", "undetermined": "not determined at N ="}  # fmt: skip
    if cls in words and not h.startswith(words[cls]):
        bad.append(f"headline {h!r} beside a {cls!r} sentence")
    if "comes and goes" in h and not (any(x <= tiny for x in e) or _dips(e)):
        bad.append(
            f"'comes and goes' but no printed ring is within error or dips: {list(zip(N, e))}"
        )
    if ("decays" in h or "shrinks" in h) and not (e and e[-1] < max(e)):
        bad.append(f"'{h}' over numbers that do not fall: {list(zip(N, e))}")
    if "persists" in h and cls != "unstable":
        bad.append(f"'persists' in the headline of a {cls!r} sentence")
    m = re.search(r"not determined at N = (\d+)", h)
    if m and N and int(m.group(1)) != N[-1]:
        bad.append(f"headline N = {m.group(1)} but the points end at N = {N[-1]}")
    return bad


def _audit_finite_size(s: str, N, e, tiny) -> list[str]:
    bad = []
    if len(e) < 2:
        return [f"'finite-size artefact' with no window of rings printed: {s!r}"]
    if "within the error bar at N = " in s:
        gone = re.search(r"within the error bar at N = ([\d, ]+)", s).group(1)
        for n in (int(x) for x in gone.replace(" ", "").split(",") if x):
            if n not in N or e[N.index(n)] > tiny:
                bad.append(
                    f"'on the circle within the error bar at N = {n}' but it prints "
                    f"{e[N.index(n)] if n in N else 'no point'}"
                )
    if "half its neighbours at N = " in s:
        at = re.search(r"half its neighbours at N = ([\d, ]+)", s).group(1)
        for n in (int(x) for x in at.replace(" ", "").split(",") if x):
            k = N.index(n) if n in N else -1
            if k not in _dips(e):
                bad.append(
                    f"'falls to less than half its neighbours at N = {n}' is not true "
                    f"of {list(zip(N, e))}"
                )
        m = re.search(r"is below (" + NUM + r")", s)
        if m and not _close(float(m.group(1)), min(e)):
            bad.append(f"'below {m.group(1)}' is not the smallest printed excess {min(e):.2e}")
    if "decays as the ring grows" in s:
        if not e[-1] < max(e):
            bad.append(f"'decays' over numbers that do not fall: {list(zip(N, e))}")
        # the fall must be a trend of the window, not the last step after a rise: the largest
        # excess lies in the first half of the window (log N)
        k = max(i for i, x in enumerate(e) if _close(x, max(e)))  # where the fall starts
        if N[k] > math.sqrt(N[0] * N[-1]) * (1 + 1e-12):
            bad.append(
                f"'decays' but the excess rises up to N = {N[k]}, past the middle of the "
                f"window: {list(zip(N, e))}"
            )
        m = re.search(r"from (" + NUM + r") at N = (\d+) to (" + NUM + r") at N = (\d+), "
                      r"(" + NUM + r") % lower", s)  # fmt: skip
        if m is not None:
            a, na, b, nb, pc = m.groups()
            if not (_close(float(a), max(e)) and _close(float(b), e[-1]) and float(b) < float(a)):
                bad.append(f"fall '{m.group(0)}' is not from the largest to the last point")
            elif abs(float(pc) - 100 * (1 - e[-1] / max(e))) > 1.0:
                bad.append(f"'{pc} % lower' but the points fall {100 * (1 - e[-1] / max(e)):.0f} %")
        for p, _dp in _FIT.findall(s):
            if float(p) < DECAY_P:
                bad.append(f"'decays' with an envelope exponent p = {p} < {DECAY_P}")
    if not ("within the error bar at N" in s or "half its neighbours" in s
            or "decays as the ring grows" in s):  # fmt: skip
        bad.append(f"'finite-size artefact' without its evidence: {s!r}")
    return bad


def audit_decision(d) -> list[str]:
    """Problems of a :class:`fpucore.floquet.decision.Decision`: its texts against the
    numbers they print and against the record's own points and error bars."""
    bad = audit_sentence(d.sentence, d.headline, d.classification,
                         tiny=max(d.points_error, default=TINY))  # fmt: skip
    pts = points(d.sentence)
    if d.classification != "stable" and len(d.points_N) > 1:
        if [n for n, _ in pts] != list(d.points_N):
            bad.append(
                f"the sentence prints N = {[n for n, _ in pts]}, the record holds "
                f"{list(d.points_N)}"
            )
    e, err = list(d.points_excess), list(d.points_error)
    if d.classification == "stable" and not d.excess <= d.error:
        bad.append(f"'stable' with excess {d.excess:.3e} > error {d.error:.3e}")
    if d.classification == "unstable" and not all(x > s for x, s in zip(e, err, strict=True)):
        bad.append(f"'unstable' but the excess is within error on a ring: {list(d.points_N)}")
    if d.classification == "unstable" and d.missing_N:
        bad.append(f"'unstable' with rings missing from the window: {d.missing_N}")
    if d.classification == "undetermined" and not d.next_step:
        bad.append("'undetermined' without a next step")
    return bad


def audit_result(fr) -> list[str]:
    """Problems of a :class:`fpucore.floquet.FloquetResult`: the decision, and the result's own
    fields and counts against it."""
    d = fr.decision
    bad = audit_decision(d)
    if fr.verdict != d.sentence or fr.classification != d.classification:
        bad.append("verdict/classification differ from the decision record")
    if fr.classification == "stable" and fr.n_unstable:
        bad.append(f"'stable' but {fr.n_unstable} multipliers beyond error")
    if fr.classification != "stable" and fr.n_unstable == 0:
        bad.append(f"{fr.classification!r} with an excess beyond error but no multiplier counted")
    if bool(fr.excess_significant) != (fr.classification != "stable"):
        bad.append("excess_significant disagrees with the class")
    return bad


def audit_cli_text(text: str) -> list[str]:
    """Problems of `fpu floquet superkink|solitary` text output."""
    bad = []
    cls = re.search(r"classification\s+: (\w+) - (.+) \((\d+) multipliers? beyond error\)", text)
    ver = re.search(r"verdict\s+: (.+)", text)
    if not cls or not ver:
        return [f"cli: no classification/verdict line in {text[:200]!r}"]
    c, h, k = cls.group(1), cls.group(2), int(cls.group(3))
    bad += [f"cli: {b}" for b in audit_sentence(ver.group(1), h, c)]
    if (c == "stable") != (k == 0):
        bad.append(f"cli: class {c!r} beside {k} multipliers beyond error")
    if k == 1 and "1 multipliers" in text:
        bad.append("cli: '1 multipliers'")
    win = re.search(r"finite-size window\s+: max\|mu\|-1 at (.+) \(", text)
    if win:
        shown = [(int(a), float(b)) for a, b in re.findall(r"N=(\d+): (" + NUM + r")", win[1])]
        said = points(ver.group(1))
        if [n for n, _ in shown] != [n for n, _ in said] or not all(
            _close(a, b) or max(a, b) <= TINY for (_, a), (_, b) in zip(shown, said, strict=True)
        ):
            bad.append(f"cli: the window line {shown} differs from the verdict's points {said}")
    return bad


def audit_sweep_rows(rows: list[dict], where: str = "sweep") -> list[str]:
    """Problems of sweep rows (CSV / JSON / SweepResult.rows): each row's words against its
    numbers."""
    bad = []
    for r in rows:
        v = r.get("verdict") or ""
        if v in ("", "not computed") and r.get("status") != "ok":  # no spectrum at this V
            continue
        c, h = r.get("classification") or None, r.get("headline") or None
        tag = f"{where} V={float(r['V']):.6g}"
        bad += [f"{tag}: {b}" for b in audit_sentence(v, h, c)]
        ma = r.get("max_modulus_away_from_1")
        pts = points(v)
        if (
            ma not in (None, "")
            and pts
            and not (
                _close(float(ma) - 1.0, pts[-1][1]) or max(float(ma) - 1.0, pts[-1][1]) <= TINY
            )
        ):
            bad.append(
                f"{tag}: max|mu|-1 column {float(ma) - 1:.3e} but the verdict says {pts[-1][1]:.3e}"
            )
        k = r.get("n_unstable")
        if k not in (None, "") and c and (c == "stable") != (int(k) == 0):
            bad.append(f"{tag}: class {c!r} beside {k} multipliers beyond error")
    return bad


def audit_csv(path: str) -> list[str]:
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    return audit_sweep_rows(rows, path)


def audit_sweep_text(text: str, where: str = "sweep text") -> list[str]:
    """Problems of `fpu floquet sweep` text: each row's class beside its headline and count,
    and the energy line's count of changes against the rows above it."""
    bad = []
    rows: list[tuple[int, float, str, int]] = []
    for line in text.splitlines():
        m = re.match(r"\s*(\d+)\s+(" + NUM + r")\s+\S+\s+\S+\s+\S+\s+(\d+)\s+(\S+)\s+(.*)$",
                     line)  # fmt: skip
        if m and m.group(4) in ("stable", "finite_size", "unstable", "undetermined"):
            n, V, k, c, h = int(m[1]), float(m[2]), int(m[3]), m[4], m[5]
            h = h.replace(" (cached)", "")
            rows.append((n, V, c, k))
            if (c == "stable") != (k == 0):
                bad.append(f"{where} N={n} V={V:g}: class {c!r} beside {k} beyond error")
            if not h.startswith({"stable": "stable", "finite_size": "finite-size artefact",
                                 "unstable": "unstable",
                                 "undetermined": "not determined"}[c]):  # fmt: skip
                bad.append(f"{where} N={n} V={V:g}: class {c!r} beside headline {h!r}")
        m = re.match(r"\s*(\d+) energy criterion: (.*)$", line)
        if m:
            n = int(m[1])
            sel = [(V, c) for (nn, V, c, _) in rows if nn == n]
            said = re.match(r"(\d+) changes? of class", m[2])
            k = int(said[1]) if said else 0
            if not said and not m[2].startswith(("No change", "not evaluated")):
                bad.append(f"{where}: energy line not understood: {m[2]!r}")
            upper = _changes(sel)
            if k > upper:
                bad.append(
                    f"{where} N={n}: energy line counts {k} changes, the rows show at most {upper}"
                )
    return bad


def _changes(sel) -> int:
    """Changes across the stable/unstable line between neighbouring classified velocities
    (an upper bound when the rows hold two intervals: the boundary pair may count once)."""
    c = [x for _, x in sorted(sel) if x != "undetermined"]
    return sum((a == "unstable") != (b == "unstable") for a, b in zip(c, c[1:], strict=False))


def main(argv: list[str]) -> int:
    bad = []
    for path in argv:
        if path.endswith(".csv"):
            bad += audit_csv(path)
        else:
            with open(path) as fh:
                bad += audit_sweep_text(fh.read(), path)
    for b in bad:
        print(b)
    print(f"{len(bad)} problems in {len(argv)} files", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
