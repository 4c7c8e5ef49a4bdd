"""The canal test on lines, and the canal verdicts that need no SMAT (docs/math.md §9).

On deterministic random lines the focal-sheet condition of :mod:`.focal` is tested exactly;
one line on which it fails is the witness of **not canal**. A plane is canal, and so is a
surface of revolution of high degree, by its symmetry algebra. These verdicts need python-flint
only: :func:`verdict_without_smat` gives them for the recognition-only path over ``QQ``
(:mod:`.rational_path`), and :mod:`.verdict` builds on the same pieces (:func:`factor_verdict`,
:func:`assemble`) when the spine must be computed.
"""

from __future__ import annotations

import random
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace

from flint import fmpq_mpoly, fmpq_poly

from ..algebra.rationals import signed_sum, squarefree, times_text
from ..errors import AnalysisError, Cancelled, SorguiError
from ..recognition.symmetry import PLANE_CANAL, SOR_EVIDENCE
from ..results import Canal, CanalEvidence
from .focal import (
    DEVELOPABLE,
    Derivatives,
    LineTest,
    SmatSample,
    UnluckyLine,
    line_test,
)

LINES = 3
"""Canal lines tested before the SMAT is computed (one failing line already decides)."""

MAX_LINES = 60
"""Lines tried at most (unlucky lines are skipped)."""

SEED = 20261127

MAX_DEGREE = 30
"""Surfaces of higher degree are not analysed (the line test costs grow with the degree)."""

SOR_SPINE_DEGREE = 8
"""Above this degree the SMAT of a surface of revolution is not computed: the symmetry algebra
already certifies it, and its spine is the axis."""


class NotCanal(Exception):
    """A line on which the canal condition fails: the witness of "not canal"."""

    def __init__(self, test: LineTest) -> None:
        super().__init__("not canal")
        self.test = test


@dataclass
class CanalClock:
    """Times the canal stage's steps and stops at a set ``cancel`` event."""

    cancel: threading.Event | None
    timings: list[tuple[str, float]] = field(default_factory=list)

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        if self.cancel is not None and self.cancel.is_set():
            raise Cancelled("the analysis was cancelled")
        start = time.perf_counter()
        try:
            yield
        finally:
            self.timings.append((name, time.perf_counter() - start))


class Lines:
    """Deterministic random lines and their tests; every canal line is kept for the SMAT."""

    def __init__(self, f: fmpq_mpoly, seed: int) -> None:
        self.D = Derivatives(f)
        self.rnd = random.Random(seed)
        self.tried = 0
        self.canal: list[LineTest] = []

    def next(self) -> LineTest:
        while self.tried < MAX_LINES:
            self.tried += 1
            point = tuple(self.rnd.randint(-7, 7) for _ in range(3))
            direction = tuple(self.rnd.randint(-7, 7) or 1 for _ in range(3))
            try:
                test = line_test(self.D, point, direction)
            except UnluckyLine:
                continue
            if not test.canal:
                raise NotCanal(test)
            if self.canal and test.branch != self.canal[0].branch:
                continue
            self.canal.append(test)
            return test
        raise AnalysisError(f"no usable line among {MAX_LINES} for the canal test")

    def sample(self, points: int) -> SmatSample:
        while SmatSample(tuple(self.canal)).point_count < points:
            self.next()
        return SmatSample(tuple(self.canal))


def factor_verdict(h: fmpq_mpoly, clock: CanalClock, is_sor: bool | None) -> tuple[Canal | None, Lines | None]:
    """The verdict for one irreducible factor over ``QQ`` when it needs no SMAT (a plane, a
    surface of revolution above :data:`SOR_SPINE_DEGREE`, a witness line, or no usable line),
    else ``None`` and the :data:`LINES` canal lines tested."""
    degree = int(h.total_degree())
    if degree == 1:
        return PLANE_CANAL, None
    if is_sor and degree > SOR_SPINE_DEGREE:
        # Above that degree a surface is neither a Dupin cyclide, nor a cone or cylinder, nor a pipe
        # with rotational symmetry (its spine would be the axis or a circle about it: a cylinder or
        # a torus): the symmetry algebra's certificate is the whole answer, no line is needed.
        return Canal(
            True, "canal: a surface of revolution", ("revolution",), certificate=SOR_EVIDENCE, notes=(SOR_NOTE,)
        ), None
    lines = Lines(h, SEED)
    try:
        with clock.stage("canal test"):
            for _ in range(LINES):
                lines.next()
    except NotCanal as witness:
        return not_canal(witness.test, lines.tried), lines
    except AnalysisError as error:
        return undecided(lines, error), lines
    return None, lines


SOR_NOTE = (
    "the spine is the axis; the SMAT of a surface of revolution is computed only for quadrics and for "
    f"Dupin cyclides up to degree {SOR_SPINE_DEGREE}"
)


def undecided(lines: Lines, error: SorguiError) -> Canal:
    """No verdict: the canal condition held on the lines tested, and the next step failed."""
    return Canal(
        None,
        f"undecided: the canal condition holds on {len(lines.canal)} lines, "
        f"but the spine could not be computed ({error.message})",
        lines_tested=lines.tried,
    )


def not_canal(test: LineTest, tried: int) -> Canal:
    """The verdict "not canal" with its witness line."""
    F = test.F
    x, y, z = test.point
    dx, dy, dz = test.direction
    witness = CanalEvidence(
        method="line",
        statement=(
            "on the line point + τ·direction the canal condition fails exactly: "
            + (
                "the finite focal root does not satisfy C"
                if test.branch == DEVELOPABLE
                else "R = a₂C₀² − a₁C₀C₁ + a₀C₁² is not 0 modulo F"
            )
            + f" (F of degree {F.degree()}, the square-free part of f on the line)"
        ),
        verified=True,
        point=(str(x), str(y), str(z)),
        direction=(str(dx), str(dy), str(dz)),
        restriction=univariate_str(F, "tau"),
    )
    return Canal(False, "not canal", witness=witness, lines_tested=tried)


def assemble(parts: list[Canal], is_sor: bool | None, clock: CanalClock, notes: tuple[str, ...] = ()) -> Canal:
    """The verdict of ``f`` from those of its irreducible factors over ``QQ``; ``is_sor`` (the
    symmetry algebra's answer) decides the ``revolution`` kind and is cross-checked."""
    result = parts[0] if len(parts) == 1 else _combine(parts, is_sor)
    if is_sor and result.is_canal is None:
        result = replace(
            result,
            is_canal=True,
            status="canal: a surface of revolution",
            kinds=tuple(sorted(set(result.kinds) | {"revolution"})),
            certificate=SOR_EVIDENCE,
        )
    all_notes = list(result.notes) + list(notes)
    if is_sor is not None and result.is_canal is not None and is_sor != ("revolution" in result.kinds):
        all_notes.append("the symmetry algebra and the canal spine disagree about revolution (internal inconsistency)")
    return replace(result, timings=tuple(clock.timings), notes=tuple(all_notes))


def verdict_without_smat(f: fmpq_mpoly, cancel: threading.Event | None = None) -> Canal | None:
    """The canal verdict of ``f ∈ QQ[x, y, z]``, not a surface of revolution, when no factor
    needs its SMAT (as :func:`.verdict.analyze_canal` gives it), else ``None``."""
    g = squarefree(f)  # a power is judged by its square-free part's degree
    if g.total_degree() > MAX_DEGREE:
        return Canal(None, f"not analysed: degree above {MAX_DEGREE}")
    clock = CanalClock(cancel)
    _, factors = g.factor()
    parts = []
    for h, _ in factors:
        verdict, _ = factor_verdict(h, clock, False if len(factors) == 1 else None)
        if verdict is None:
            return None
        parts.append(verdict)
    return assemble(parts, False, clock)


def _combine(parts: list[Canal], is_sor: bool | None) -> Canal:
    """The verdict of a reducible surface from its factors over ``QQ``."""
    if any(p.is_canal is False for p in parts):
        bad = next(p for p in parts if p.is_canal is False)
        return Canal(
            False,
            "not canal: a component is not canal",
            witness=bad.witness,
            lines_tested=sum(p.lines_tested for p in parts),
        )
    if any(p.is_canal is None for p in parts):
        return Canal(None, "undecided for a component", lines_tested=sum(p.lines_tested for p in parts))
    kinds = set(parts[0].kinds)
    for p in parts[1:]:
        kinds &= set(p.kinds)
    kinds.discard("revolution")
    if is_sor:
        kinds.add("revolution")
    return Canal(
        True,
        f"canal: each of the {len(parts)} components is canal",
        tuple(sorted(kinds)),
        tuple(f for p in parts for f in p.families),
        CanalEvidence("components", "; ".join(p.certificate.statement for p in parts if p.certificate), True),
        parametrizations=tuple(q for p in parts for q in p.parametrizations),
        lines_tested=sum(p.lines_tested for p in parts),
        notes=tuple(n for p in parts for n in p.notes),
    )


def univariate_str(F: fmpq_poly, name: str) -> str:
    """``F`` as sympy prints it as an expression in ``name`` (``3*tau**2 - tau/2 + 1``), which
    sympy and the project's parser read back."""
    terms: list[tuple[bool, str]] = []
    coefficients = F.coeffs()
    for i in range(len(coefficients) - 1, -1, -1):
        c = coefficients[i]
        if not c:
            continue
        negative, c = c < 0, abs(c)
        body = str(c) if i == 0 else times_text(c, name if i == 1 else f"{name}**{i}")
        terms.append((negative, body))
    if len(terms) == 2 and terms[0][0] and not terms[1][0] and coefficients[0]:
        terms.reverse()  # sympy's special case: ``1 - tau``, not ``-tau + 1``
    return signed_sum(terms)
