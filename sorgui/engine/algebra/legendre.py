"""Rational points of conics: Legendre's equation ``a·x² + b·y² + c·z² = 0`` over the integers
(docs/math.md §5, "A point of a conic").

A conic over ``QQ`` is parameterized by the lines through one of its rational points. When none
has small coordinates, Singular's ``paraPlaneCurve`` searches for one in ways whose time grows
fast with the size of the coefficients (a conic of 54-bit coefficients, from the nearest exact
surface of a rounded torus, took 11 s). Legendre's equation decides it instead:

* the coefficients are made square-free and pairwise coprime (flint's factorization), each
  change of coefficients a change of scale of one variable;
* by Legendre's theorem a nontrivial solution exists exactly when ``a, b, c`` are not all of one
  sign and ``−bc``, ``−ca``, ``−ab`` are squares modulo ``|a|``, ``|b|``, ``|c|``;
* then every vector of the lattice ``L`` of index ``|abc|`` cut out by the square roots
  (``y ≡ r_a·z mod a``, ``z ≡ r_b·x mod b``, ``x ≡ r_c·y mod c``) has ``a·x² + b·y² + c·z² ≡ 0``
  modulo ``abc``, and the shortest vectors of ``L`` for ``|a|·x² + |b|·y² + |c|·z²`` (flint's
  LLL on its Gram matrix) give a solution among their small combinations (Cremona and Rusin,
  "Efficient solution of rational conics", 2003).

Numbers are factored only as far as is quick (:func:`.factoring.quick_factorization`), so the
answer comes within about a second, or the equation is left undecided.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

from flint import fmpz, fmpz_mat

from .factoring import Factors, quick_factorization

SEARCH = 2
"""Coefficients ``|k| ≤`` this of the combinations of the reduced basis that are tried."""


def solve(a: int, b: int, c: int) -> tuple[bool | None, tuple[int, int, int] | None]:
    """Whether ``a·x² + b·y² + c·z² = 0`` (``a, b, c`` nonzero integers) has a nontrivial integer
    solution (Legendre's theorem; ``None`` when a coefficient cannot be factored quickly,
    :func:`.factoring.quick_factorization`), and one with gcd 1 when it has (``None`` if the small
    combinations of the reduced lattice hold none: never seen; the caller then looks elsewhere)."""
    form = _normal_form(a, b, c)
    if form is None:
        return None, None
    roots = _roots(form)
    if roots is None:
        return False, None
    (na, nb, nc), scales, _ = form
    for x, y, z in _short_vectors((na, nb, nc), roots):
        if na * x * x + nb * y * y + nc * z * z == 0:
            return True, _integers([scales[0] * x, scales[1] * y, scales[2] * z])
    return True, None


def has_solution(a: int, b: int, c: int) -> bool | None:
    """The first half of :func:`solve`: whether a nontrivial solution exists (``None``: undecided)."""
    return solve(a, b, c)[0]


def solution(a: int, b: int, c: int) -> tuple[int, int, int] | None:
    """The second half of :func:`solve`: a nontrivial solution, or ``None``."""
    return solve(a, b, c)[1]


_Form = tuple[tuple[int, int, int], tuple[Fraction, Fraction, Fraction], tuple[list[int], list[int], list[int]]]
"""Square-free, pairwise coprime coefficients, the scales ``k`` of the variables (a solution
``v`` of the new equation gives ``(k₁v₁, k₂v₂, k₃v₃)`` of the given one), and the primes of each
coefficient."""


def _normal_form(a: int, b: int, c: int) -> _Form | None:
    """The equation with square-free, pairwise coprime coefficients (``None`` when a coefficient
    is not factored): a square factor ``s²`` of a coefficient goes into its variable's scale, and
    a common prime ``p`` of two coefficients moves to the third (``p·(a'x² + b'y²) + c·z² = 0`` is
    ``a'(px)² + b'(py)² + pc·z² = 0`` divided by ``p``)."""
    signs = [1 if k > 0 else -1 for k in (a, b, c)]
    factors: list[Factors] = []
    for k in (a, b, c):
        found = quick_factorization(abs(k))
        if found is None:
            return None
        factors.append(found)
    scales = [Fraction(1)] * 3
    changed = True
    while changed:
        changed = False
        for i in range(3):
            for p, e in list(factors[i].items()):
                if e >= 2:
                    scales[i] /= p ** (e // 2)
                    factors[i][p] = e % 2
                    if not factors[i][p]:
                        del factors[i][p]
        for i, j in ((0, 1), (0, 2), (1, 2)):
            k = 3 - i - j
            for p in set(factors[i]) & set(factors[j]):
                del factors[i][p], factors[j][p]
                factors[k][p] = factors[k].get(p, 0) + 1
                scales[i] /= p
                scales[j] /= p
                changed = True
    coefficients = [sign * _product(f) for sign, f in zip(signs, factors)]
    primes = [sorted(f) for f in factors]
    return (
        (coefficients[0], coefficients[1], coefficients[2]),
        (scales[0], scales[1], scales[2]),
        (primes[0], primes[1], primes[2]),
    )


def _product(factors: Factors) -> int:
    out = 1
    for p, e in factors.items():
        out *= p**e
    return out


def _roots(form: _Form) -> tuple[int, int, int] | None:
    """``(r_a, r_b, r_c)``: ``r_a² ≡ −c/b (mod a)``, ``r_b² ≡ −a/c (mod b)``, ``r_c² ≡ −b/a (mod c)``
    for the square-free, pairwise coprime ``a, b, c``; ``None`` when one does not exist or the
    three have one sign (then the conic has no rational point)."""
    (a, b, c), _, primes = form
    if (a > 0) == (b > 0) == (c > 0):
        return None
    out = []
    for modulus, top, bottom, factors in ((a, -c, b, primes[0]), (b, -a, c, primes[1]), (c, -b, a, primes[2])):
        root = _square_root(top, bottom, abs(modulus), factors)
        if root is None:
            return None
        out.append(root)
    return out[0], out[1], out[2]


def _square_root(top: int, bottom: int, modulus: int, primes: list[int]) -> int | None:
    """A square root of ``top/bottom`` modulo the square-free ``modulus`` (coprime to both), the
    product of ``primes``, by the Chinese remainder theorem; ``None`` when there is none."""
    root, done = 0, 1
    for p in primes:
        value = top * pow(bottom, -1, p) % p
        if p == 2:
            r = value
        elif fmpz(value).jacobi(p) != 1:
            return None
        else:
            r = int(fmpz(value).sqrtmod(p))
        root += done * ((r - root) * pow(done, -1, p) % p)  # ≡ previous roots mod done, ≡ r mod p
        done *= p
    return root % modulus if modulus > 1 else 0


def _short_vectors(coefficients: tuple[int, int, int], roots: tuple[int, int, int]) -> list[tuple[int, int, int]]:
    """The small combinations of an LLL-reduced basis of the lattice ``L`` of the square roots,
    shortest first for ``|a|·x² + |b|·y² + |c|·z²``."""
    a, b, c = (abs(k) for k in coefficients)
    r_a, r_b, r_c = roots
    n = a * b * c
    idempotents = [_idempotent(m, n // m) for m in (a, b, c)]
    local = (
        [(1, 0, 0), (0, r_a, 1), (0, a, 0)],  # y ≡ r_a·z (mod a)
        [(1, 0, r_b), (0, 1, 0), (0, 0, b)],  # z ≡ r_b·x (mod b)
        [(r_c, 1, 0), (0, 0, 1), (c, 0, 0)],  # x ≡ r_c·y (mod c)
    )
    generators = [[e * g for g in v] for e, vectors in zip(idempotents, local) for v in vectors]
    generators += [[n if i == j else 0 for j in range(3)] for i in range(3)]
    basis = fmpz_mat(generators).hnf()
    rows = [[int(basis[i, j]) for j in range(3)] for i in range(3)]
    weights = (a, b, c)
    gram = fmpz_mat([[sum(w * u[k] * v[k] for k, w in enumerate(weights)) for v in rows] for u in rows])
    _, transform = gram.lll(True, 0.99, 0.51, "gram")  # the arguments: transform, delta, eta, rep
    reduced = [[sum(int(transform[i, k]) * rows[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    found = []
    for k in itertools.product(range(-SEARCH, SEARCH + 1), repeat=3):
        if any(k):
            v = tuple(sum(k[i] * reduced[i][j] for i in range(3)) for j in range(3))
            found.append((sum(w * x * x for w, x in zip(weights, v)), v))
    found.sort()
    return [(v[0], v[1], v[2]) for _, v in found]


def _idempotent(m: int, rest: int) -> int:
    """``e ≡ 1 (mod m)``, ``e ≡ 0 (mod rest)`` for coprime ``m`` and ``rest``."""
    if m == 1:
        return 0
    return rest * pow(rest, -1, m) % (m * rest)


def _integers(values: list[Fraction]) -> tuple[int, int, int]:
    """Rationals scaled to integers with gcd 1 (a projective point)."""
    common = math.lcm(*(v.denominator for v in values))
    ints = [int(v * common) for v in values]
    g = math.gcd(*ints)
    return ints[0] // g, ints[1] // g, ints[2] // g
