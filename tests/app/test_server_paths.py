"""A page never names a path of the server: stores and files are named relative to the server's
data directory (app/data_dir.py), and an exception's text repeated in a message has the
server's directories taken out.  ("no atlas store at /…/clone/x.zarr" told a stranger with a
link where the server's checkout was.)"""

from __future__ import annotations

import os
import sys

import pytest

pytest.importorskip("panel")

from app.data_dir import DATA_DIR_NAME, data_name, hide_server_paths  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.url_state import parse_url  # noqa: E402
from app.views.atlas import AtlasScene  # noqa: E402


@pytest.fixture
def root(tmp_path, monkeypatch):
    """A data directory deep below the server's disk, with a directory that is no store and a
    symlink loop (Path.resolve names the loop by its absolute path)."""
    root = tmp_path / "srv" / "clone"
    (root / "stores" / "empty.zarr").mkdir(parents=True)
    (root / "loop").symlink_to(root / "loop")
    monkeypatch.setenv("FPU_ATLAS_ROOT", str(root))
    return root


def _atlas_message(raw: str) -> str:
    sc = AtlasScene(ExplorerState(atlas=raw))
    sc.refresh()
    assert sc.last_message, raw
    return sc.last_message


@pytest.mark.parametrize(
    "raw, said",
    [
        ("stores/none.zarr", "no atlas store at stores/none.zarr"),
        ("./stores/../stores/none.zarr", "no atlas store at stores/none.zarr"),
        ("stores/empty.zarr", "cannot read stores/empty.zarr"),
        ("{root}/stores/none.zarr", "no atlas store at stores/none.zarr"),  # typed absolute
    ],
)
def test_the_atlas_message_names_the_store_relative_to_the_data_directory(root, raw, said):
    msg = _atlas_message(raw.format(root=root))
    assert said in msg, msg
    shown = msg.replace(raw.format(root=root), "")  # what the visitor typed is theirs
    assert str(root.parent) not in shown, msg


@pytest.mark.parametrize("raw", ["../elsewhere.zarr", "loop/x.zarr", "/etc", "stores/\x00"])
def test_a_refused_store_is_named_without_the_servers_path(root, raw):
    """Outside the directory, a symlink loop, a NUL byte: the URL message names the value as
    typed and the valid range as "below the server's data directory", never the directory's
    absolute path (the loop's RuntimeError named it)."""
    values, errors = parse_url({"atlas": raw})
    assert values == {} and len(errors) == 1, errors
    assert str(root.parent) not in errors[0] and DATA_DIR_NAME in errors[0], errors[0]
    msg = _atlas_message(raw)
    assert str(root.parent) not in msg and "atlas store=" in msg, msg


def test_exception_text_loses_the_servers_directories(root):
    """Below the data directory a path becomes relative; the server's other directories (its
    Python, temp, home) become "…/"; a path typed by the visitor elsewhere is left alone."""
    text = (
        f"cannot read {root}/stores/x.zarr: [Errno 2] in {root}; {sys.prefix}/lib/x.py; "
        f"{os.path.join(os.path.expanduser('~'), 'n')}; {root}2/other"
    )
    out = hide_server_paths(text)
    assert "cannot read stores/x.zarr:" in out and f"in {DATA_DIR_NAME};" in out, out
    assert sys.prefix not in out and "…/lib/x.py" in out and "…/n" in out, out
    assert data_name(root / "stores" / "x.zarr") == "stores/x.zarr" and data_name(root) == "."
    assert data_name("/etc/passwd") == "passwd"  # outside: never opened, its last part only
