"""The engine's immutable result objects and their JSON form (``sorgui analyze --json``).

Every exact number is stored as a string that sympy reads back exactly (``"3/5"``,
``"sqrt(2)/2"``), every polynomial as a sympy-syntax string in ``x, y, z`` (or the variables
named beside it). The GUI and the exporters only read these objects; ``to_json`` and
``from_json`` are inverse to each other.

The objects of the later stages (rationality, real locus, parameterizations, canal families,
base curves, a typed parametrization's report) are in :mod:`.stage_results`, loaded only by
what makes or reads them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, is_dataclass
from typing import TYPE_CHECKING, Any, Literal

if TYPE_CHECKING:
    from .stage_results import BaseCurve, CanalFamily, ParametricInput, Parametrization, Rationality, RealLocus

Triple = tuple[str, str, str]
"""Three exact numbers or expressions, as strings."""


@dataclass(frozen=True)
class Axis:
    """A line as a ``K``-rational point and direction, and its Plücker coordinates ``(v : p × v)``."""

    point: Triple
    direction: Triple
    plucker: tuple[str, str, str, str, str, str]


@dataclass(frozen=True)
class Profile:
    """The profile curve (docs/math.md §3).

    ``polynomial`` is the orthonormal profile ``p(x, y)`` (x along the axis, y the distance to
    it); ``square`` is ``P²``, i.e. ``p`` with ``y²`` replaced by ``y``. ``rational`` is the
    ``K``-rational ``p̃(s, r) = f(c + s·a + r·u)`` with the frame ``frame_point = c``,
    ``frame_direction = a``, ``frame_normal = u``; ``rational_square`` is ``p̃²(s, w)``.
    ``verified`` is the exact test ``f = p(x, y² + z²)`` in the axis frame (over ``QQ`` proved by
    (★) holding identically for the rotation about the axis, docs/math.md §3.1).
    """

    polynomial: str
    square: str
    rational: str
    rational_square: str
    frame_point: Triple
    frame_direction: Triple
    frame_normal: Triple
    even: bool
    verified: bool


UNDECIDED = "undecided"
"""The ``symmetry`` of a recognition that did not finish within the time limit."""

MAP_NEAR_FACTOR = 30.0
"""How many times the tolerance the relative deviation of a map's near kind may reach (the unit
of a map's ``residual``, :mod:`.parametric.nearly`): the rounding of a surface of revolution's
map printed with 6, 10 or 15 digits leaves 0.5 to 0.8 times the tolerance, a coefficient moved
by ``10⁻⁶`` (at 10 digits) or ``10⁻³`` (at 6) hundreds and thousands of times."""

MAP_NEAR_CEILING = 0.05
"""The largest relative deviation a map's near kind may have, however coarse its rounding: at two
significant digits (a tolerance of 0.05) :data:`MAP_NEAR_FACTOR` times the tolerance is above 1,
and every map was "nearly a cylinder" (the cosine of a normal with a direction is at most 1)."""


def map_near_limit(tolerance: float) -> float:
    """The relative deviation within which a map is near a kind (the unit of its ``residual``):
    :data:`MAP_NEAR_FACTOR` times ``tolerance``, at most :data:`MAP_NEAR_CEILING`."""
    return min(MAP_NEAR_FACTOR * tolerance, MAP_NEAR_CEILING)


@dataclass(frozen=True)
class Recognition:
    """What the symmetry algebra says about one polynomial (docs/math.md §2)."""

    polynomial: str
    degree: int
    is_sor: bool
    symmetry: str
    symmetry_dimension: int
    symmetry_basis: tuple[tuple[str, ...], ...]
    axis: Axis | None = None
    center: Triple | None = None
    normal: Triple | None = None
    direction: Triple | None = None
    profile: Profile | None = None
    radius_squared: str | None = None
    """A sphere of degree 2: the square of its radius (negative: no real point)."""

    @property
    def decided(self) -> bool:
        """Whether the symmetry is known: not :data:`UNDECIDED` (a time limit met first)."""
        return self.symmetry != UNDECIDED


@dataclass(frozen=True)
class Factor:
    """An irreducible factor of ``f`` over ``K`` with its multiplicity and its own recognition."""

    polynomial: str
    multiplicity: int
    recognition: Recognition


@dataclass(frozen=True)
class ApproximateAxis:
    """A line in floating point: a point on it and a unit direction (length units of the input)."""

    point: tuple[float, float, float]
    direction: tuple[float, float, float]


@dataclass(frozen=True)
class NearestSurface:
    """The exact surface that a rounded input was meant to be (docs/math.md, "Rounded input").

    ``polynomial`` is exact (rational, or over the input's field); ``axis`` is exact as in the
    rest of the JSON; ``relative_distance`` is ``‖f - g‖₂ / ‖f‖₂`` over the coefficients, with
    ``g`` the snapped polynomial; ``max_deviation`` is the largest distance (length units) from a
    sampled point of ``g = 0`` to ``f = 0`` inside the viewport's box; ``within_rounding`` says
    whether every coefficient of ``f - g`` lies within the rounding of the printed input (and the
    zero sets are not far apart, docs/math.md §8.6), and ``largest_residual`` is the largest of
    them in units of that rounding (``≤ 1``: within it).
    ``analysis`` is the whole exact analysis of ``g`` (``None`` with ``--recognition-only``).
    """

    polynomial: str
    kind: str
    axis: Axis | None
    center: Triple | None
    normal: Triple | None
    relative_distance: float
    max_deviation: float | None
    within_rounding: bool
    analysis: Analysis | None = None
    largest_residual: float | None = None


@dataclass(frozen=True)
class Approximation:
    """Whether a rounded input is, within its rounding, a surface of revolution.

    ``tolerance`` is the relative tolerance in force and ``tolerance_source`` says where it came
    from (``"input"``: derived from the printed digits; ``"given"``: ``--tolerance``).
    ``singular_values`` are those of the floating-point system (★), largest first, relative to
    the largest; ``relative_distance`` is ``‖f - f̄‖₂ / ‖f‖₂`` for the nearest invariant
    polynomial ``f̄`` about the refined axis, and ``residual`` the same residual measured in units
    of the input's rounding (≤ 1 means within it). ``kind`` is the approximate symmetry kind (or
    ``None``); ``nearest`` is the snapped exact surface, when one was found.
    """

    tolerance: float | None
    tolerance_source: str
    near_sor: bool
    kind: str | None
    relative_distance: float | None
    residual: float | None
    singular_values: tuple[float, ...]
    axis: ApproximateAxis | None = None
    center: tuple[float, float, float] | None = None
    normal: tuple[float, float, float] | None = None
    nearest: NearestSurface | None = None
    notes: tuple[str, ...] = ()

    def to_json(self) -> dict[str, Any]:
        """The ``approximate`` object of ``sorgui analyze --json``."""
        data: dict[str, Any] = _lists(
            {k: getattr(self, k) for k in _field_names(Approximation) if k not in ("axis", "nearest")}
        )
        data["axis"] = _plain(self.axis)
        nearest = self.nearest
        if nearest is not None:
            data["nearest"] = _lists(
                {k: getattr(nearest, k) for k in _field_names(NearestSurface) if k not in ("axis", "analysis")}
            )
            data["nearest"]["axis"] = _plain(nearest.axis)
            data["nearest"]["analysis"] = None if nearest.analysis is None else nearest.analysis.to_json()
        else:
            data["nearest"] = None
        return data

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Approximation:
        """The inverse of :meth:`to_json`."""
        nearest = data.get("nearest")
        if nearest is not None:
            nearest = NearestSurface(
                polynomial=nearest["polynomial"],
                kind=nearest["kind"],
                axis=_build(Axis, nearest.get("axis")),
                center=_tuples(nearest.get("center")),
                normal=_tuples(nearest.get("normal")),
                relative_distance=nearest["relative_distance"],
                max_deviation=nearest.get("max_deviation"),
                within_rounding=nearest["within_rounding"],
                analysis=None if nearest.get("analysis") is None else Analysis.from_json(nearest["analysis"]),
                largest_residual=nearest.get("largest_residual"),
            )
        plain = {k: _tuples(v) for k, v in data.items() if k in _field_names(cls) and k not in ("axis", "nearest")}
        return cls(**plain, axis=_build(ApproximateAxis, data.get("axis")), nearest=nearest)


@dataclass(frozen=True)
class CanalEvidence:
    """A certificate (``canal``) or a witness line (``not canal``), with what was checked.

    ``method`` is ``resultant`` (f | Res_t(S, ∂S/∂t) for a rational family), ``incidence`` (f in
    the incidence ideal of the family, a surface over a line; docs/math.md §9), ``elimination``
    (f divides every generator of the eliminated envelope ideal), ``rotation`` or ``symmetry`` (a
    surface of revolution or a sphere), or ``line`` (a witness ``point + τ·direction``).
    """

    method: str
    statement: str
    verified: bool
    point: Triple | None = None
    direction: Triple | None = None
    restriction: str | None = None


@dataclass(frozen=True)
class Canal:
    """Whether ``X`` is a canal surface, exactly (docs/math.md §9). ``is_canal`` is ``None``
    when undecided; ``kinds`` among ``pipe``, ``revolution``, ``dupin``, ``developable``;
    ``families`` are the sphere families found (the two focal conics of a Dupin cyclide)."""

    is_canal: bool | None
    status: str
    kinds: tuple[str, ...] = ()
    families: tuple[CanalFamily, ...] = ()
    certificate: CanalEvidence | None = None
    witness: CanalEvidence | None = None
    parametrizations: tuple[Parametrization, ...] = ()
    lines_tested: int = 0
    timings: tuple[tuple[str, float], ...] = ()
    notes: tuple[str, ...] = ()

    @property
    def spine(self) -> CanalFamily | None:
        return self.families[0] if self.families else None

    def to_json(self) -> dict[str, Any]:
        """The ``canal`` object of ``sorgui analyze --json``."""
        spine = self.spine
        return {
            "is_canal": self.is_canal,
            "status": self.status,
            "kinds": list(self.kinds),
            "spine": _plain(spine),
            "radius_squared": None if spine is None else spine.radius_squared,
            "families": [_plain(f) for f in self.families],
            "certificate": _plain(self.certificate),
            "witness": _plain(self.witness),
            "parametrizations": [_plain(p) for p in self.parametrizations],
            "lines_tested": self.lines_tested,
            "timings": dict(self.timings),
            "notes": list(self.notes),
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Canal:
        """The inverse of :meth:`to_json`."""
        from .stage_results import CanalFamily, Parametrization

        return cls(
            is_canal=data["is_canal"],
            status=data["status"],
            kinds=tuple(data["kinds"]),
            families=tuple(_build(CanalFamily, f) for f in data["families"]),
            certificate=_build(CanalEvidence, data.get("certificate")),
            witness=_build(CanalEvidence, data.get("witness")),
            parametrizations=tuple(_build(Parametrization, p) for p in data.get("parametrizations", [])),
            lines_tested=data.get("lines_tested", 0),
            timings=tuple(data.get("timings", {}).items()),
            notes=tuple(data.get("notes", ())),
        )


@dataclass(frozen=True)
class Conical:
    """Whether ``X`` is a cone (all lines through one apex) or a cylinder (all lines along one
    direction) over some curve, docs/math.md §10. ``kind`` is ``cone``, ``cylinder`` or ``none``;
    ``rational`` says whether ``X`` is rational (exactly when its base curve is), ``None`` when
    undecided. ``apex`` of a cylinder is set when ``f(c + X)`` is also homogeneous (planes
    through a line). For rounded input that is exactly neither, ``near_apex`` is the apex of a
    cone within the rounding, or ``near_direction`` the unit direction of a cylinder within it,
    and ``near_residual`` the relative residual (of Euler's identity, or ``|M a| / |M|``).
    ``components`` are the irreducible factors of a reducible base curve, each analysed."""

    kind: str
    apex: Triple | None = None
    direction: Triple | None = None
    base_curve: BaseCurve | None = None
    rational: bool | None = None
    parametrizations: tuple[Parametrization, ...] = ()
    notes: tuple[str, ...] = ()
    near_apex: tuple[float, float, float] | None = None
    near_residual: float | None = None
    near_direction: tuple[float, float, float] | None = None
    components: tuple[BaseCurve, ...] = ()

    def to_json(self) -> dict[str, Any]:
        """The ``conical`` object of ``sorgui analyze --json``: its fields, as they are."""
        data: dict[str, Any] = _plain(self)
        return data

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Conical:
        """The inverse of :meth:`to_json`."""
        from .stage_results import BaseCurve, Parametrization

        return cls(
            kind=data["kind"],
            apex=_tuples(data.get("apex")),
            direction=_tuples(data.get("direction")),
            base_curve=_build(BaseCurve, data.get("base_curve")),
            rational=data.get("rational"),
            parametrizations=tuple(_build(Parametrization, p) for p in data.get("parametrizations", [])),
            notes=tuple(data.get("notes", ())),
            near_apex=_tuples(data.get("near_apex")),
            near_residual=data.get("near_residual"),
            near_direction=_tuples(data.get("near_direction")),
            components=tuple(_build(BaseCurve, c) for c in data.get("components", [])),
        )


Verdict = Literal["sor", "near", "not", "not exactly", "undecided"]
"""What :attr:`Analysis.verdict` says."""


@dataclass(frozen=True)
class Analysis:
    """The whole answer for one input: recognition, factors, rationality and parameterizations."""

    input: str
    field: str
    method: str
    recognition: Recognition
    factors: tuple[Factor, ...]
    squarefree: str
    rationality: Rationality | None = None
    parametrizations: tuple[Parametrization, ...] = ()
    timings: tuple[tuple[str, float], ...] = ()
    approximate: Approximation | None = None
    unfinished: tuple[str, ...] = ()
    """Stages cut short by the time limit of the whole analysis (their results are undecided)."""
    real_locus: RealLocus | None = None
    canal: Canal | None = None
    conical: Conical | None = None
    input_kind: str = "equation"
    """``equation`` (``f(x, y, z) = 0`` typed) or ``parametrization`` (``parametric`` says more)."""
    parametric: ParametricInput | None = None

    @property
    def is_sor(self) -> bool:
        """Whether ``X`` is a surface of revolution (spheres, planes and cylinders included)."""
        return self.recognition.is_sor

    @property
    def verdict(self) -> Verdict:
        """The answer every view words: ``undecided`` (the recognition met the time limit),
        ``sor`` (a surface of revolution), ``near`` (rounded input that is none exactly but one
        within its rounding, docs/math.md §8), ``not exactly`` (rounded input that is none
        exactly, the analysis of its rounding unfinished), else ``not``."""
        if not self.recognition.decided:
            return "undecided"
        if self.recognition.is_sor:
            return "sor"
        if self.approximate is None and "approximate" in self.unfinished:
            return "not exactly"
        return "near" if self.approximate is not None and self.approximate.near_sor else "not"

    def to_json(self) -> dict[str, Any]:
        """The JSON object of ``sorgui analyze --json`` (recognition keys at the top level)."""
        rec = _plain(self.recognition)
        return {
            "input": self.input,
            "input_kind": self.input_kind,
            "polynomial": rec["polynomial"],
            "field": self.field,
            "method": self.method,
            "degree": rec["degree"],
            "is_sor": rec["is_sor"] if self.recognition.decided else None,  # not known: neither yes nor no
            "symmetry": rec["symmetry"],
            "symmetry_dimension": rec["symmetry_dimension"],
            "symmetry_basis": rec["symmetry_basis"],
            "axis": rec["axis"],
            "center": rec["center"],
            "radius_squared": rec["radius_squared"],
            "normal": rec["normal"],
            "direction": rec["direction"],
            "profile": rec["profile"],
            "factors": [_plain(f) for f in self.factors],
            "squarefree": self.squarefree,
            "rationality": _plain(self.rationality),
            "parametrizations": [_plain(p) for p in self.parametrizations],
            "timings": dict(self.timings),
            "approximate": None if self.approximate is None else self.approximate.to_json(),
            "real_locus": _plain(self.real_locus),
            "canal": None if self.canal is None else self.canal.to_json(),
            "conical": None if self.conical is None else self.conical.to_json(),
            "unfinished": list(self.unfinished),
            "parametric": _plain(self.parametric),
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Analysis:
        """The inverse of :meth:`to_json`."""
        from .stage_results import ParametricInput, Parametrization, Rationality, RealLocus

        recognition = _recognition_from(data)
        return cls(
            input=data["input"],
            field=data["field"],
            method=data["method"],
            recognition=recognition,
            factors=tuple(
                Factor(f["polynomial"], f["multiplicity"], _recognition_from(f["recognition"])) for f in data["factors"]
            ),
            squarefree=data["squarefree"],
            rationality=_build(Rationality, data.get("rationality")),
            parametrizations=tuple(_build(Parametrization, p) for p in data.get("parametrizations", [])),
            timings=tuple(data.get("timings", {}).items()),
            approximate=None if data.get("approximate") is None else Approximation.from_json(data["approximate"]),
            real_locus=_build(RealLocus, data.get("real_locus")),
            canal=None if data.get("canal") is None else Canal.from_json(data["canal"]),
            conical=None if data.get("conical") is None else Conical.from_json(data["conical"]),
            unfinished=tuple(data.get("unfinished", ())),
            input_kind=data.get("input_kind", "equation"),
            parametric=_build(ParametricInput, data.get("parametric")),
        )


VERSION_KEY = "sorgui_version"
"""The key of a report's JSON that names the version of sorgui that wrote it."""


def report_json(analysis: Analysis) -> dict[str, Any]:
    """The JSON document of a report (``sorgui analyze --json``, ``-o FILE.json``): the version of
    sorgui that wrote it, then :meth:`Analysis.to_json` (a reader refuses a newer version's)."""
    from sorgui import __version__

    return {VERSION_KEY: __version__, **analysis.to_json()}


_FIELD_NAMES: dict[type, list[str]] = {}


def _field_names(cls: type) -> list[str]:
    names = _FIELD_NAMES.get(cls)
    if names is None:
        names = _FIELD_NAMES[cls] = [f.name for f in fields(cls)]
    return names


def _plain(obj: Any) -> Any:
    """A dataclass as JSON-ready data (tuples become lists); ``None`` stays ``None``."""
    return _lists(obj)


def _lists(value: Any) -> Any:
    """JSON-ready data: a dataclass as the dict of its fields (``dataclasses.asdict``, without
    its deep copy of every leaf: a tenth of a batch line's time), tuples as lists, and a number
    that is not finite as ``None``: JSON has no infinity (a report holding ``Infinity`` was
    refused by sorgui's own reader and by other programs)."""
    if isinstance(value, (str, int)) or value is None:
        return value
    if isinstance(value, dict):
        return {k: _lists(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_lists(v) for v in value]
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if is_dataclass(value) and not isinstance(value, type):
        return {name: _lists(getattr(value, name)) for name in _field_names(type(value))}
    return value


def _tuples(value: Any) -> Any:
    if isinstance(value, list):
        return tuple(_tuples(v) for v in value)
    return value


def _build(cls: type, data: dict[str, Any] | None) -> Any:
    """Rebuild a flat dataclass from its JSON form (lists back to tuples)."""
    if data is None:
        return None
    names = {f.name for f in fields(cls)}
    return cls(**{k: _tuples(v) for k, v in data.items() if k in names})


def _recognition_from(data: dict[str, Any]) -> Recognition:
    return Recognition(
        polynomial=data["polynomial"],
        degree=data["degree"],
        is_sor=bool(data["is_sor"]),
        symmetry=data["symmetry"],
        symmetry_dimension=data["symmetry_dimension"],
        symmetry_basis=_tuples(data["symmetry_basis"]),
        axis=_build(Axis, data.get("axis")),
        center=_tuples(data.get("center")),
        normal=_tuples(data.get("normal")),
        direction=_tuples(data.get("direction")),
        profile=_build(Profile, data.get("profile")),
        radius_squared=data.get("radius_squared"),
    )
