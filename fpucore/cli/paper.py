"""``fpu paper``: the paper's figures, computed and compared with the printed numbers.

    fpu paper --list                                   # the 17 figures by LaTeX label
    fpu paper --figure pplane --out pplane.html        # one figure with its comparison rows
    fpu paper --figure pplane --out pplane.svg         # the figure alone (.svg or .png)
    fpu paper --figure pplane --out pplane.ipynb       # its notebook (runs top to bottom)
    fpu paper --out report.html                        # all figures + comparison table, offline
    fpu paper --table docs/paper_comparison.md         # the comparison table (Markdown + .json)
    fpu paper --thumbnails app/assets/figures          # <label>.png, 400 px wide, per figure
    fpu paper --family trilinear --list                # the trilinear family's figures
    fpu paper --family trilinear --figure tri_compact --out tri_compact.html

The explorer's committed copies (package data of the explorer, read by its Paper tab):
    fpu paper --table docs/paper_comparison.md --table-json app/assets/paper_comparison.json \
              --thumbnails app/assets/figures

``--reduced`` lowers grid sizes and the number of velocities (never the paper's N, L, t of a
compared number); computed figures are cached (``$FPU_CACHE_DIR/paper``) and reused.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import fpucore
from fpucore.cli.common import check_out_dir, check_out_path, output_file, print_json
from fpucore.errors import ParameterError


def register(sub) -> None:
    p = sub.add_parser("paper", help="the paper's figures: compute, compare, export")
    p.add_argument("--list", action="store_true", help="list the figures and exit")
    p.add_argument(
        "--family",
        default="paper",
        help="paper (the paper's figures, default) or trilinear (the soft-hard-soft "
        "piecewise-linear family's figures)",
    )
    p.add_argument(
        "--figure",
        action="append",
        default=None,
        metavar="LABEL",
        help="a figure's LaTeX label (repeatable; default: all)",
    )
    p.add_argument(
        "--out", default=None, help="one figure: .html/.svg/.png; several or all: the HTML report"
    )
    p.add_argument(
        "--table",
        default=None,
        metavar="FILE.md",
        help="write the comparison table (Markdown, and .json beside it)",
    )
    p.add_argument(
        "--table-json",
        default=None,
        metavar="FILE.json",
        help="where --table writes its JSON (default: beside the .md)",
    )
    p.add_argument(
        "--thumbnails",
        default=None,
        metavar="DIR",
        help="write each figure's thumbnail DIR/<label>.png (400 px wide)",
    )
    p.add_argument("--reduced", action="store_true", help="smaller grids / fewer velocities")
    p.add_argument("--no-cache", action="store_true", help="recompute cached figures")
    p.add_argument("--workers", type=int, default=None, help="processes (default: all cores)")
    p.add_argument(
        "--time-budget",
        type=float,
        default=3600.0,
        metavar="S",
        help="stop starting figures after S seconds (default 3600)",
    )
    p.add_argument("--json", action="store_true", help="print the comparisons as JSON")
    p.set_defaults(func=run)


def _check(args) -> list[str]:
    from fpucore.paper import plot  # heavy: Numba
    from fpucore.paper.report import family  # heavy: Numba

    reg = family(args.family)
    formats = (*plot.FORMATS, ".ipynb")
    labels = list(reg.LABELS) if not args.figure else [reg.figure(lab).label for lab in args.figure]
    if args.family != "paper" and args.out is not None and args.out.lower().endswith(".ipynb"):
        why = f"notebooks hold the paper's figures, not --family {args.family}"
        raise ParameterError("--out", args.out, "an .html, .svg or .png file", why)
    if args.family != "paper" and (args.table is not None or args.thumbnails is not None):
        why = "the table and thumbnails are the paper's (the explorer's copies)"
        raise ParameterError("--family", args.family, "paper with --table or --thumbnails", why)
    if args.out is not None and Path(args.out).suffix.lower() not in formats:
        raise ParameterError("--out", args.out, "a file ending in " + ", ".join(formats))
    if args.out is not None and args.out.lower().endswith(".ipynb") and len(labels) != 1:
        raise ParameterError("--out", args.out, "one --figure", "a notebook holds one figure")
    if args.out is not None and len(labels) > 1 and not args.out.lower().endswith(".html"):
        raise ParameterError("--out", args.out, "an .html file", "several figures make a report")
    if args.table is not None:
        check_out_path(args.table, "--table")
        if not args.table.lower().endswith(".md"):
            raise ParameterError("--table", args.table, "a Markdown file (.md)")
    if args.table_json is not None:
        if args.table is None:
            raise ParameterError("--table-json", args.table_json, "a .json file with --table")
        check_out_path(args.table_json, "--table-json")
        if not args.table_json.lower().endswith(".json"):
            raise ParameterError("--table-json", args.table_json, "a JSON file (.json)")
    if args.thumbnails is not None:
        check_out_dir(args.thumbnails, "--thumbnails")
    if args.workers is not None and not 1 <= args.workers <= 4096:
        raise ParameterError("--workers", args.workers, "[1, 4096]")
    return labels


def run(args) -> int:
    from tqdm import tqdm  # heavy: tqdm

    from fpucore.paper import notebook, plot  # heavy: Numba
    from fpucore.paper.report import compute_many, family  # heavy: Numba

    reg = family(args.family)
    FIGURES, LABELS = reg.FIGURES, reg.LABELS
    if args.list:
        if args.json:
            rows = [
                {
                    "label": lab,
                    "number": FIGURES[lab].number,
                    "section": FIGURES[lab].section,
                    "caption": FIGURES[lab].caption,
                }
                for lab in LABELS
            ]
            print_json({"figures": rows})
            return 0
        for lab in LABELS:
            f = FIGURES[lab]
            print(f"{f.number:2d}  {lab:22s} {f.section:5s} {f.caption[:70]}…")
        return 0
    labels = _check(args)
    # with --json, stdout carries the JSON alone (`fpu paper --json | jq`): lines for people go to
    # stderr
    people = sys.stderr if args.json else sys.stdout
    if args.out is not None and args.out.lower().endswith(".ipynb"):
        with output_file(args.out) as tmp:
            notebook.write(labels[0], tmp, reduced=args.reduced)  # computed when it runs
        print(f"wrote {args.out}", file=people)
        return 0
    if args.out is None and args.table is None and args.thumbnails is None and not args.json:
        raise ParameterError(
            "--out", None, "--out FILE, --table FILE.md, --thumbnails DIR, --json or --list"
        )
    bar = tqdm(total=len(labels), desc="fpu paper", unit="fig", file=sys.stderr, leave=False)

    def progress(done: int, total: int, label: str) -> None:
        bar.n = done
        bar.set_postfix_str(label)
        bar.refresh()

    results, missing, wall = compute_many(
        labels,
        reduced=args.reduced,
        use_cache=not args.no_cache,
        workers=args.workers,
        time_budget_s=args.time_budget,
        progress=progress,
        family_name=args.family,
    )
    bar.close()
    n = sum(len(r.comparisons) for r in results)
    ok = sum(r.n_agree for r in results)
    what = "printed numbers" if args.family == "paper" else "rows (closed forms, second methods)"
    summary = f"{len(results)}/{len(labels)} figures, {ok} of {n} {what} agree, {wall:.1f} s"
    # every file atomically (fpucore/cli/common.py: output_file): a full disk leaves no partial
    # file; the computed figures stay in the cache, so a rerun only writes
    kept = "the computed figures are cached: rerun to write" if not args.no_cache else ""
    if args.out is not None:
        with output_file(args.out, "--out", kept) as tmp:
            if len(labels) == 1 and results and not args.out.lower().endswith(".html"):
                plot.save(results[0], tmp)  # .svg / .png: the figure alone
            else:  # HTML: the figure(s) with caption, notes and the comparison table
                title = (
                    f"Fig. {FIGURES[labels[0]].number} ({labels[0]}) — fpu-explorer"
                    if len(labels) == 1
                    else "The paper, figure by figure — fpu-explorer"
                    if args.family == "paper"
                    else "The trilinear family, figure by figure — fpu-explorer"
                )
                plot.report_html(results, FIGURES, tmp, title, summary)
        print(f"wrote {args.out}", file=people)
    if args.table is not None:
        json_path = Path(args.table_json or Path(args.table).with_suffix(".json"))
        doc = _table_doc(results, missing, args.reduced, args.thumbnails, args.table_json)
        with output_file(args.table, "--table", kept) as tmp:
            Path(tmp).write_text(doc, encoding="utf-8")
        with output_file(json_path, "--table", kept + f" ({args.table} was written)") as tmp:
            Path(tmp).write_text(table_json(results, missing, args.reduced), encoding="utf-8")
        print(f"wrote {args.table} and {json_path}", file=people)
    if args.thumbnails is not None:
        for k, r in enumerate(results):
            target = Path(args.thumbnails) / f"{r.label}.png"
            with output_file(
                target,
                "--thumbnails",
                f"{k} of {len(results)} thumbnails were written before this one",
            ) as tmp:
                plot.thumbnail(r, tmp)
        print(f"wrote {len(results)} thumbnails in {args.thumbnails}", file=people)
    if args.json:
        print_json(
            {"figures": [r.as_dict() for r in results], "missing": missing, "elapsed_s": wall}
        )
    print(summary, file=people)
    for m in missing:
        print(f"not computed: {m}", file=sys.stderr)
    return 0


def _table_doc(
    results, missing, reduced: bool, thumbnails: str | None = None, table_json: str | None = None
) -> str:
    from fpucore.paper.report import markdown_table  # heavy: Numba

    head = (
        "# The paper vs fpu-explorer, number by number\n\n"
        "Generated by `fpu paper --table docs/paper_comparison.md"
        f"{' --reduced' if reduced else ''}"
        f"{f' --table-json {Path(table_json).as_posix()}' if table_json else ''}"
        f"{f' --thumbnails {Path(thumbnails).as_posix()}' if thumbnails else ''}` (do not edit by"
        f" hand; the same numbers in {Path(table_json or 'paper_comparison.json').name})."
        "  Each row: a number the paper"
        " (Vainchtein & Truskinovsky) prints, our value, our error bar, and the verdict — a value"
        " agrees when |ours − paper| ≤ error + half a unit of the paper's last printed digit; a"
        " bound holds when ours ± error is on its side (fpucore/paper/compare.py).  a = −1,"
        " b = 10 throughout.\n\n"
    )
    return head + markdown_table(results, missing)


def table_json(results, missing, reduced: bool) -> str:
    """The comparison table as JSON (the explorer's Paper tab reads it when no ``fpu paper`` run
    is cached): the fpucore version and per figure its comparisons, the same numbers as the
    Markdown table."""
    from fpucore.result import jsonable  # heavy: NumPy

    doc = {
        "generated_by": "fpu paper --table" + (" --reduced" if reduced else ""),
        "fpucore_version": fpucore.__version__,
        "figures": {
            r.label: {
                "reduced": r.reduced,
                "elapsed_s": r.elapsed_s,
                "comparisons": [
                    {
                        k: getattr(c, k)
                        for k in (
                            "quantity",
                            "printed",
                            "paper",
                            "ours",
                            "error",
                            "kind",
                            "agrees",
                            "why",
                            "elapsed_s",
                        )
                    }
                    for c in r.comparisons
                ],
            }
            for r in results
        },
        "missing": list(missing),
    }
    return json.dumps(jsonable(doc), indent=1, ensure_ascii=False) + "\n"
