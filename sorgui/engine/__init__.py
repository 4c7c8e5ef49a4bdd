"""The exact engine: pure mathematics over K, with no Qt and no VTK.

Entry point: :func:`analyze` turns pasted text into an immutable :class:`Analysis`.
Modules, one idea each (following sympy's ``polys``): ``parsing`` (safe parser), ``polys``
(exact polynomial facade over sympy and flint), ``rationals`` (``QQ`` on flint alone),
``rational_path`` (the recognition-only analysis over ``QQ`` without sympy), ``linalg`` (null
spaces over K), ``symmetry`` (the symmetry algebra L of (★)), ``paper_method`` (the paper's
Algorithm II), ``profile`` (profile curve and axis frames), ``recognition`` (axis, profile,
factors), ``singular`` and ``curves`` (plane curves with Singular), ``rationality`` (Table 1,
tubular surface), ``parametrization`` (rational parameterizations of X), ``canal`` and its
``canal_*`` modules (canal surfaces), ``report`` (result objects and JSON), ``analysis`` (the
staged pipeline), ``errors`` (the one exception hierarchy). The sympy-based modules are loaded
only when an analysis needs them.
"""

from .analysis import STAGES, analyze, analyze_polynomial
from .errors import (
    AnalysisError,
    Cancelled,
    ParseError,
    SingularError,
    SingularTimeout,
    SorguiError,
)
from .report import (
    Analysis,
    Axis,
    Factor,
    Parametrization,
    Profile,
    Rationality,
    Recognition,
)

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
