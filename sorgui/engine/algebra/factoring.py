"""Integers factored only as far as is quick (docs/math.md §5, "A point of a conic").

Exact steps that need an integer's primes (Legendre's theorem, the square-free part of a
radicand) meet integers of hundreds of digits when the input is a rounded equation's nearest
exact surface. flint factors 48 digits in at most about 0.2 s and 60 digits in seconds, and
beyond that can take any time: such a step is left undecided rather than run for minutes.
"""

from __future__ import annotations

from flint import fmpz

MAX_BITS = 160
"""A number of at most this many bits (48 digits) is factored whole: flint takes at most about
0.2 s (a 56-digit one 1.5 s). A larger one only loses its factors of up to :data:`SMOOTH_BITS`
bits: what is left must then be prime or small enough, else it is not factored."""
SMOOTH_BITS = 32
"""The size of the prime factors looked for in a number beyond :data:`MAX_BITS` (a few tens of
milliseconds at 250 bits): the coefficients of conics from rounded input are products of many
small primes and one or two large ones."""
LARGEST_BITS = 1200
"""No number of more bits is factored at all (looking for its small primes takes 0.09 s at 1,200
bits, 0.6 s at 3,000)."""

Factors = dict[int, int]
"""An integer's prime factorization, ``{prime: exponent}``."""


def quick_factorization(m: int, whole_bits: int = MAX_BITS) -> Factors | None:
    """The prime factorization of ``m > 0``, or ``None`` when it is not found quickly: whole up to
    ``whole_bits`` bits; beyond, up to :data:`LARGEST_BITS`, the factors of up to
    :data:`SMOOTH_BITS` bits and a cofactor that is proved prime or is factored whole."""
    if m.bit_length() <= whole_bits:
        return {int(p): int(e) for p, e in fmpz(m).factor()}
    if m.bit_length() > LARGEST_BITS:
        return None
    found: Factors = {}
    for p, e in fmpz(m).factor_smooth(SMOOTH_BITS):
        if p.bit_length() <= SMOOTH_BITS or p.is_prime():
            found[int(p)] = found.get(int(p), 0) + int(e)
        elif p.bit_length() <= whole_bits:
            for q, f in p.factor():
                found[int(q)] = found.get(int(q), 0) + int(e) * int(f)
        else:
            return None
    return found
