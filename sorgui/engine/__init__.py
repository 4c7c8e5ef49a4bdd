"""The exact engine: pure mathematics over K, with no Qt and no VTK.

Entry point: :func:`analyze` turns pasted text into an immutable :class:`Analysis`. Laid out as
sympy's ``polys``: a core of one module per idea, and subpackages, one idea each.

The core: ``parsing`` (reading pasted text: its entry points), ``expanded`` (the fast path for
expanded polynomials), ``syntax`` (the general parser: tokens, syntax tree, evaluation),
``limits`` (what both readers accept), ``parametric_parsing`` (a parametrization's text),
``expressions`` (reading Singular's
answers and the engine's own strings), ``values`` (the engine's strings decoded once, as sympy
objects, floats and float terms), ``results`` (the result objects and their JSON) and
``stage_results`` (those of the stages after the recognition, loaded when first needed),
``vocabulary`` (the words for kinds of surface), ``errors`` (the one exception hierarchy),
``stages``, ``timelimit`` and ``lifetime`` (ending an analysis when asked), ``analysis`` (the
staged pipeline) and ``rational_path`` (the recognition-only pipeline over ``QQ`` without
sympy).

Subpackages: ``algebra`` (polynomials, ``QQ`` on flint, number fields, radicals, linear algebra,
real roots), ``singular`` (the Singular process, plane curves, sorgui's Singular library),
``recognition`` (the symmetry algebra, the paper's method, the profile, the recognizer),
``revolution`` (real points, Table 1, parameterizations), ``conical`` (cones and cylinders over
any curve), ``canal`` (canal surfaces) and ``rounded`` (decimal input). A subpackage's
``__init__`` imports nothing, and the sympy-based modules are loaded only when an analysis
needs them. Importing the package loads ``analysis`` (the parser, flint) only when
:func:`analyze` or :func:`analyze_polynomial` is first asked for, so that a module that needs
only the result objects (``results``) or ``lifetime`` is light to import.
"""

from typing import TYPE_CHECKING

from .errors import (
    AnalysisError,
    Cancelled,
    ParseError,
    SingularError,
    SingularTimeout,
    SorguiError,
)
from .results import Analysis, Axis, Factor, Profile, Recognition
from .stages import STAGES

if TYPE_CHECKING:
    from .analysis import analyze, analyze_polynomial
    from .stage_results import Parametrization, Rationality


def __getattr__(name: str) -> object:
    """:func:`analyze` and :func:`analyze_polynomial` from ``analysis``, :class:`Parametrization`
    and :class:`Rationality` from ``stage_results``, when first asked for (PEP 562)."""
    if name in ("analyze", "analyze_polynomial"):
        from . import analysis

        return getattr(analysis, name)
    if name in ("Parametrization", "Rationality"):
        from . import stage_results

        return getattr(stage_results, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "STAGES",
    "Analysis",
    "AnalysisError",
    "Axis",
    "Cancelled",
    "Factor",
    "Parametrization",
    "ParseError",
    "Profile",
    "Rationality",
    "Recognition",
    "SingularError",
    "SingularTimeout",
    "SorguiError",
    "analyze",
    "analyze_polynomial",
]
