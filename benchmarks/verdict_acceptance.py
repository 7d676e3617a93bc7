"""The paper's stability cases (a = −1, b = 10; §6) and other laws as `fpu floquet sweep` runs,
timed, with every word of their text and CSV audited (:mod:`benchmarks.verdict_audit`) and the
class counts per case and N printed (docs/stability_verdicts.md is written from them).

    python -m benchmarks.verdict_acceptance [OUTDIR]   # default benchmarks/out/verdicts; slow
"""

from __future__ import annotations

import csv
import os
import subprocess
import sys
import time

from benchmarks.verdict_audit import audit_csv, audit_sweep_text

# the paper's cases (a = −1, b = 10; §6) and other laws, as `fpu floquet sweep` arguments
_SW1 = (
    "4.3134030504 4.4549277768 4.5964525033 4.7379772298 4.8795019562 5.0210266827 "
    "5.1625514092 5.3040761356 5.3826610927 5.3983062803 5.413951468 5.4295966556 "
    "5.4452418433 5.4608870309 5.4765322185 5.4921774062"
)  # 8 + 8 midpoints, w₊ = 1
_SW6 = (
    "3.7062975675 3.9077901515 4.1092827355 4.3107753195 4.5122679035 4.7137604875 "
    "4.9152530715 5.1167456555 5.2279715012 5.2489306087 5.2698897161 5.2908488236 "
    "5.311807931 5.3327670385 5.353726146 5.3746852534"
)  # 8 + 8 midpoints, w₊ = 6
_QUARTIC = ["--law", "w + 10*w**2 - w**3 - 0.01*w**4"]
ACCEPTANCE = {
    "sk200_500": "superkink --V-min 4.8 --V-max 5.85 --n 22 --N 200 500".split(),
    "sw1_500": f"solitary --w-plus 1 --V {_SW1} --N 500".split(),
    "sw6_500": f"solitary --w-plus 6 --V {_SW6} --N 500".split(),
    "ft6": "solitary --w-plus 6 --V 5.21749194749 5.2174919476 --N 200 500".split(),
    "c16_sk": "superkink --a -1 --b 6 --V-min 2.95 --V-max 3.6 --n 8 --N 200".split(),
    "c16_sw": "solitary --a -1 --b 6 --w-plus 1 --V 3.2 3.3 3.4 3.46 3.47 3.48 3.49 --N 200"
    .split(),
    "c210_sk": "superkink --a -2 --b 10 --V-min 3.44 --V-max 4.2 --n 8 --N 200".split(),
    "c210_sw": "solitary --a -2 --b 10 --w-plus 1 --V 3.9 4.0 4.09 4.1 4.11 4.12 --N 200"
    .split(),
    "q_sk": ["superkink", *_QUARTIC, *"--V-min 4.71 --V-max 5.74 --n 8 --N 200".split()],
    "q_sw": ["solitary", *_QUARTIC, *"--w-plus 1 --V 4.4 4.8 5.2 5.28 5.3 5.35 5.4 --N 200"
                                     .split()],
}  # fmt: skip


def class_counts(path: str) -> dict:
    """{N: {class: count}} of a sweep CSV."""
    out: dict = {}
    with open(path) as fh:
        for r in csv.DictReader(fh):
            c = r["classification"] or "not computed"
            out.setdefault(int(r["N"]), {}).setdefault(c, 0)
            out[int(r["N"])][c] += 1
    return out


def acceptance(outdir: str) -> int:
    """Run every ACCEPTANCE sweep through the CLI (structured route, no cache), time it, audit
    its text and CSV, and print the class counts per case and N."""
    os.makedirs(outdir, exist_ok=True)
    bad = []
    for name, args in ACCEPTANCE.items():
        csv_path, txt_path = f"{outdir}/{name}.csv", f"{outdir}/{name}.txt"
        cmd = [sys.executable, "-m", "fpucore", "floquet", "sweep", *args, "--method",
               "structured", "--no-cache", "--no-progress", "--out", csv_path]  # fmt: skip
        t0 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, check=False)
        dt = time.perf_counter() - t0
        with open(txt_path, "w") as fh:
            fh.write(out.stdout)
        found = audit_csv(csv_path) + audit_sweep_text(out.stdout, txt_path)
        bad += found
        print(f"{name}: {dt:.1f} s wall, {class_counts(csv_path)}, {len(found)} problems",
              flush=True)  # fmt: skip
    for b in bad:
        print(b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(acceptance(sys.argv[1] if len(sys.argv) > 1 else "benchmarks/out/verdicts"))
