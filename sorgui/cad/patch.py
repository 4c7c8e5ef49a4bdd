"""A verified real parameterization as rational Bézier patches over the window's parameter box.

``X(s, t) = (N₁, N₂, N₃)/D`` over ``[s₀, s₁] × [t₀, t₁]`` (:data:`sorgui.render.PATCH_RANGE`, the
box the 3D view draws) is, exactly, the tensor-product rational Bézier patch whose weights are
the Bernstein coefficients of ``D`` and whose weighted poles are those of ``N`` (docs/math.md
§11): the Bernstein form is taken along ``t`` and then along ``s`` (:func:`.geometry.bernstein`
on the segment from ``(a, 1)`` to ``(b, 1)``). Where the weights of a box do not share one sign
it is cut into four, down to a limit; the small boxes about a pole of the map are left out.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
import numpy as np
import sympy

from sorgui.engine.results import Parametrization
from sorgui.engine.values import read_expression
from sorgui.render import PATCH_RANGE

from .geometry import DIGITS, MAX_DEGREE, CadGeometryError, Form, bernstein, over_one_denominator, real_number

Grid = list[list[mpmath.mpf]]
"""``c[i][j]``: the coefficient of ``s^i·t^j``."""

SPLITS = 4
"""How many times a box is cut into four before a sign change of ``D`` is taken for a pole (a box
of 1/16 of the side left out)."""


@dataclass(frozen=True)
class PatchMap:
    """The numerators and the common denominator of a parameterization as coefficient grids."""

    numerators: tuple[Grid, Grid, Grid]
    denominator: Grid


@dataclass(frozen=True)
class BezierPatch:
    """Poles ``(m + 1, n + 1, 3)`` and positive weights ``(m + 1, n + 1)`` of one patch."""

    poles: np.ndarray
    weights: np.ndarray


def patch_map(param: Parametrization) -> PatchMap:
    """The coordinates of ``param`` over one denominator, as grids of 40-digit numbers."""
    s, t = (sympy.Symbol(name) for name in param.parameters)
    polys = [sympy.Poly(e, s, t) for e in over_one_denominator([read_expression(c) for c in param.coordinates])]
    m = max(p.degree(s) for p in polys)
    n = max(p.degree(t) for p in polys)
    if max(m, n) > MAX_DEGREE:
        raise CadGeometryError(f"the parameterization has degree {max(m, n)} > {MAX_DEGREE} in one parameter")
    grids = [_grid(p, m, n) for p in polys]
    return PatchMap((grids[0], grids[1], grids[2]), grids[3])


def _grid(poly: sympy.Poly, m: int, n: int) -> Grid:
    grid = [[mpmath.mpf(0)] * (n + 1) for _ in range(m + 1)]
    for (i, j), c in poly.terms():
        grid[i][j] = real_number(c)
    return grid


def _tensor_bernstein(grid: Grid, s_box: tuple[float, float], t_box: tuple[float, float]) -> Grid:
    along_t = [bernstein(row, (t_box[0], 1.0), (t_box[1], 1.0)) for row in grid]
    columns: list[Form] = [list(col) for col in zip(*along_t)]
    along_s = [bernstein(col, (s_box[0], 1.0), (s_box[1], 1.0)) for col in columns]
    return [list(row) for row in zip(*along_s)]


def bezier_patches(param: Parametrization, box: tuple[float, float] = PATCH_RANGE) -> list[BezierPatch]:
    """The patches covering ``box × box`` of ``param`` (one, or more where ``D``'s Bernstein
    coefficients change sign), without the small boxes about its poles."""
    patches = _patches(patch_map(param), box, box, 0)
    if not patches:
        raise CadGeometryError("the parameterization has poles all over the drawn parameter box")
    return patches


def _patches(
    mapping: PatchMap, s_box: tuple[float, float], t_box: tuple[float, float], depth: int
) -> list[BezierPatch]:
    weights = _tensor_bernstein(mapping.denominator, s_box, t_box)
    values = np.array([[float(w) for w in row] for row in weights])
    if not (np.all(values > 0) or np.all(values < 0)):
        if depth >= SPLITS:
            return []
        s_mid, t_mid = sum(s_box) / 2, sum(t_box) / 2
        return [
            patch
            for s_part in ((s_box[0], s_mid), (s_mid, s_box[1]))
            for t_part in ((t_box[0], t_mid), (t_mid, t_box[1]))
            for patch in _patches(mapping, s_part, t_part, depth + 1)
        ]
    with mpmath.workdps(DIGITS):
        coordinates = [_tensor_bernstein(g, s_box, t_box) for g in mapping.numerators]
        poles = np.array(
            [
                [[float(coordinates[k][i][j] / weights[i][j]) for k in range(3)] for j in range(len(weights[0]))]
                for i in range(len(weights))
            ]
        )
    weights_out = np.abs(values)
    return [BezierPatch(poles, weights_out / weights_out.max())]
