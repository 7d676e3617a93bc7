"""Run every speed benchmark (``make bench``): each ``benchmarks/bench_*.py`` in its own process,
one after another (2 cores: running them side by side would measure contention, not code)."""

from __future__ import annotations

import pathlib
import subprocess
import sys


def main(argv: list[str] | None = None) -> int:
    names = sorted(p.stem for p in pathlib.Path(__file__).parent.glob("bench_*.py"))
    wanted = set(argv or sys.argv[1:])
    rc = 0
    for name in names:
        if wanted and name not in wanted:
            continue
        print(f"\n=== {name} ===", flush=True)
        rc |= subprocess.call([sys.executable, "-m", f"benchmarks.{name}"])
    return rc


if __name__ == "__main__":
    raise SystemExit(main())
