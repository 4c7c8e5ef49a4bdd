"""A plane curve ``p(x, y) = 0`` evaluated quickly, and Newton's method onto it.

The profile of a surface of revolution is traced and fitted point by point (:mod:`.meridian`,
:mod:`.fitted`): thousands of evaluations of ``p`` and ``∇p`` at one or a few points. Here ``p``
is a dense coefficient array in coordinates divided by a length (the drawn ball's radius), its
largest coefficient 1: the values are ``p`` times a positive constant, so signs, zero sets,
directions of ``∇p``, Newton steps ``p·∇p/|∇p|²`` and first-order distances ``|p|/|∇p|`` are
those of ``p``, and nothing overflows inside the ball.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sorgui.engine.values import Terms


@dataclass(frozen=True, eq=False)
class PlaneCurve:
    """``p(x, y) = Σ c[i, j]·(x/L)^i·(y/L)^j`` up to a positive factor, ``L`` = ``length``."""

    coefficients: np.ndarray
    length: float

    @classmethod
    def from_terms(cls, terms: Terms, length: float) -> PlaneCurve:
        """The curve of float ``terms`` ``((i, j), c)``, scaled by ``length``."""
        degree = max((max(i, j) for (i, j), _ in terms), default=0)
        logs = [np.log2(abs(c)) + (i + j) * np.log2(length) for (i, j), c in terms if c != 0]
        shift = -int(np.floor(max(logs))) if logs else 0
        coefficients = np.zeros((degree + 1, degree + 1))
        for (i, j), c in terms:
            if c:
                coefficients[i, j] += np.sign(c) * np.exp2(np.log2(abs(c)) + shift + (i + j) * np.log2(length))
        return cls(coefficients, float(length))

    def value_and_gradient(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``p`` and ``∇p`` (up to one positive factor) at points ``(n, 2)``."""
        u = np.asarray(xy, dtype=np.float64).reshape(-1, 2) / self.length
        n = self.coefficients.shape[0]
        powers = [np.vander(u[:, k], n, increasing=True) for k in range(2)]
        slopes = [np.zeros_like(p) for p in powers]
        for k in range(2):
            slopes[k][:, 1:] = powers[k][:, :-1] * np.arange(1, n)
        with np.errstate(over="ignore", invalid="ignore"):
            inner = powers[1] @ self.coefficients.T
            value = np.einsum("ni,ni->n", powers[0], inner)
            dx = np.einsum("ni,ni->n", slopes[0], inner)
            dy = np.einsum("ni,ni->n", powers[0], slopes[1] @ self.coefficients.T)
        return value, np.column_stack([dx, dy]) / self.length

    def onto(self, xy: np.ndarray, steps: int = 8) -> np.ndarray:
        """Points moved onto ``p = 0`` by Newton steps ``-p·∇p/|∇p|²`` (points on the axis
        ``y = 0`` stay on it when ``p`` is even in ``y``: its gradient there is along ``x``)."""
        out = np.array(xy, dtype=np.float64).reshape(-1, 2)
        for _ in range(steps):
            values, gradients = self.value_and_gradient(out)
            norm2 = np.einsum("ij,ij->i", gradients, gradients)
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                step = np.where(norm2[:, None] > 0, -(values / norm2)[:, None] * gradients, 0.0)
            out = out + np.nan_to_num(step, nan=0.0, posinf=0.0, neginf=0.0)
        return out

    def distance(self, xy: np.ndarray) -> np.ndarray:
        """The first-order distance ``|p|/|∇p|`` (0 at a singular point on the curve)."""
        values, gradients = self.value_and_gradient(xy)
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.abs(values) / np.linalg.norm(gradients, axis=1)
        return np.asarray(np.where(np.isnan(out), 0.0, out))
