"""Floating-point helpers shared by the rounded-input stage of the engine and the render layer.

Numpy only: the render layer may import this without the engine (no sympy, no flint), and the
engine's rounded-input stage (:mod:`sorgui.engine.rounded`) uses the same numerics, so a root
found for the deviation of rounded input and for a touching sphere in the 3D view agree. Numpy
is imported by the function that needs it: the text report prints through :func:`without_noise`,
and an analysis that prints its answer need not load numpy (about 50 ms).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray


def real_roots(coefficients: NDArray[np.float64]) -> NDArray[np.float64]:
    """The real roots of a univariate polynomial (lowest degree first), numerically."""
    import numpy as np

    c = np.asarray(coefficients, dtype=np.float64)
    top = float(np.abs(c).max(initial=0.0))
    if top == 0.0 or not np.isfinite(top):
        return np.zeros(0)
    c = c / top
    nonzero = np.nonzero(np.abs(c) > 1e-12)[0]
    if len(nonzero) == 0 or nonzero[-1] == 0:
        return np.zeros(0)
    roots = np.roots(c[: nonzero[-1] + 1][::-1])
    real: NDArray[np.float64] = roots[np.abs(roots.imag) <= 1e-6 * np.maximum(1.0, np.abs(roots))].real
    return real[np.isfinite(real)]


def without_noise(values: Sequence[float], tolerance: float | None = None) -> list[float]:
    """A float vector with its rounding noise taken out: entries below the rounding
    (``tolerance``, or 1e-12, relative to the largest entry or to 1) are 0."""
    noise = max(1e-12, tolerance or 0.0) * max(1.0, *(abs(c) for c in values))
    return [0.0 if abs(c) < noise else float(c) for c in values]
