"""The explorer's scenes: registered once, small, and independent of each other.

* the tab bar, the state's ``tab`` values, the URL's ``tab=`` names and the warm-up's default
  list all come from app/scene_registry.py — and no module of app/ writes a second list of
  scene names (or a scene its own key) that could disagree with it;
* no scene file (nor any module of app/) passes 400 lines, and no scene imports another scene
  (shared pieces live in modules that scenes import).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

pytest.importorskip("panel")

from app import scene_registry, url_state, warmup  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402
from app.views.scene import Scene  # noqa: E402
from fpucore.errors import ParameterError  # noqa: E402

APP = Path(__file__).resolve().parents[2] / "app"
REGISTRY = APP / "scene_registry.py"


def _app_files() -> list[Path]:
    return [p for p in sorted(APP.rglob("*.py")) if "__pycache__" not in p.parts]


def test_every_list_of_tabs_is_the_registry():
    keys = tuple(e.key for e in scene_registry.SCENES)
    assert len(set(keys)) == len(keys) == len(SCENES)
    assert tuple(cls.key for cls in SCENES) == keys == scene_registry.TABS
    assert all(issubclass(cls, Scene) for cls in SCENES)
    assert tuple(ExplorerState.param.tab.objects) == keys
    ex = Explorer()
    assert [name for name, _ in zip(ex.tabs._names, ex.tabs.objects)] == [c.title for c in SCENES]
    assert [s.key for s in ex.scenes] == list(keys)
    for i, key in enumerate(keys):
        assert url_state.parse_url_value("tab", key) == key
        ex.state.tab = key
        assert ex.tabs.active == i
    with pytest.raises(ParameterError, match="tab"):
        url_state.parse_url_value("tab", "nosuchscene")
    warm = warmup.DEFAULT_SCENES.split(",")
    assert warm == [e.key for e in scene_registry.SCENES if e.warm] and "floquet" not in warm


def _names_in(node: ast.AST, keys: set[str]) -> set[str]:
    """The scene keys a literal names: its string items, or the comma-separated parts of a
    string ("force,phase")."""
    out: set[str] = set()
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        for item in node.elts:
            if isinstance(item, ast.Constant) and isinstance(item.value, str):
                out |= {item.value} & keys
    elif isinstance(node, ast.Constant) and isinstance(node.value, str) and "," in node.value:
        out |= set(node.value.split(",")) & keys
    return out


def test_no_second_list_of_scenes_can_disagree_with_the_registry():
    """A literal that names two scenes or more (a tuple of tabs, a "force,phase" default) or a
    scene class that names its own key would be a second list to keep in step by hand."""
    keys = set(scene_registry.TABS)
    bad = []
    for path in _app_files():
        if path == REGISTRY:
            continue
        tree = ast.parse(path.read_text())
        rel = path.relative_to(APP.parent)
        for node in ast.walk(tree):
            names = _names_in(node, keys)
            if len(names) >= 2:
                bad.append(f"{rel}:{node.lineno}: names the scenes {sorted(names)}")
            if isinstance(node, ast.ClassDef) and path.name != "scene.py":
                for stmt in node.body:
                    targets = stmt.targets if isinstance(stmt, ast.Assign) else []
                    if any(isinstance(t, ast.Name) and t.id == "key" for t in targets):
                        bad.append(f"{rel}:{stmt.lineno}: {node.name} sets its own key")
    assert not bad, "scene names written beside app/scene_registry.py:\n" + "\n".join(bad)


MAX_LINES = 400


def test_no_module_of_the_explorer_passes_400_lines():
    long = {
        str(p.relative_to(APP.parent)): n
        for p in _app_files()
        if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert not long, f"files over {MAX_LINES} lines (split them by topic): {long}"


def _scene_modules() -> dict[str, Path]:
    return {
        f"app.views.{e.module}": APP / "views" / f"{e.module}.py" for e in scene_registry.SCENES
    }


def _imported_modules(path: Path) -> set[str]:
    """The app modules ``path`` imports (relative imports resolved; ``from . import x`` names
    the module x when it is one)."""
    rel = path.relative_to(APP.parent).with_suffix("")
    parts = list(rel.parts)
    pkg = parts[:-1]  # the package of a module, and of an __init__ its own package
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = pkg[: len(pkg) - (node.level - 1)] if node.level else []
            mod = ".".join(base + ([node.module] if node.module else []))
            out.add(mod)
            out |= {f"{mod}.{a.name}" for a in node.names}
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
    return out


def test_no_scene_imports_another_scene():
    """What two scenes share (the Floquet classes' colours, the formatting of a comparison, …)
    lives in a module both import; only the registry's loader (app/views/__init__) reaches the
    scene modules."""
    scenes = _scene_modules()
    assert all(p.exists() for p in scenes.values()), scenes
    bad = []
    for path in _app_files():
        if path == APP / "views" / "__init__.py":
            continue
        own = next((m for m, p in scenes.items() if p == path), None)
        for target in sorted(_imported_modules(path) & set(scenes) - {own}):
            bad.append(f"{path.relative_to(APP.parent)} imports the scene {target}")
    assert not bad, "\n".join(bad)


def test_a_scene_builds_its_state_in_its_constructor():
    """A scene's attributes and its widgets' watchers are set up in ``__init__`` (after the
    base class has built its widgets and figures), not in a hook the base class calls."""
    hooks = [
        f"{p.relative_to(APP.parent)}: {node.name}"
        for p in _app_files()
        for node in ast.walk(ast.parse(p.read_text()))
        if isinstance(node, ast.FunctionDef) and node.name == "_extra_watch"
    ]
    assert not hooks, hooks
    for cls in SCENES:
        assert "_extra_watch" not in vars(cls)
