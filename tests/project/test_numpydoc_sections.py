"""The public functions of wave, floquet and simulate document their arguments and results in
numpydoc sections (``Parameters`` and ``Returns``, each underlined with dashes)."""

from __future__ import annotations

import importlib
import inspect
import re

import pytest

PACKAGES = ("fpucore.wave", "fpucore.floquet", "fpucore.simulate")
REQUIRED = ("Parameters", "Returns")


def public_functions() -> list[tuple[str, object]]:
    out = []
    for pkg in PACKAGES:
        mod = importlib.import_module(pkg)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if inspect.isfunction(obj):
                out.append((f"{pkg}.{name}", obj))
    return out


def missing_sections(doc: str | None) -> list[str]:
    text = inspect.cleandoc(doc or "")
    return [s for s in REQUIRED if not re.search(rf"^{s}\n-{{{len(s)}}}$", text, re.MULTILINE)]


def test_the_three_packages_export_functions():
    assert len(FUNCTIONS) >= 30


FUNCTIONS = public_functions()


@pytest.mark.parametrize("qualname,fn", FUNCTIONS, ids=[q for q, _ in FUNCTIONS])
def test_public_function_has_numpydoc_sections(qualname, fn):
    assert missing_sections(fn.__doc__) == [], f"{qualname} lacks numpydoc sections"


def test_a_docstring_without_sections_is_caught():
    assert missing_sections("One line.\n\n    Returns the value.\n") == list(REQUIRED)
    assert missing_sections("Sum.\n\n    Parameters\n    ---\n    x : float\n") == list(REQUIRED)
