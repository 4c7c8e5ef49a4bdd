"""Exact sample surfaces with known answers, for the property tests and the benchmarks.

Surfaces of revolution about a given axis (``revolve``), moved by rational rigid motions
(``quaternion_rotation``, ``move``), dense ones in general position (``general_position``),
and what a CAD system prints (``random_sor`` about an axis turned by a float quaternion,
``printed`` with ``k`` significant digits, ``rational_sor`` on a rational axis): docs/math.md §2,
§3 and §8. Nothing in sorgui itself imports this module.
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from fractions import Fraction

import numpy as np
from flint import fmpq, fmpq_mpoly_ctx
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from sorgui.engine.algebra.linalg import Vector, cross, dot, is_zero
from sorgui.engine.algebra.polys import XYZ, Poly, compose, poly_ring
from sorgui.engine.rounded import dense

PARAPLANECURVE_SEXTIC = {
    (6, 0): 1,
    (4, 2): 3,
    (2, 4): 3,
    (0, 6): 1,
    (4, 0): -4,
    (3, 1): -34,
    (2, 2): -7,
    (1, 3): 12,
    (0, 4): 6,
    (2, 0): 36,
    (1, 1): 36,
    (0, 2): 9,
}
"""The rational sextic ``x⁶ + 3x⁴y² + 3x²y⁴ + y⁶ − 4x⁴ − 34x³y − 7x²y² + 12xy³ + 6y⁴ + 36x² + 36xy
+ 9y²`` of the example of Singular's ``paraPlaneCurve`` (paraplanecurves.lib, ``f2`` at ``z = 1``),
as the coefficients of ``F(s, w)`` for :func:`revolve`: the slow tail of the full analysis at
degree 12 (docs/math.md §5)."""


def rational_vector(values: Sequence[object], K: Domain = QQ) -> Vector:
    """Integers, fractions, strings like ``"3/5"`` or ``QQ`` elements as a vector over ``K``."""
    out = []
    for v in values:
        if isinstance(v, (int, str, Fraction)):
            q = Fraction(v)
            v = QQ(q.numerator, q.denominator)
        out.append(K.convert(v))
    return tuple(out)


def revolve(
    profile: dict[tuple[int, int], int], point: Vector, direction: Vector, K: Domain = QQ, axis_distance: bool = False
) -> Poly:
    """``f = F(a·(p - c), |p - c|²)`` for ``F(s, w) = Σ F_ij s^i w^j``: a SOR about the axis (c, a).

    With ``axis_distance`` the second variable is the squared distance to the axis,
    ``|p - c|² - (a·(p - c))²/|a|²``, so ``F(s, w) = w - g(s)`` is the tube ``y² + z² = g(x)``.
    """
    R = poly_ring(XYZ, K)
    x, y, z = R.gens
    d = [x - point[0], y - point[1], z - point[2]]
    h = sum((direction[i] * d[i] for i in range(3)), start=R.zero)
    rho = sum((d[i] ** 2 for i in range(3)), start=R.zero)
    if axis_distance:
        rho = rho - h**2 * K.quo(K.one, dot(direction, direction))
    F = poly_ring(("s", "w"), K).from_dict({m: K.convert(c) for m, c in profile.items()})
    return compose(F, [h, rho])


def quaternion_rotation(q: Sequence[int]) -> list[list[Fraction]]:
    """The rational rotation matrix of the (non-normalised) integer quaternion ``q``."""
    a, b, c, d = q
    n = a * a + b * b + c * c + d * d
    m = [
        [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
        [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
        [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d],
    ]
    return [[Fraction(v, n) for v in row] for row in m]


def move(f: Poly, rotation: list[list[Fraction]], shift: Vector) -> Poly:
    """``g(p) = f(Rᵀ(p - t))``: the surface moved by the rigid motion ``p ↦ R p + t``."""
    R = f.ring
    K = R.domain
    gens = R.gens
    d = [gens[i] - shift[i] for i in range(3)]
    images = [
        sum(
            (K.convert(QQ(rotation[j][i].numerator, rotation[j][i].denominator)) * d[j] for j in range(3)), start=R.zero
        )
        for i in range(3)
    ]
    return compose(f, images)


def apply(rotation: list[list[Fraction]], v: Vector, K: Domain = QQ) -> Vector:
    """``R v``."""
    return tuple(
        sum(
            (K.convert(QQ(rotation[i][j].numerator, rotation[i][j].denominator)) * v[j] for j in range(3)), start=K.zero
        )
        for i in range(3)
    )


def same_line(point: Vector, direction: Vector, other_point: Vector, other_direction: Vector) -> bool:
    """Whether two (point, direction) pairs describe the same line."""
    diff = tuple(p - q for p, q in zip(point, other_point))
    return is_zero(cross(direction, other_direction)) and is_zero(cross(diff, direction))


def general_position(degree: int, seed: int, drop: tuple[tuple[int, int], ...] = ()) -> Poly:
    """``F(a·(p - c), |p - c|²) = 0`` with a random dense ``F`` (``i + 2j ≤ degree``), moved."""
    rng = random.Random(seed)
    profile = {
        (i, j): rng.randint(-5, 5) or 1
        for i in range(degree + 1)
        for j in range(degree // 2 + 1)
        if i + 2 * j <= degree and (i, j) not in drop
    }
    f = revolve(profile, rational_vector((QQ(1, 2), -1, 2)), rational_vector((2, -1, 3)))
    return move(f, quaternion_rotation((2, 1, -1, 1)), rational_vector((1, QQ(-1, 3), 0)))


def rotation(quaternion: np.ndarray) -> np.ndarray:
    """The rotation matrix of a quaternion (normalised here)."""
    a, b, c, d = quaternion / np.linalg.norm(quaternion)
    return np.array(
        [
            [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
            [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
            [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d],
        ]
    )


def random_sor(rng: np.random.Generator, degree: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A random surface of revolution of the given degree: dense array, axis direction, point."""
    n = rotation(rng.normal(size=4))[:, 2]
    point = rng.uniform(-2.0, 2.0, 3)
    one = dense.from_terms({(0, 0, 0): 1.0}, degree)
    h, rho = dense.linear_form(n, point), dense.squared_distance(point)
    total = dense.zeros(degree)
    for j, rj in enumerate(dense.powers(one, rho, degree // 2 + 1)):
        for term in dense.powers(rj, h, degree - 2 * j + 1):
            total += rng.uniform(-1.0, 1.0) * term
    return total, n, point


def sphere(center: np.ndarray, radius: float) -> np.ndarray:
    """``|p - c|² - r²``."""
    return dense.from_terms(dict(dense.squared_distance(center)), 2) - radius**2 * dense.from_terms({(0, 0, 0): 1.0}, 2)


def cylinder(direction: np.ndarray, point: np.ndarray, radius: float) -> np.ndarray:
    """``|p - c|² - (n·(p - c))² - r²`` for a unit ``n``."""
    rho = dense.from_terms(dict(dense.squared_distance(point)), 2)
    h = dense.from_terms(dict(dense.linear_form(direction, point)), 2)
    f: np.ndarray = (
        rho - dense.times(h, dense.linear_form(direction, point)) - radius**2 * dense.from_terms({(0, 0, 0): 1.0}, 2)
    )
    return f


def printed(array: np.ndarray, digits: int) -> str:
    """The polynomial as a CAD system prints it: every coefficient to ``digits`` significant digits."""
    return _print(array, f"+.{digits - 1}e")


def printed_fixed(array: np.ndarray, decimals: int) -> str:
    """The polynomial printed in fixed point, ``decimals`` digits after the point (``%.6f``)."""
    return _print(array, f"+.{decimals}f")


def _print(array: np.ndarray, spec: str) -> str:
    terms = []
    for i, j, k in zip(*np.nonzero(array)):
        monomial = "".join(f"*{v}^{e}" for v, e in zip("xyz", (i, j, k)) if e)
        terms.append(f"{array[i, j, k]:{spec}}{monomial}")
    return " ".join(terms)


def rational_sor(
    quaternion: tuple[int, int, int, int], point: tuple[Fraction, ...], profile: dict[tuple[int, int], Fraction]
) -> dict[tuple[int, int, int], Fraction]:
    """The exact ``Σ q_ij h^i ρ^j`` about the rational axis through ``point`` along the image of
    the z-axis under the rational rotation of an integer quaternion, as exact coefficients."""
    a, b, c, d = quaternion
    norm = a * a + b * b + c * c + d * d
    n = [
        Fraction(2 * (b * d + a * c), norm),
        Fraction(2 * (c * d - a * b), norm),
        Fraction(a * a - b * b - c * c + d * d, norm),
    ]
    ctx = fmpq_mpoly_ctx.get(("x", "y", "z"), "lex")
    gens = ctx.gens()
    shifted = [g - fmpq(p.numerator, p.denominator) for g, p in zip(gens, point)]
    h = sum((fmpq(v.numerator, v.denominator) * s for v, s in zip(n, shifted)), ctx.from_dict({}))
    rho = sum((s * s for s in shifted), ctx.from_dict({}))
    total = ctx.from_dict({})
    for (i, j), q in profile.items():
        total += fmpq(q.numerator, q.denominator) * h**i * rho**j
    return {(int(i), int(j), int(k)): Fraction(int(c.p), int(c.q)) for (i, j, k), c in total.to_dict().items()}


def printed_exact(coefficients: dict[tuple[int, int, int], Fraction], digits: int) -> str:
    """Exact coefficients divided by the largest, printed to ``digits`` significant digits."""
    top = max(abs(c) for c in coefficients.values())
    terms = []
    for (i, j, k), c in sorted(coefficients.items()):
        monomial = "".join(f"*{v}^{e}" for v, e in zip("xyz", (i, j, k)) if e)
        terms.append(f"{float(c / top):+.{digits - 1}e}{monomial}")
    return " ".join(terms)


# --- parametrizations (docs/math.md §13) ------------------------------------------------------


def map_text(components: Sequence[str]) -> str:
    """Three components as a user types a parametrization: ``x = …, y = …, z = …``."""
    return ", ".join(f"{name} = {c}" for name, c in zip("xyz", components))


def revolved_patch(
    radius: dict[int, Fraction | int],
    height: dict[int, Fraction | int],
    rotation: Sequence[Sequence[float | Fraction]] | None = None,
    shift: Sequence[float | Fraction] = (0, 0, 0),
    digits: int | None = None,
    extra: str = "",
) -> list[str]:
    """The surface of revolution ``R·(r(s)·(1 − t², 2t)/(1 + t²), z(s)) + shift`` of bidegree
    ``(max deg, 2)`` (``r``, ``z`` as coefficient dictionaries in ``s``), with ``extra`` added to
    the first component before the motion; each component is written over the denominator
    ``1 + t²``, every coefficient exact, or to ``digits`` significant digits (a CAD system's
    output, ``%.{digits-1}e``)."""
    motion = rotation or [[1, 0, 0], [0, 1, 0], [0, 0, 1]]

    def coefficient(c: float | Fraction) -> str:
        if digits is not None:
            return f"({float(c):.{digits - 1}e})"
        q = Fraction(c)
        return f"({q.numerator}/{q.denominator})" if q.denominator != 1 else f"({q.numerator})"

    r = " + ".join(f"{coefficient(Fraction(c))}*s^{e}" for e, c in sorted(radius.items()))
    z = " + ".join(f"{coefficient(Fraction(c))}*s^{e}" for e, c in sorted(height.items()))
    base = [f"(1 - t^2)*({r})" + (f" + (1 + t^2)*({extra})" if extra else ""), f"2*t*({r})", f"(1 + t^2)*({z})"]
    components = []
    for i in range(3):
        terms = [f"{coefficient(motion[i][j])}*({base[j]})" for j in range(3) if motion[i][j]]
        terms.append(f"{coefficient(shift[i])}*(1 + t^2)")
        components.append(f"({' + '.join(terms)})/(1 + t^2)")
    return components


def bicubic_patch(seed: int, size: int = 9) -> list[str]:
    """A random polynomial patch of bidegree ``(3, 3)`` (integer coefficients in ``±size``)."""
    rng = random.Random(seed)
    components = []
    for _ in range(3):
        terms = []
        for i in range(4):
            for j in range(4):
                c = rng.randint(-size, size)
                monomial = "".join(f"*{v}^{e}" if e > 1 else f"*{v}" for v, e in (("s", i), ("t", j)) if e)
                terms.append(f"{'-' if c < 0 else '+'} {abs(c)}{monomial}")
        components.append(" ".join(terms).lstrip("+ "))
    return components
