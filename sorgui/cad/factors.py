"""A reducible surface of revolution, one factor at a time.

A profile fitted to the whole zero set of ``f = g₁·g₂`` strays where the factors cross (the
traced profile turns from one factor's curve to the other's there), so a reducible surface whose
factors are not all analytic (:func:`.geometry.analytic_surfaces` takes those) is built as the
union of its factors' parts: each factor is its own analysis (its recognition, its polynomial)
with the scene's points that lie on it, and gets its own route. The parts cross where the
factors do; they are sewn apart (:func:`.sewing.assemble`), as a CAD kernel keeps two surfaces
that meet.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from sorgui.engine.results import Analysis
from sorgui.engine.values import Terms, polynomial_terms
from sorgui.render import ClipBox, ClipSphere, LineData, MeshData
from sorgui.render.geometry import runs
from sorgui.render.sampling import first_order_distance


@dataclass(frozen=True)
class FactorScene:
    """What a CAD export needs of a scene (:class:`.model.Scene`), for one factor: the scene's
    ball and box, and the points of its traced profile and of its mesh that lie on the factor."""

    region: ClipSphere
    profile_curve: LineData
    box: ClipBox | None
    surface: MeshData


def factor_parts(
    analysis: Analysis, region: ClipSphere, box: ClipBox | None, profile: LineData, surface: MeshData
) -> list[tuple[Analysis, FactorScene]]:
    """Each distinct factor of ``analysis`` as an analysis of its own (without the maps and the
    rationality of the whole, which are not the factor's), with the points of ``profile`` and
    ``surface`` nearer its zero set than any other factor's (by the first-order distance
    ``|g|/|∇g|``). A factor that owns no point of the mesh is left out: it misses the region."""
    factors = analysis.factors
    terms = [polynomial_terms(factor.polynomial) for factor in factors]
    owners = _owners(terms, surface.points)
    polylines = profile.polylines()
    lines = [_owners(terms, line) if len(line) else np.zeros(0, dtype=np.int64) for line in polylines]
    parts = []
    for index, factor in enumerate(factors):
        on = owners == index
        if not on.any():
            continue
        own = dataclasses.replace(
            analysis,
            recognition=factor.recognition,
            factors=(dataclasses.replace(factor, multiplicity=1),),
            squarefree=factor.polynomial,
            rationality=None,
            parametrizations=(),
        )
        pieces = [piece for line, owner in zip(polylines, lines) for piece in runs(line, owner == index)]
        mesh = dataclasses.replace(
            surface,
            points=surface.points[on],
            faces=np.zeros(0, dtype=np.int64),
            normals=surface.normals[on],
            side=surface.side[on],
        )
        parts.append((own, FactorScene(region, LineData.from_polylines(pieces), box, mesh)))
    return parts


def _owners(terms: list[Terms], points: np.ndarray) -> np.ndarray:
    """For each point, the index of the factor whose zero set is nearest (a point where two
    factors cross goes to the first)."""
    distances = np.stack([np.nan_to_num(first_order_distance(t, points), nan=0.0) for t in terms])
    owners: np.ndarray = np.argmin(distances, axis=0)
    return owners
