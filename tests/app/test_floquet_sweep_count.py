"""The Floquet scene's sweep control: the number typed under "velocities in the sweep (total)"
is the number of velocities swept, also for a solitary family, whose two intervals (tensile
(c₊, V_SK) and compressive (V_SK, c₋)) share it.

References: the paper's closed forms for a = -1, b = 10, w₊ = 1: c₊ = 3√2, c₋ = 11/2,
V_SK = 2√65/3.  (The old control swept the typed number on *each* interval: 2k velocities.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}
C_PLUS, C_MINUS, V_SK = 3 * math.sqrt(2), 5.5, 2 * math.sqrt(65) / 3


def test_the_sweep_has_as_many_velocities_as_the_control_says():
    st = ExplorerState(w_plus=1.0, V=5.0, N=100, tol=1e-8)
    sc = BY_KEY["floquet"](st)
    sc.panel.get_root(Document())
    assert "total" in sc.n_sweep.label  # the label says what the number counts
    for k, (n_tensile, n_compressive) in ((5, (3, 2)), (4, (2, 2))):  # a user retypes it
        sc.n_sweep.value = k
        sc._want_sweep = True  # what the Sweep button sets
        sc.refresh()
        assert sc.last_message is None, sc.last_message
        V = np.asarray(sc._sweep_result.V)
        assert V.size == k
        assert f"sweep ({k} V)" in sc.status.object
        # both intervals, the odd one to the tensile side, none at a limit
        assert np.sum((C_PLUS < V) & (V < V_SK)) == n_tensile
        assert np.sum((V_SK < V) & (V < C_MINUS)) == n_compressive
        # every swept velocity is drawn on panel (c) (in the colour of its decision) or
        # named in the status as not converged
        drawn = sum(len(src.data["x"]) for _, src in sc.r_cls.values())
        assert drawn == k or "did not converge" in sc.status.object
