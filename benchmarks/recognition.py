"""Benchmark: recognition (axis + profile) of surfaces of revolution in general position.

For each degree, a random profile ``F(s, w)`` is placed on a rational axis and moved by a
rational rotation (so every monomial of the given degree appears), then recognised by both
methods, timed inside the process. Run ``python -m benchmarks.recognition [--write]``; with
``--write`` the table replaces the recognition section of ``docs/benchmarks.md``.
"""

from __future__ import annotations

import random

from sympy.polys.domains import QQ

from benchmarks.report import median_time, run
from sorgui.engine.recognition.recognize import METHODS, recognize
from sorgui.samples import move, quaternion_rotation, rational_vector, revolve

DEGREES = (4, 6, 8, 10, 12, 16, 20, 25, 30)


def random_profile(degree: int, rng: random.Random) -> dict[tuple[int, int], int]:
    """A random ``F(s, w)`` of weighted degree ``degree`` (``s`` weight 1, ``w`` weight 2), with
    the leading terms that make the surface of that total degree."""
    profile = {
        (i, j): rng.randint(-9, 9) or 1
        for i in range(degree + 1)
        for j in range(degree // 2 + 1)
        if i + 2 * j <= degree and rng.random() < 0.7
    }
    profile[(degree, 0)] = 1
    profile[(degree % 2, degree // 2)] = 1
    return profile


def surface(degree: int, seed: int = 1):
    """A SOR of the given total degree in general position (deterministic for a seed)."""
    profile = random_profile(degree, random.Random(seed))
    f = revolve(profile, rational_vector((QQ(1, 2), QQ(-1, 3), 2)), rational_vector((3, -2, 5)))
    return move(f, quaternion_rotation((1, 2, -1, 3)), rational_vector((QQ(1, 5), 1, QQ(-2, 7))))


def recognised(f, method: str):
    """``recognize`` checked: the benchmark only counts correct answers."""
    report, _, _ = recognize(f, method)
    assert report.is_sor and report.profile.verified
    return report


def table(repeats: int) -> str:
    """The markdown table of median recognition times per degree and method."""
    rows = [
        "| degree | terms | " + " | ".join(f"{m} (s)" for m in METHODS) + " |",
        "|---:|---:|" + "---:|" * len(METHODS),
    ]
    for degree in DEGREES:
        f = surface(degree)
        cells = [f"{median_time(lambda m=m, f=f: recognised(f, m), repeats)[0]:.3f}" for m in METHODS]
        rows.append(f"| {degree} | {len(f)} | " + " | ".join(cells) + " |")
        print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("recognition", __doc__, table)
