"""What the Floquet scene hands out: "Copy as Python" (the wave, its spectrum and, once run,
the family's sweep with its energy criterion), the JSON download and the notebook's plot.

A mixin of :class:`app.views.floquet.FloquetScene`, which keeps the results these read
(``_fr``, ``_r``, ``_sweep_result``, ``_ec``) and the sweep's velocities (``_sweep_values``).
"""

from __future__ import annotations

import numpy as np

from fpucore.floquet import changes_summary

from .. import compute
from .formatting import as_json, provenance
from .python_code import python_preamble
from .report import SceneMessage


class FloquetFiles:
    """Code, data and notebook plot of the Floquet scene."""

    def python_code(self) -> str:
        s = self.state
        req = compute.WaveRequest(s.mode, s.w_plus, s.V, s.N, s.tol)
        code = python_preamble(s) + (
            f"r = {req.call(s.law()).code()}\n"
            "print(r.converged, r.residual)\n"
            f"fr = {compute.SpectrumRequest(req).call().code('r')}\n"
            "print(len(fr.multipliers), fr.max_modulus, fr.error, fr.classification)\n"
            "print(fr.verdict)\n"
        )
        sw = self._sweep_result
        if sw is not None:
            kind, wp, Vs, _, branch = self._sweep_values()
            req = compute.SweepRequest(kind, wp, Vs, s.N, branch)
            code += (
                f"sw = {req.call().code()}\n"
                "print(sw.V.tolist(), sw.max_modulus.tolist(), list(sw.classification))\n"
            )
            if kind == "solitary":
                code += (
                    "# energy criterion: extrema of E_ren (the sweep's waves, the QC family)\n"
                    f"ec = floquet.criterion_from_samples(law, {wp!r}, sw.V, sw.energy, "
                    "sw.energy_error, sw.floquet_converged)\n"
                    "print(ec.extrema_V, ec.extrema_V_error, ec.qc_extrema_V)\n"
                    "print(floquet.stability_changes(law, sw.w_plus, sw.V, sw.classification, "
                    "ec))\n"
                )
        return code

    def download_data(self):
        fr, r = self._fr, self._r
        if fr is None:
            raise SceneMessage("nothing shown yet")
        mu = np.asarray(fr.multipliers)
        out = {
            "header": provenance(self.state, "Floquet multipliers of the discrete wave"),
            "python": self.python_code(),
            "V": r.V,
            "N": r.N,
            "kind": r.kind,
            "multipliers_re": mu.real,
            "multipliers_im": mu.imag,
            "max_modulus": fr.max_modulus,
            "error": fr.error,
            "symmetry_error": fr.symmetry_error,
            "integrator_error": fr.integrator_error,
            "verdict": fr.verdict,
            "classification": fr.classification,
            "finite_size_N": fr.finite_size_N,
            "finite_size_excess": fr.finite_size_excess,
            "finite_size_error": fr.finite_size_error,
            "finite_size_exponent": fr.finite_size_exponent,
            "decision": fr.decision.as_dict(),
        }
        sw = self._sweep_result
        if sw is not None:
            out["sweep"] = {
                "V": sw.V,
                "max_modulus": sw.max_modulus,
                "max_modulus_error": sw.max_modulus_error,
                "classification": sw.classification,
                "headline": [r.get("headline") for r in sw.rows],
                "energy": sw.energy,
                "energy_error": sw.energy_error,
            }
        ec = getattr(self, "_ec", None)
        if ec is not None:
            crit, changes = ec
            out["energy_criterion"] = {
                "extrema_V": crit.extrema_V,
                "extrema_V_error": crit.extrema_V_error,
                "extrema_kind": crit.extrema_kind,
                "qc_extrema_V": crit.qc_extrema_V,
                "qc_extrema_V_error": crit.qc_extrema_V_error,
                "qc_extrema_kind": crit.qc_extrema_kind,
                "unexplained_changes": [(c.V_from, c.V_to) for c in changes if not c.explained],
                "cross_check": changes_summary(changes),
            }
        return "floquet.json", as_json(out)

    def notebook_plot(self) -> str:
        code = (
            "import numpy as np\nimport matplotlib.pyplot as plt\n\n"
            "mu = np.asarray(fr.multipliers)\n"
            "th = np.linspace(0, 2 * np.pi, 721)\n"
            "fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5))\n"
            "ax1.plot(mu.real, mu.imag, 'x')\n"
            "ax1.plot(np.cos(th), np.sin(th), 'r')\n"
            "ax1.set(aspect='equal', xlabel='Re μ', ylabel='Im μ', title='Floquet multipliers')\n"
        )
        if self._sweep_result is not None:
            return code + (
                "y = np.maximum(np.asarray(sw.max_modulus) - 1,\n"
                "               np.maximum(sw.max_modulus_error, 1e-16))\n"
                "ax2.semilogy(sw.V, y, 'o-')\n"
                "ax2.set(xlabel='V', ylabel='max |μ| − 1', title='sweep')\n"
            )
        return code + "ax2.set_visible(False)\n"
