"""fpucore's files stay small and named for what they hold (DEVELOPERS.md: <= 400 lines): a
module that grows past the limit is split by topic (a group of helpers, a result class, a
kernel family into a sibling module), not allowed to grow."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "fpucore"
MAX_LINES = 400

# Modules over the limit, each to be split and then removed from here (the test fails when an
# entry is back under the limit, so the list only shrinks): none now
ALLOWED: set[str] = set()


def line_count(path: Path) -> int:
    """Lines of a file as ``wc -l`` counts them (a last line without newline counts too)."""
    return len(path.read_text(encoding="utf-8").splitlines())


def module_sizes(pkg: Path = PKG) -> dict[str, int]:
    """{path relative to the repository: line count} of every Python module of the package."""
    return {
        p.relative_to(pkg.parent).as_posix(): line_count(p)
        for p in sorted(pkg.rglob("*.py"))
        if "__pycache__" not in p.parts
    }


def oversized(sizes: dict[str, int], allowed: set[str] = ALLOWED) -> list[str]:
    return [f"{m}: {n} lines" for m, n in sizes.items() if n > MAX_LINES and m not in allowed]


def test_every_module_is_at_most_400_lines():
    sizes = module_sizes()
    assert len(sizes) > 100, "fpucore's modules were not found"
    bad = oversized(sizes)
    assert not bad, f"modules over {MAX_LINES} lines (split them by topic):\n" + "\n".join(bad)


def test_the_allow_list_holds_only_oversized_modules():
    sizes = module_sizes()
    stale = [m for m in sorted(ALLOWED) if sizes.get(m, 0) <= MAX_LINES]
    assert not stale, f"at most {MAX_LINES} lines now (or gone): remove from ALLOWED: {stale}"


@pytest.mark.parametrize("lines,too_big", [(400, False), (401, True)])
def test_the_limit_is_inclusive(tmp_path, lines, too_big):
    """400 lines pass, 401 fail; a last line without newline counts (as for ``wc -l``)."""
    pkg = tmp_path / "fpucore"
    pkg.mkdir()
    (pkg / "big.py").write_text("x = 1\n" * (lines - 1) + "x = 1")
    sizes = module_sizes(pkg)
    assert sizes == {"fpucore/big.py": lines}
    assert bool(oversized(sizes, set())) is too_big
    assert not oversized(sizes, {"fpucore/big.py"})
