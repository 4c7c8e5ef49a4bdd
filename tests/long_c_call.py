"""An equation whose analysis sits in one long C call: the product of three dense random
polynomials of degree 15 with 300-digit coefficients. Its factors stage is one flint
factorization of a degree-45 polynomial that takes 10 to 20 s on the project's machine, where no
Python signal handler and no cancel event is looked at; the tests end it from outside."""

from __future__ import annotations

import random


def factored_product(seed: int = 2, degree: int = 15, digits: int = 300, factors: int = 3) -> str:
    rng = random.Random(seed)
    bound = 10**digits

    def dense() -> str:
        terms = [
            f"{rng.randint(-bound, bound)}*x^{i}*y^{j}*z^{k}"
            for i in range(degree + 1)
            for j in range(degree + 1 - i)
            for k in range(degree + 1 - i - j)
            if rng.random() < 0.5
        ]
        return "(" + "+".join(terms) + ")"

    return "*".join(dense() for _ in range(factors))
