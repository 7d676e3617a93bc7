"""The scenes, in tab order: the one list that the tab bar (app/views), the URL's ``tab=`` names
(app/state.py, app/url_state.py) and the server's warm-up (app/warmup.py) read.

A scene registers itself here with one line — its key, where its class lives, and whether the
server renders it before it accepts connections — and nowhere else: its class gets its ``key``
from this entry (app/views/__init__.py), so no second list or name can disagree with this one.
This module imports nothing of the dashboard (state.py reads it before any view exists).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SceneEntry:
    """One tab: ``key`` its URL name (``tab=key``) and CSS class (``scene-key``); ``module`` and
    ``cls`` its class (app/views/<module>.py); ``warm``: rendered by the server's warm-up for
    the default parameters (a scene whose first render would hold the server's start for
    seconds is left to its first visitor)."""

    key: str
    module: str
    cls: str
    warm: bool


SCENES = (
    SceneEntry("force", "force_law", "ForceLawScene", warm=True),
    SceneEntry("phase", "phase_plane", "PhasePlaneScene", warm=True),
    SceneEntry("profiles", "profiles", "ProfilesScene", warm=True),
    SceneEntry("diagram", "diagram", "DiagramScene", warm=True),
    # its eigenvalue calls (0.2–0.8 s alone at N = 500, many times that on a loaded machine)
    SceneEntry("floquet", "floquet", "FloquetScene", warm=False),
    SceneEntry("simulation", "simulation", "SimulationScene", warm=True),
    SceneEntry("atlas", "atlas", "AtlasScene", warm=False),
    SceneEntry("paper", "paper", "PaperScene", warm=False),
)

#: the tabs' keys in tab order (the URL's tab= values)
TABS = tuple(e.key for e in SCENES)
#: the scenes the server's warm-up renders by default (FPU_WARM_SCENES overrides it)
WARM_SCENES = ",".join(e.key for e in SCENES if e.warm)
