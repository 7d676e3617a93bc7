"""Docstrings as fpucore writes them, read by autodoc under ``-W -n``.

* ``|μ|``, ``|a|``: absolute values in prose, which reStructuredText reads as substitution
  references; escaped outside literals.
* A cross-reference to a name fpucore really has but does not export (a module constant such as
  ``STATUSES``, a kernel module) is shown as code without a link; a name that does not exist
  anywhere in fpucore stays a broken reference and fails the build.
"""

from __future__ import annotations

import importlib
import re
import sys

_LITERAL = re.compile(r"(``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`)")


def escape_bars(app, what, name, obj, options, lines: list[str]) -> None:
    for i, line in enumerate(lines):
        parts = _LITERAL.split(line)
        lines[i] = "".join(p if j % 2 else p.replace("|", "\\|") for j, p in enumerate(parts))


def exists(dotted: str) -> bool:
    """Is ``dotted`` (a.b.c) a module, or an attribute reached from the longest importable
    module prefix?"""
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        except Exception:  # noqa: BLE001  (a module that fails to import has no such name)
            return False
        for attr in parts[k:]:
            if attr in getattr(obj, "__annotations__", {}) or attr in getattr(
                obj, "__dataclass_fields__", {}
            ):
                obj = None
                continue
            if obj is None or not hasattr(obj, attr):
                return False
            obj = getattr(obj, attr)
        return True
    return False


def lookup(dotted: str):
    """The object named ``dotted`` (longest importable module prefix, then attributes), or
    None."""
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except Exception:  # noqa: BLE001
            continue
        for attr in parts[k:]:
            obj = getattr(obj, attr, None)
        return obj
    return None


def home_module(dotted: str) -> str:
    """The module that defines the object named ``dotted`` (its ``__module__``, through a
    property's getter), or ''."""
    obj = lookup(dotted)
    obj = getattr(obj, "fget", obj)
    return getattr(obj, "__module__", "") or ""


def candidates(target: str, module: str | None, cls: str | None, source: str) -> list[str]:
    """Where ``target`` may live: itself, then relative to the documented module (and class),
    then relative to the object whose docstring holds it (autodoc documents a re-exported
    object under its package, while its docstring's short names are its own module's)."""
    target = target.lstrip(".~")
    out = [target]
    m = re.search(r"docstring of ([\w.]+)", source or "")
    owner = m.group(1) if m else ""
    for pkg in (module or "", owner, home_module(owner) if owner else ""):
        while pkg:
            if cls:
                out.append(f"{pkg}.{cls}.{target}")
            out.append(f"{pkg}.{target}")
            pkg = pkg.rpartition(".")[0]
    return [c for c in out if c.startswith("fpucore")]


def resolve_fpucore(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"]
    found = any(
        exists(c)
        for c in candidates(target, node.get("py:module"), node.get("py:class"), node.source)
    )
    # a bare name in a signature (no module context: "<unknown>" source), e.g. a Protocol or an
    # alias a module defines for its annotations: found when an fpucore module defines it
    found = found or (
        "." not in target
        and any(
            name.startswith("fpucore") and target in vars(mod)
            for name, mod in list(sys.modules.items())
            if mod is not None
        )
    )
    return contnode if found else None
