"""A held curve of the explorer's state (Hold on Wave profiles and Phase plane): the wave it
shows, named by what a link must carry to redraw it."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class HeldWave:
    """One held curve: the wave it shows, under the state's law (and N, tol).  A superkink is
    named by its w₊ alone (V = V_SK(w₊), eq. cubic_cond2, follows from the law); a solitary
    wave by (w₊, V).  Its curves are recomputed (cached) by the scenes that draw it."""

    mode: str
    w_plus: float
    V: float | None = None

    def label(self, V: float | None = None) -> str:
        """Legend label; ``V``: the superkink's velocity under the current law."""
        if self.mode == "superkink":
            v = f"superkink V = {V:.6g}, " if V is not None else "superkink "
            return f"{v}w₊ = {self.w_plus:.6g}"
        return f"V = {self.V:.6g}, w₊ = {self.w_plus:.6g}"

    def url(self, w_plus: float) -> str:
        """URL form: ``V`` (solitary at the state's w₊ ``w_plus``), ``V@w₊`` (solitary at another
        w₊) or ``sk@w₊`` (superkink); floats exact (repr)."""
        if self.mode == "superkink":
            return f"sk@{self.w_plus!r}"
        if self.w_plus == w_plus:
            return repr(self.V)
        return f"{self.V!r}@{self.w_plus!r}"
