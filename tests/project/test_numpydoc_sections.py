"""The public functions of wave, floquet and simulate document their arguments and results in
numpydoc sections (``Parameters`` and ``Returns``, each underlined with dashes), with every
parameter of the signature listed, in order."""

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


def documented_parameters(doc: str | None) -> list[str]:
    """Names of the Parameters section's entries (``a, b : float`` gives a and b)."""
    text = inspect.cleandoc(doc or "")
    m = re.search(r"^Parameters\n-+\n(.*?)(?:\n\n\w+\n-+\n|\Z)", text, re.DOTALL | re.MULTILINE)
    names: list[str] = []
    for line in (m.group(1) if m else "").splitlines():
        if line and not line.startswith(" "):
            names += [x.strip().strip("`").lstrip("*") for x in line.split(" : ")[0].split(",")]
    return names


FUNCTIONS = public_functions()


def test_the_three_packages_export_functions():
    assert len(FUNCTIONS) >= 30


@pytest.mark.parametrize("qualname,fn", FUNCTIONS, ids=[q for q, _ in FUNCTIONS])
def test_public_function_has_numpydoc_sections(qualname, fn):
    assert missing_sections(fn.__doc__) == [], f"{qualname} lacks numpydoc sections"
    assert documented_parameters(fn.__doc__) == list(inspect.signature(fn).parameters), qualname


def test_a_docstring_without_sections_is_caught():
    assert missing_sections("One line.\n\n    Returns the value.\n") == list(REQUIRED)
    assert missing_sections("Sum.\n\n    Parameters\n    ---\n    x : float\n") == list(REQUIRED)
    doc = "Sum.\n\n    Parameters\n    ----------\n    x, y : float\n        Terms.\n    **kw\n"
    assert documented_parameters(doc + "\n    Returns\n    -------\n    z : float\n") == [
        "x",
        "y",
        "kw",
    ]
