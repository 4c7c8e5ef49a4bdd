"""What a parametric patch is made of: the verified real rational parameterizations of an
analysis, in the order they are tried, and for rounded input the nearest exact surface's.

The window's patch, the mesh files ``NAME.patch.stl`` (``.obj``, ``.ply``, ``.vtp``) and the
CAD file ``NAME.patch.step`` all take the first map of :func:`patch_maps`, so that each writes
the patch the others show: a map of ``X`` (docs/math.md §6), of a canal surface by its circles
(§9), of a cone or cylinder by its lines (§10), or a sphere's stereographic projection. For
rounded input, which is exactly none of these, the maps are those of the exact surface it was
meant to be (:func:`nearest_surface`, §8.5), also when the rounded surface has maps of its
own: a rounded cone is exactly a cone over a conic, whose map by its lines has coefficients in
``QQ(√659998899417)`` of 80 digits, no CAD patch, and the mesh files took that map while
``NAME.patch.step`` took the nearest cone's.
"""

from __future__ import annotations

from .results import Analysis, NearestSurface, Recognition
from .stage_results import Parametrization
from .values import read_expression


def own_maps(analysis: Analysis) -> list[Parametrization]:
    """The verified real parameterizations of ``analysis`` itself, in the order they are tried."""
    candidates = [
        *analysis.parametrizations,
        *(analysis.canal.parametrizations if analysis.canal is not None else ()),
        *(analysis.conical.parametrizations if analysis.conical is not None else ()),
        *sphere_parametrization(analysis.recognition),
    ]
    return [p for p in candidates if p.real and p.verified]


def patch_maps(analysis: Analysis) -> list[Parametrization]:
    """For rounded input the nearest exact surface's maps, when it has any; else :func:`own_maps`."""
    stand_in = patch_stand_in(analysis)
    exact = stand_in.analysis if stand_in is not None else None
    return own_maps(analysis if exact is None else exact)


def patch_stand_in(analysis: Analysis) -> NearestSurface | None:
    """The nearest exact surface whose maps :func:`patch_maps` gives for ``analysis``: rounded
    input whose nearest exact surface has a map; ``None`` when the maps are its own (or there are
    none)."""
    nearest = nearest_surface(analysis)
    return nearest if nearest is not None and nearest.analysis is not None and own_maps(nearest.analysis) else None


def nearest_surface(analysis: Analysis) -> NearestSurface | None:
    """The exact surface of revolution a rounded input was meant to be, if the engine found one
    (and analysed it) and the input itself is not one."""
    approx = analysis.approximate
    if analysis.recognition.is_sor or approx is None or approx.nearest is None:
        return None
    nearest = approx.nearest
    if nearest.analysis is None or not nearest.analysis.recognition.is_sor:
        return None
    return nearest


def sphere_parametrization(rec: Recognition) -> list[Parametrization]:
    """A sphere's inverse stereographic projection ``c + r·(2s, 2t, s² + t² − 1)/(s² + t² + 1)``
    (exact: ``r = √(r²)`` of the recognition), none for another surface."""
    if rec.symmetry != "sphere" or rec.center is None or rec.radius_squared is None:
        return []
    if not float(read_expression(rec.radius_squared).evalf(30)) > 0:
        return []
    r = f"sqrt({rec.radius_squared})"
    c = rec.center
    d = "(s**2 + t**2 + 1)"
    coordinates = (f"({c[0]}) + ({r})*2*s/{d}", f"({c[1]}) + ({r})*2*t/{d}", f"({c[2]}) + ({r})*(s**2 + t**2 - 1)/{d}")
    method = "stereographic projection of the sphere"
    return [Parametrization(coordinates, ("s", "t"), "QQ", True, True, method, True, "an identity of the sphere")]
