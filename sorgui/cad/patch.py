"""A verified real parameterization as rational Bézier patches over the window's parameter box.

``X(s, t) = (N₁, N₂, N₃)/D`` over ``[s₀, s₁] × [t₀, t₁]`` (:data:`sorgui.render.PATCH_RANGE`, the
box the 3D view draws) is, exactly, the tensor-product rational Bézier patch whose weights are
the Bernstein coefficients of ``D`` and whose weighted poles are those of ``N`` (docs/math.md
§11): the Bernstein form is taken along ``t`` and then along ``s`` (:func:`.geometry.bernstein`
on the segment from ``(a, 1)`` to ``(b, 1)``). Where the weights of a box do not share one sign
it is cut into four, down to a limit; the small boxes about a pole of the map are left out.

A profile turned about the axis covers the surface twice where the profile's distance to the
axis ``ρ(t)`` takes both signs (``(s, t)`` and ``(s', t')`` with ``ρ(t') = −ρ(t)`` meet): only
the ``t`` where ``ρ ≥ 0`` are kept. A box whose normal ``X_s × X_t`` turns against ``∇f``
inside it (a fold of the map, as at a cone's apex) is cut into four until it does not, and
each patch says which way it points.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import mpmath
import numpy as np
import numpy.polynomial.polynomial as P
import sympy

from sorgui.engine.stage_results import Parametrization
from sorgui.engine.values import Terms, read_expression
from sorgui.render import PATCH_RANGE
from sorgui.render.sampling import value_and_gradient

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
    """Poles ``(m + 1, n + 1, 3)`` and positive weights ``(m + 1, n + 1)`` of one patch;
    ``turned``: its normal ``X_s × X_t`` points against ``∇f``."""

    poles: np.ndarray
    weights: np.ndarray
    turned: bool = False


ORIENTING_SPLITS = 3
"""How many times a box whose normal turns against ``∇f`` inside it is cut into four."""

ROTATED = "rotated profile"
"""The engine's name of a parameterization that turns a profile about the axis by ``s = tan(θ/2)``."""


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


def bezier_patches(
    param: Parametrization, terms: Terms | None = None, box: tuple[float, float] = PATCH_RANGE
) -> list[BezierPatch]:
    """The patches covering ``box × box`` of ``param`` once (for a turned profile, the ``t``
    where ``ρ ≥ 0``), without the small boxes about its poles, each oriented along ``∇f``
    (``terms``) where that is known."""
    mapping = patch_map(param)
    floats = _FloatMap(mapping)
    t_boxes = floats.outer_profile(box) if param.method == ROTATED else [box]
    patches = []
    for t_box in t_boxes:
        for s_part, t_part, sign in floats.oriented(box, t_box, terms, 0):
            patches += [dataclasses.replace(p, turned=sign < 0) for p in _patches(mapping, s_part, t_part, 0)]
    if not patches:
        raise CadGeometryError("the parameterization has poles all over the drawn parameter box")
    return patches


class _FloatMap:
    """The map ``X(s, t)`` in floats (coefficient grids), for signs: of ``ρ(t)`` and of ``n·∇f``."""

    def __init__(self, mapping: PatchMap) -> None:
        grids = [*mapping.numerators, mapping.denominator]
        self.grids = [np.array([[float(c) for c in row] for row in g]) for g in grids]

    def values(self, s: np.ndarray, t: np.ndarray) -> np.ndarray:
        """``X`` at the points ``(s, t)``: ``(n, 3)``."""
        n = [P.polyval2d(s, t, g) for g in self.grids]
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.column_stack([n[0] / n[3], n[1] / n[3], n[2] / n[3]])

    def normals(self, s: np.ndarray, t: np.ndarray) -> np.ndarray:
        """``(N_s·D − N·D_s) × (N_t·D − N·D_t)``: ``X_s × X_t`` times ``D⁴ > 0`` (not finite where
        the products leave floating point: far out on a wide parameter box, those points say
        nothing)."""
        with np.errstate(over="ignore", invalid="ignore"):
            value = [P.polyval2d(s, t, g) for g in self.grids]
            ds = [P.polyval2d(s, t, P.polyder(g, axis=0)) for g in self.grids]
            dt = [P.polyval2d(s, t, P.polyder(g, axis=1)) for g in self.grids]
            xs = np.column_stack([ds[k] * value[3] - value[k] * ds[3] for k in range(3)])
            xt = np.column_stack([dt[k] * value[3] - value[k] * dt[3] for k in range(3)])
            return np.asarray(np.cross(xs, xt))

    def outer_profile(self, box: tuple[float, float]) -> list[tuple[float, float]]:
        """The ``t``-intervals of ``box`` where the profile ``X(0, t)`` lies on one side of the
        axis (``ρ(t) > 0``, the side of the point farthest from it). The axis is where the
        circle through ``X(0, t)``, ``X(±1, t)`` (angles 0 and ±90°) has its centre."""
        t = np.linspace(box[0], box[1], 801)
        radial = self._radial(t)
        lengths = np.linalg.norm(radial, axis=1)
        if not np.isfinite(lengths).any():
            return [box]
        reference = radial[int(np.nanargmax(np.where(np.isfinite(lengths), lengths, -1.0)))]

        def rho(at: float) -> float:
            with np.errstate(invalid="ignore", over="ignore"):
                return float(self._radial(np.array([at]))[0] @ reference)

        with np.errstate(invalid="ignore", over="ignore"):
            values = radial @ reference
        finite = np.isfinite(values)
        positive = values > 0
        edges = [box[0]]
        for k in np.flatnonzero(finite[:-1] & finite[1:] & (positive[:-1] != positive[1:])):
            low, high = float(t[k]), float(t[k + 1])
            for _ in range(60):
                if (rho((low + high) / 2) > 0) == positive[k]:
                    low = (low + high) / 2
                else:
                    high = (low + high) / 2
            edges.append((low + high) / 2)
        edges.append(box[1])
        out = [
            (a, b) for a, b in zip(edges[:-1], edges[1:]) if b - a > 1e-9 * (box[1] - box[0]) and rho((a + b) / 2) > 0
        ]
        return out or [box]

    def _radial(self, t: np.ndarray) -> np.ndarray:
        zero, one = np.zeros_like(t), np.ones_like(t)
        start, left, right = self.values(zero, t), self.values(one, t), self.values(-one, t)
        with np.errstate(invalid="ignore", over="ignore"):
            radial: np.ndarray = start - (left + right) / 2
        return radial

    def oriented(
        self, s_box: tuple[float, float], t_box: tuple[float, float], terms: Terms | None, depth: int
    ) -> list[tuple[tuple[float, float], tuple[float, float], float]]:
        """The box (cut into four where the sign of ``n·∇f`` changes inside it, at most
        :data:`ORIENTING_SPLITS` times) and the sign of ``n·∇f`` on each part."""
        if terms is None:
            return [(s_box, t_box, 1.0)]
        grid = (np.arange(7) + 0.5) / 7
        s = np.repeat(s_box[0] + (s_box[1] - s_box[0]) * grid, 7)
        t = np.tile(t_box[0] + (t_box[1] - t_box[0]) * grid, 7)
        points, normals = self.values(s, t), self.normals(s, t)
        good = np.all(np.isfinite(points), axis=1) & np.all(np.isfinite(normals), axis=1)
        if not good.any():
            return [(s_box, t_box, 1.0)]
        _, gradients = value_and_gradient(terms, points[good], normalise=True)
        agreement = np.einsum("ij,ij->i", _unit(normals[good]), _unit(gradients))
        signs = np.sign(agreement[np.abs(agreement) > 1e-6])
        if len(signs) == 0:
            return [(s_box, t_box, 1.0)]
        if np.all(signs == signs[0]) or depth >= ORIENTING_SPLITS:
            return [(s_box, t_box, 1.0 if signs.sum() >= 0 else -1.0)]
        s_mid, t_mid = sum(s_box) / 2, sum(t_box) / 2
        return [
            part
            for s_part in ((s_box[0], s_mid), (s_mid, s_box[1]))
            for t_part in ((t_box[0], t_mid), (t_mid, t_box[1]))
            for part in self.oriented(s_part, t_part, terms, depth + 1)
        ]


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


def _unit(vectors: np.ndarray) -> np.ndarray:
    """Each row divided by its length, scaled first by its largest entry (a normal of 1e200
    would overflow when squared)."""
    scaled = vectors / np.maximum(np.max(np.abs(vectors), axis=1, keepdims=True), 1e-300)
    return np.asarray(scaled / np.maximum(np.linalg.norm(scaled, axis=1, keepdims=True), 1e-300))
