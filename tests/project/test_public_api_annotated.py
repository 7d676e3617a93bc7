"""fpucore's public API is fully annotated: every parameter and return of every public function,
and of every public method of a public class, named in a subpackage's ``__all__`` (the names the
docs' API reference documents).  mypy (``make test``) checks the annotations against the code;
this test checks that there is nothing left for it to skip."""

from __future__ import annotations

import importlib
import inspect

import pytest

PUBLIC = ["fpucore", "fpucore.law", "fpucore.qc", "fpucore.wave", "fpucore.floquet",
          "fpucore.simulate", "fpucore.atlas", "fpucore.parallel", "fpucore.paper",
          "fpucore.tableaux", "fpucore.errors", "fpucore.result", "fpucore.budget"]  # fmt: skip


def unannotated(fn, qual: str) -> list[str]:
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):  # a builtin: nothing to annotate
        return []
    out = [f"{qual}({n})" for n, p in sig.parameters.items()
           if n not in ("self", "cls") and p.annotation is inspect.Parameter.empty]  # fmt: skip
    if sig.return_annotation is inspect.Signature.empty and not qual.endswith(".__init__"):
        out.append(f"{qual} -> ?")
    return out


def public_callables(module_name: str):
    """(qualified name, function) of the module's public functions and its public classes'
    public methods and properties, defined in fpucore (dataclass-generated methods excluded)."""
    mod = importlib.import_module(module_name)
    for name in getattr(mod, "__all__", [n for n in dir(mod) if not n.startswith("_")]):
        obj = getattr(mod, name)
        if inspect.isclass(obj) and obj.__module__.startswith("fpucore"):
            for attr, member in vars(obj).items():
                if attr.startswith("_") and attr != "__init__":
                    continue
                member = member.fget if isinstance(member, property) else member
                member = getattr(member, "__func__", member)  # static/class methods
                if inspect.isfunction(member) and member.__module__.startswith("fpucore"):
                    if attr == "__init__" and hasattr(obj, "__dataclass_fields__"):
                        continue
                    yield f"{module_name}.{name}.{attr}", member
        elif inspect.isfunction(obj) and obj.__module__.startswith("fpucore"):
            yield f"{module_name}.{name}", obj
        elif hasattr(obj, "py_func"):  # a Numba dispatcher
            yield f"{module_name}.{name}", obj.py_func


@pytest.mark.parametrize("module_name", PUBLIC)
def test_public_api_is_fully_annotated(module_name):
    missing = [m for qual, fn in public_callables(module_name) for m in unannotated(fn, qual)]
    assert not missing, f"{len(missing)} unannotated: {missing[:20]}"


def test_the_check_sees_the_api():
    """The walk reaches the functions and methods users call (a walk that found nothing would
    pass vacuously)."""
    names = {q for m in PUBLIC for q, _ in public_callables(m)}
    for q in ("fpucore.wave.solve_superkink", "fpucore.floquet.spectrum", "fpucore.qc.solitary",
              "fpucore.law.CubicLaw.f", "fpucore.simulate.riemann",
              "fpucore.atlas.run"):  # fmt: skip
        assert q in names, q
    assert len(names) > 150, len(names)
