"""One thin view class per scene (tab); each only renders what fpucore computed.

The scenes are loaded from the registry (app/scene_registry.py), in its order; each class gets
its ``key`` from its entry there, the one place a scene is named.
"""

from importlib import import_module

from ..scene_registry import SCENES as ENTRIES


def _load(entry):
    cls = getattr(import_module(f".{entry.module}", __name__), entry.cls)
    cls.key = entry.key
    return cls


SCENES = tuple(_load(e) for e in ENTRIES)

__all__ = ["SCENES"]
