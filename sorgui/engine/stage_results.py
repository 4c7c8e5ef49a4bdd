"""The result objects of the stages after the recognition: the rationality analysis (Table 1),
the real locus, the parameterizations, the sphere families of a canal surface, the base curve of
a cone or a cylinder, and what a typed parametrization says of itself. Frozen dataclasses of
strings and numbers, as in :mod:`.results`, which holds the recognition's objects and the whole
:class:`~.results.Analysis` with its JSON form.

Apart from :mod:`.results` because making a frozen dataclass costs about a millisecond (its
methods are compiled when the class is made): a recognition-only process, which never makes
these objects, does not load this module (docs/benchmarks.md, "Start of a process").
"""

from __future__ import annotations

from dataclasses import dataclass

Triple = tuple[str, str, str]
"""Three exact numbers or expressions, as strings (as :data:`.results.Triple`)."""


@dataclass(frozen=True)
class Rationality:
    """The rationality analysis of docs/math.md §5 (the paper's Section 3 and Table 1).

    ``None`` in a field means "not computed" or "undecided"; ``status`` says which, and
    ``notes`` explain limits met on the way (a time limit, a field Singular refuses).
    """

    status: str
    profile_reducible: bool | None = None
    absolute_factors: tuple[str, ...] = ()
    genus_profile: int | None = None
    genus_profile_square: int | None = None
    table_row: int | None = None
    complex_rational: bool | None = None
    unirational: bool | None = None
    real_rational: bool | None = None
    square_parametrization: tuple[str, str] | None = None
    tubular_surface: str | None = None
    h: str | None = None
    tau: Triple | None = None
    real_roots_of_h: int | None = None
    notes: tuple[str, ...] = ()
    given_map_proper: bool | None = None
    """``True`` when a proper map found here is the typed parametrization's after bijections of
    the parameters, and was left out for it (docs/math.md §6, "The typed map"): the typed map
    is then proper too. ``None`` otherwise (no typed map, or none such)."""


@dataclass(frozen=True)
class RealLocus:
    """What the real points of ``X`` are (docs/math.md §3.4): the surface turned from the profile.

    ``kind`` is ``"empty"``, ``"points"``, ``"curve"`` or ``"surface"`` (the largest piece;
    ``dimension`` -1, 0, 1 or 2), or ``"undecided"`` (``dimension`` ``None``) when the profile is
    too large for the exact decision. Below a surface the pieces are counted exactly: ``points``
    isolated real points, ``circles`` circles about the axis, ``axis_line`` whether the whole
    axis lies on ``X``. ``None`` means not counted (above a surface, or no unique axis).
    """

    kind: str
    dimension: int | None
    points: int | None = None
    circles: int | None = None
    axis_line: bool | None = None


GIVEN_MAP = "the given parametrization"
"""The ``method`` of a typed parametrization's own map, listed first among the maps."""


@dataclass(frozen=True)
class Parametrization:
    """A rational parameterization of ``X`` in the original coordinates, checked by substitution.

    ``verification`` says how: substituted into ``f`` itself, or into ``f`` written in the axis
    frame (``f(c + s·a + y·u + z·w) = P²(s, y² + |a|²z²)``, itself an exact identity).
    """

    coordinates: Triple
    parameters: tuple[str, str]
    field: str
    real: bool
    proper: bool | None
    method: str
    verified: bool
    verification: str = "substituted into f"


@dataclass(frozen=True)
class CanalFamily:
    """One sphere family of a canal surface: its SMAT curve ``(m, ρ)`` (docs/math.md §9).

    ``equations`` generate the SMAT ideal in ``m1, m2, m3, r`` (``r`` is ``ρ``, the squared
    radius); ``spine_equations`` the spine's ideal in ``m1, m2, m3``; ``plane_model`` is
    ``G(u, v)``, the image under ``u, v`` = ``projection`` (integer forms in ``m1, m2, m3, r``).
    ``parametrization`` is ``m(t)`` and ``radius_squared`` ``ρ(t)`` (or the constant of a pipe),
    over ``field``; ``circle_*`` are the characteristic circles (centre, radius², plane normal).
    Without a rational ``m(t)`` (a SMAT curve of positive genus), ``radical_spine`` and
    ``radical_radius_squared`` may give ``m(t)``, ``ρ(t)`` in square roots, ``t`` standing for the
    SMAT coordinate ``radical_parameter``, verified on the SMAT equations.
    """

    degree: int
    smat_degree: int
    genus: int | None
    planar: bool
    on_line: bool
    pipe: bool
    equations: tuple[str, ...]
    spine_equations: tuple[str, ...]
    plane_model: str
    projection: tuple[tuple[int, ...], tuple[int, ...]]
    parametrization: Triple | None = None
    radius_squared: str | None = None
    parameter: str = "t"
    field: str | None = None
    verified: bool = False
    circle_center: Triple | None = None
    circle_radius_squared: str | None = None
    circle_normal: Triple | None = None
    radical_spine: Triple | None = None
    radical_radius_squared: str | None = None
    radical_parameter: str | None = None


@dataclass(frozen=True)
class BaseCurve:
    """The base curve of a cone or a cylinder (docs/math.md §10), a plane curve in ``variables``.

    For a cone with apex ``c`` it is the top-degree form ``f_d`` (a projective plane curve) in
    the affine chart ``chart = 1``: ``X = c + t·(point in the chart)``. For a cylinder along ``a``
    it is the section by the plane through ``frame_point`` spanned by ``frame_u`` and
    ``frame_w`` (both ``⟂ a``): ``X = frame_point + u·frame_u + v·frame_w + t·a``.
    ``genus`` is that of the curve when it is absolutely irreducible (else ``None``);
    ``multiplicity`` is that of a component (a factor over ``K``) of a reducible base curve.
    """

    polynomial: str
    variables: tuple[str, str]
    degree: int
    chart: str | None = None
    frame_point: Triple | None = None
    frame_u: Triple | None = None
    frame_w: Triple | None = None
    reducible: bool | None = None
    absolutely_irreducible: bool | None = None
    genus: int | None = None
    multiplicity: int = 1


BEING_COMPUTED = "being computed"
"""A map's implicit equation's status (:attr:`ParametricInput.implicit_status`) while its stage runs."""


@dataclass(frozen=True)
class ParametricInput:
    """A surface typed as a rational parametrization ``P(s, t)`` and what the map itself says
    (docs/math.md §13), decided before and besides its implicit equation.

    ``components`` and ``parameters`` are as typed; ``map`` is ``P`` exactly (reduced fractions,
    in ``map_parameters``, the typed names when they are among sorgui's parameter names, else
    ``s, t`` in the typed order) over ``field``, of ``degree`` over a common denominator.
    ``symmetry``, ``symmetry_dimension`` and ``symmetry_basis`` are the symmetry algebra of its
    normal lines (the kinds of an equation's); ``conical`` is ``cone``, ``cylinder`` or ``none``
    with the ``apex`` and the cylinder ``directions``. ``profile_check`` is the cross-check
    ``∂(h, ρ)/∂(s, t) ≡ 0`` about the axis (``None`` without one axis); ``profile_curve`` is
    ``F(h, rho)``, the equation of the profile curve ``(h, ρ)``. ``implicit_method`` says how
    the implicit equation was found (``None``: it was not, ``implicit_status`` says why).
    ``fibre`` is the number of parameter points over a generic point of ``X`` (``proper``: it is
    1), decided by ``proper_method``.
    """

    components: Triple
    parameters: tuple[str, str]
    map: Triple
    map_parameters: tuple[str, str]
    field: str
    degree: int
    symmetry: str
    symmetry_dimension: int
    symmetry_basis: tuple[tuple[str, ...], ...]
    conical: str
    apex: Triple | None = None
    directions: tuple[Triple, ...] = ()
    profile_check: bool | None = None
    profile_curve: str | None = None
    implicit_method: str | None = None
    implicit_status: str = ""
    fibre: int | None = None
    proper: bool | None = None
    proper_method: str | None = None
    notes: tuple[str, ...] = ()
