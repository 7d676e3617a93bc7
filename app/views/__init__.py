"""One thin view class per scene (tab); each only renders what fpucore computed."""

from .atlas import AtlasScene
from .diagram import DiagramScene
from .floquet import FloquetScene
from .force_law import ForceLawScene
from .paper import PaperScene
from .phase_plane import PhasePlaneScene
from .profiles import ProfilesScene
from .simulation import SimulationScene

SCENES = (
    ForceLawScene,
    PhasePlaneScene,
    ProfilesScene,
    DiagramScene,
    FloquetScene,
    SimulationScene,
    AtlasScene,
    PaperScene,
)

__all__ = ["SCENES"] + [cls.__name__ for cls in SCENES]
