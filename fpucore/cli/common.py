"""Helpers shared by every ``fpu`` command: JSON output, the argument parser, law options."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import re
import stat
import sys
import tempfile
from typing import TYPE_CHECKING, cast

from fpucore.errors import ParameterError

if TYPE_CHECKING:
    from fpucore.law import HardeningSofteningLaw, PiecewiseLinearLaw, PolynomialLaw, SmoothLaw


def jsonable(obj):
    """:func:`fpucore.result.jsonable`, imported when a command prints (NumPy stays out of
    ``fpu --help``)."""
    from fpucore.result import jsonable as convert  # heavy: NumPy

    return convert(obj)


def print_json(obj) -> None:
    """Print one JSON object on stdout (NaN/inf become null, numpy types become Python)."""
    sys.stdout.write(json.dumps(jsonable(obj)) + "\n")


# argparse takes "-1" and "-0.5" as values but "-1e-2" or "-inf" as an unknown option ("expected
# one argument"): every negative number, in any notation float() reads, is a value here.
NEGATIVE_NUMBER = re.compile(
    r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE
)


#: argparse's message for a value its type could not convert ("argument --V: invalid float
#: value: 'abc'")
BAD_VALUE = re.compile(r"^argument (--?[\w-]+)(?:/--?[\w-]+)*: invalid (float|int) value: '(.*)'$")


class Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER  # argparse's hook for this decision

    def error(self, message):  # one line on stderr, exit 2 (argparse default prints usage too)
        # a value argparse could not convert: in the form of every other refusal (ParameterError:
        # the argument, its value and what it must be), not argparse's words
        m = BAD_VALUE.match(message)
        if m:
            name, kind, raw = m.group(1).lstrip("-"), m.group(2), m.group(3)
            valid = "a real number" if kind == "float" else "an integer"
            message = str(ParameterError(name, raw, valid, "not a number"))
        self.exit(2, f"fpu: error: {message}\n")


class OutputError(Exception):
    """An output that could not be written after the work was done (disk full, permission
    revoked, ...): the CLI prints its one-line message and exits 1.  The message says what was
    written and what was kept (a partial file is never left under the target's name)."""


# Special places no output belongs to: kernel interfaces take a write of "x.csv" as a command or
# refuse it only when the data arrive (``/proc``, ``/sys``), device files swallow it (/dev/null)
# or fail at the end (/dev/full: ENOSPC).
PSEUDO_FS = ("/proc", "/sys")


def _probe_dir(parent: str) -> str | None:
    """None if a file can be created (and removed) in ``parent``, else the reason: the one test
    that holds for root too (``os.access`` says yes on /proc and on a read-only mount)."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".fpu-", suffix=".probe", dir=parent)
    except OSError as exc:
        return f"cannot create a file in {parent}: {exc.strerror or exc}"
    os.close(fd)
    os.unlink(probe)
    return None


def _special(target: str) -> str | None:
    """The reason a path is a special place for an output (or None)."""
    real = os.path.realpath(target)
    for d in PSEUDO_FS:
        if real == d or real.startswith(d + os.sep):
            return f"{d} is a kernel file system, not a place for files"
    try:
        mode = os.stat(real).st_mode
    except OSError:
        return None
    if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        return "it is a special file (a device, a pipe or a socket), not a regular file"
    return None


def check_out_path(path: str, name: str = "--out", store: bool = False) -> None:
    """Refuse an output file that cannot be written, before any computation: its directory must
    exist and take a new file (probed), the path must not be a directory, a device file
    (``/dev/full``) or inside ``/proc`` / ``/sys``.  ``store``: the output is a directory store
    (the atlas's Zarr), which may exist already (resume)."""
    if not path or not isinstance(path, str):
        raise ParameterError(name, path, "a file name")
    target = os.path.abspath(os.path.expanduser(path))
    parent = os.path.dirname(target)
    why = _special(target)
    if why:
        raise ParameterError(name, path, "a regular file in a writable directory", why)
    if os.path.isdir(target) and not store:
        raise ParameterError(name, path, "a file path", "it is a directory")
    if not os.path.isdir(parent):
        raise ParameterError(
            name, path, "a file in an existing directory", f"directory {parent} does not exist"
        )
    if os.path.exists(target) and not os.access(target, os.W_OK):
        raise ParameterError(name, path, "a writable file", "permission denied")
    why = _probe_dir(parent)
    if why:
        raise ParameterError(name, path, "a file in a writable directory", why)


def check_out_dir(path: str, name: str) -> None:
    """Refuse an output directory (``--thumbnails DIR``) that does not exist or cannot take new
    files, before any computation (``/proc`` is a directory, and every write into it fails)."""
    if not path or not isinstance(path, str):
        raise ParameterError(name, path, "an existing writable directory")
    target = os.path.abspath(os.path.expanduser(path))
    if not os.path.isdir(target):
        raise ParameterError(name, path, "an existing directory")
    why = _special(target) or _probe_dir(target)
    if why:
        raise ParameterError(name, path, "an existing writable directory", why)


@contextlib.contextmanager
def output_file(path: str | os.PathLike, name: str = "--out", kept: str = ""):
    """Write an output atomically: yields a temporary path beside ``path`` (same suffix, so
    writers that choose the format by the suffix still work); once the block finishes it
    replaces ``path`` (``os.replace``).  On any failure the temporary file is removed — no
    partial file is left, under either name — and an OSError (disk full, permission, quota)
    becomes one :class:`OutputError` saying what was kept (``kept``: e.g. "the table was
    printed above")."""
    target = os.path.abspath(os.path.expanduser(os.fspath(path)))
    parent, base = os.path.split(target)
    stem, suffix = os.path.splitext(base)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{stem}.", suffix=f".partial{suffix}", dir=parent)
        os.close(fd)
        os.chmod(tmp, _file_mode(target))  # mkstemp's 0600 would outlive the rename
    except OSError as exc:
        raise _output_error(name, path, exc, kept) from None
    try:
        yield tmp
        os.replace(tmp, target)
    except OSError as exc:
        _remove(tmp)
        raise _output_error(name, path, exc, kept) from None
    except BaseException:
        _remove(tmp)
        raise


def _file_mode(target: str) -> int:
    """The mode a plain ``open(target, "w")`` would give: the existing file's, else 0666 less
    the umask."""
    try:
        return os.stat(target).st_mode & 0o7777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _remove(path: str) -> None:
    with contextlib.suppress(OSError):
        os.unlink(path)


def _output_error(name: str, path, exc: OSError, kept: str) -> OutputError:
    what = exc.strerror or str(exc)
    tail = f"; {kept}" if kept else ""
    return OutputError(
        f"could not write {name} {os.fspath(path)}: {what} (nothing written there, "
        f"no partial file left){tail}"
    )


LAW_HELP = (
    "any hardening-softening law f(w), instead of --a/--b: a polynomial of degree <= 16 or a "
    "smooth expression with exp, log, sqrt, tanh, sinh, cosh, atan, quotients, integer and "
    "rational powers and named constants given by --const, e.g. --law "
    '"w + b*w**2 - c*w**3*exp(w/d)" --const b=10 --const c=1 --const d=50 (an expression with '
    'a leading minus: --law="-..."), or a piecewise-linear law: '
    '"trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)" or '
    '"piecewise(breakpoints=[0.5, 1.5], slopes=[1, 4, 0.2])"'
)
CONST_HELP = "a named constant of --law, NAME=VALUE (repeat for each constant)"
DEFAULT_A, DEFAULT_B = -1.0, 10.0  # the paper's cubic


def add_law_args(p: argparse.ArgumentParser) -> None:
    """--a/--b (the cubic; defaults: the paper's a = -1, b = 10) or --law EXPR (any
    hardening–softening polynomial, instead of --a/--b), shared by every subcommand."""
    p.add_argument("--a", type=float, default=None, help="cubic coefficient a < 0 (default -1)")
    p.add_argument("--b", type=float, default=None, help="quadratic coefficient b > 0 (default 10)")
    p.add_argument("--law", default=None, metavar="EXPR", help=LAW_HELP)
    p.add_argument("--const", action="append", default=None, metavar="NAME=VALUE", help=CONST_HELP)


def law_from_args(args) -> HardeningSofteningLaw:
    """The law of the command line: ``--law`` parsed by SymPy if given, else CubicLaw(a, b).
    Both at once is refused: --law would silently replace the cubic the user asked for."""
    from fpucore.law import CubicLaw, law_from_expression  # heavy: Numba, SciPy

    a, b = getattr(args, "a", None), getattr(args, "b", None)
    if getattr(args, "law", None) is not None:
        if a is not None or b is not None:
            given = " ".join(f"--{n} {v:g}" for n, v in (("a", a), ("b", b)) if v is not None)
            raise ParameterError(
                "--law",
                args.law,
                "either --law EXPR or the cubic's --a/--b, not both",
                f"{given} given too; write the cubic into the law (a*w**3 + b*w**2 + w)",
            )
        return law_from_expression(args.law, _constants_of(getattr(args, "const", None)))
    if getattr(args, "const", None):
        raise ParameterError(
            "--const", args.const[0], "constants of a --law EXPR", "--const needs --law"
        )
    return CubicLaw(DEFAULT_A if a is None else a, DEFAULT_B if b is None else b)


def _constants_of(items) -> dict | None:
    """{name: value} from --const NAME=VALUE items (ParameterError naming the item)."""
    if not items:
        return None
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        try:
            val = float(value)
        except ValueError:
            val = None
        if not sep or val is None:
            raise ParameterError("--const", item, "NAME=VALUE with a real VALUE, e.g. b=10")
        if name.strip() in out:
            raise ParameterError("--const", item, "each constant once")
        out[name.strip()] = val
    return out


def law_fields(law: HardeningSofteningLaw) -> dict:
    """The law in JSON output: a, b for the cubic; the expression and coefficients otherwise."""
    from fpucore.law import CubicLaw  # heavy: Numba, SciPy

    if isinstance(law, CubicLaw):
        return {"a": law.a, "b": law.b, "law": law.describe()}
    if hasattr(law, "breakpoints"):  # piecewise-linear
        pl = cast("PiecewiseLinearLaw", law)
        return {
            "law": pl.expression,
            "breakpoints": list(pl.breakpoints),
            "slopes": list(pl.slopes),
        }
    if hasattr(law, "coeffs"):
        poly = cast("PolynomialLaw", law)
        return {"law": poly.expression, "coeffs": list(poly.coeffs)}
    sm = cast("SmoothLaw", law)
    err = sm.representation_error
    return {
        "law": sm.expression,
        "constants": sm.constants_dict,
        "represented_interval": list(sm.interval),
        "representation_error": {"f": err.f, "df": err.df, "ddf": err.ddf},
    }
