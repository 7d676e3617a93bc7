"""What the diagram scene hands out: "Copy as Python" (the QC family, the existence diagram, the
energy criterion and, once computed, the discrete waves and the branch views' sweeps), the CSV
download and the notebook's plot.

A mixin of :class:`app.views.diagram.DiagramScene`, which keeps the results these read
(``_fam``, ``_rows``, ``_ec_qc``, ``_ec_d``, ``_branch``, ``_sk_branch``, ``_exist``).
"""

from __future__ import annotations

import numpy as np

from .. import compute
from .formatting import as_csv, provenance
from .python_code import python_preamble
from .report import SceneMessage


class DiagramFiles:
    """Code, data and notebook plot of the diagram scene."""

    def download_data(self):
        fam = getattr(self, "_fam", None)
        if fam is None:
            raise SceneMessage("nothing shown yet")
        cols = {
            "V_below": fam.V_below,
            "amp_below": fam.amp_below,
            "E_below": fam.energy_below,
            "V_above": fam.V_above,
            "amp_above": fam.amp_above,
            "E_above": fam.energy_above,
        }
        if self._rows:
            cols["V_discrete"] = np.array([r.V for r in self._rows])
            cols["amp_discrete"] = np.array([r.amplitude for r in self._rows])
            cols["E_discrete"] = np.array([r.energy for r in self._rows])
            cols["residual_discrete"] = np.array([r.residual for r in self._rows])
            cols["amp_error_discrete"] = np.array([r.amplitude_error for r in self._rows])
            cols["E_error_discrete"] = np.array([r.energy_error for r in self._rows])
        ec = getattr(self, "_ec_qc", None)
        if ec is not None:
            cols["E_QC_extremum_V"] = ec.qc_extrema_V
            cols["E_QC_extremum_V_error"] = ec.qc_extrema_V_error
        ed = getattr(self, "_ec_d", None)
        if ed is not None:
            cols["E_discrete_extremum_V"] = ed.extrema_V
            cols["E_discrete_extremum_V_error"] = ed.extrema_V_error
        sw = getattr(self, "_branch", None)
        if sw is not None:
            cols["V_branch"] = np.asarray(sw.V, float)
            cols["E_branch"] = np.asarray(sw.energy, float)
            cols["max_modulus_branch"] = np.asarray(sw.max_modulus, float)
            cols["max_modulus_error_branch"] = np.asarray(sw.max_modulus_error, float)
        if self._sk_branch is not None:
            sk, amp, _ = self._sk_branch
            cols["V_superkink_branch"] = np.asarray(sk.V, float)
            cols["amplitude_superkink_branch"] = amp
            cols["max_modulus_superkink_branch"] = np.asarray(sk.max_modulus, float)
            cols["max_modulus_error_superkink_branch"] = np.asarray(sk.max_modulus_error, float)
            # the classes (text) go in the header, in the order of V_branch
        d = getattr(self, "_exist", None)
        if d is not None:
            cols.update(w_plus=d.w_plus, c_plus=d.c_plus, V_SK=d.V_SK, c_minus=d.c_minus)
        hdr = provenance(
            self.state,
            f"QC solitary family for w_plus={fam.w_plus!r} (c_plus={fam.c_plus!r}, "
            f"V_SK={fam.V_SK!r}, c_minus={fam.c_minus!r}); existence diagram columns",
            **({"branch_classification": list(sw.classification)} if sw is not None else {}),
            **(
                {"superkink_branch_classification": list(self._sk_branch[0].classification)}
                if self._sk_branch is not None
                else {}
            ),
        )
        return "diagram.csv", as_csv(cols, hdr + "\n" + self.python_code())

    def notebook_plot(self) -> str:
        code = (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            "fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(14, 4))\n"
            "for V, amp, E in ((fam.V_below, fam.amp_below, fam.energy_below),\n"
            "                  (fam.V_above, fam.amp_above, fam.energy_above)):\n"
            "    ax1.plot(V, amp)\n"
            "    ax2.plot(V, E)\n"
            "E = np.r_[fam.energy_below, fam.energy_above]\n"
            "lo, hi = np.quantile(E, [0.08, 0.92])\n"
            "ax2.set_ylim(lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo))\n"
        )
        if getattr(self, "_rows", None):
            code += (
                "ax1.plot([r.V for r in rows], [r.amplitude for r in rows], 'ko')\n"
                "ax2.plot([r.V for r in rows], [r.energy for r in rows], 'ko')\n"
            )
        if getattr(self, "_branch", None) is not None:
            code += (
                "colors = {'stable': 'g', 'finite_size': 'b', 'unstable': 'r', "
                "'undetermined': 'gray'}\n"
                "for V, E, c in zip(sw.V, sw.energy, sw.classification):\n"
                "    ax2.plot(V, E, 'o', color=colors.get(c, 'k'), mec='k')\n"
            )
        if getattr(self, "_sk_branch", None) is not None:
            code += (
                "colors = {'stable': 'g', 'finite_size': 'b', 'unstable': 'r', "
                "'undetermined': 'gray'}\n"
                "fig4, ax4 = plt.subplots(figsize=(9, 3))\n"
                "for V, A, c in zip(sk.V, amp, sk.classification):\n"
                "    ax4.plot(V, A, 'o', color=colors.get(c, 'k'), mec='k')\n"
                "ax4.set(xlabel='V', ylabel='|w₋ − w₊|', title='superkinks by Floquet class')\n"
            )
        return code + (
            "for ax in (ax1, ax2):\n"
            "    ax.axvline(fam.V_SK, color='r', ls='--')\n"
            "ax1.set(xlabel='V', ylabel='amplitude')\n"
            "ax2.set(xlabel='V', ylabel='E_ren')\n"
            "ax3.plot(d.w_plus, d.V_SK, 'r', d.w_plus, d.c_plus, 'b', d.w_plus, d.c_minus, 'g')\n"
            "ax3.set(xlabel='w₊', ylabel='V', title='existence')\n"
        )

    def python_code(self) -> str:
        s = self.state
        try:
            qc_n = compute.energy.energy_qc_samples(s.law())
        except compute.ParameterError:
            qc_n = compute.energy.ENERGY_QC_SAMPLES[True]
        code = python_preamble(s) + (
            "from fpucore.qc import diagram\n"
            f"fam = {compute.QCFamilyRequest(s.w_plus).call().code()}\n"
            f"d = {compute.ExistenceRequest().call().code()}\n"
            "print(fam.c_plus, fam.V_SK, fam.c_minus)\n"
            "# energy criterion: extrema of E_ren^QC(V), where stability may change\n"
            f"ec = floquet.energy_criterion(law, {float(s.w_plus)!r}, qc_samples={qc_n})\n"
            "print(ec.qc_extrema_kind, ec.qc_extrema_V, ec.qc_extrema_V_error)\n"
        )
        if getattr(self, "_rows", None):
            Vs = [float(r.V) for r in self._rows]
            req = compute.FamilyRequest(s.w_plus, Vs, s.N, s.tol)
            code += (
                f"rows = {req.call().code()}.results\n"
                "print([(r.V, r.amplitude, r.energy) for r in rows])\n"
            )
        sw = getattr(self, "_branch", None)
        if sw is not None:
            req = compute.SweepRequest("solitary", float(sw.w_plus), sw.V, s.N, "lower")
            code += (
                "# branch view: the family's Floquet sweep, classified\n"
                f"sw = {req.call().code()}\n"
                "print(list(zip(sw.V, sw.energy, sw.classification)))\n"
            )
        if self._sk_branch is not None:
            sk, _, branch = self._sk_branch
            req = compute.SweepRequest("superkink", None, sk.V, s.N, branch)
            code += (
                "# superkink branch view: the superkink family's Floquet sweep, classified\n"
                f"sk = {req.call().code()}\n"
                f"amp = [abs(qc.superkink_from_V(law, v, branch={branch!r}).w_minus\n"
                f"           - qc.superkink_from_V(law, v, branch={branch!r}).w_plus) "
                "for v in sk.V]\n"
                "print(list(zip(sk.V.tolist(), amp, sk.max_modulus.tolist(), "
                "sk.classification)))\n"
            )
        return code
