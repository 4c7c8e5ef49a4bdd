"""Standard views of a surface of revolution and the camera as plain data.

A view is where the camera stands, what it looks at and which way is up, for a drawn ball
(centre ``c``, radius ``r``): *along the axis* looks down the axis (the circles of latitude are
circles on screen), *across the axis* looks perpendicular to it with the axis vertical (the
silhouette is the profile curve), and the three coordinate views look along ``x``, ``y``, ``z``.
:class:`CameraState` is what the settings store to restore the camera on the next start.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from sorgui.render.geometry import perpendicular_vector, unit

DISTANCE = 3.2
"""The camera stands this many radii from the centre of the ball (the ball fills the view)."""

COORDINATE_VIEWS = {
    "x": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "y": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
    "z": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
}
"""Looking along the named axis: the camera's offset from the centre and its up vector."""


@dataclass(frozen=True)
class CameraState:
    """A camera: position, focal point, up vector, view angle, parallel scale and projection."""

    position: tuple[float, float, float]
    focal_point: tuple[float, float, float]
    view_up: tuple[float, float, float]
    view_angle: float = 30.0
    parallel_scale: float = 1.0
    parallel: bool = False

    def to_dict(self) -> dict[str, object]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, object]) -> CameraState | None:
        """The state saved by :meth:`to_dict`, or ``None`` if ``data`` is not one, or is the
        camera of a scene never framed (:meth:`framed`)."""
        try:
            state = cls(
                position=_triple(data["position"]),
                focal_point=_triple(data["focal_point"]),
                view_up=_triple(data["view_up"]),
                view_angle=float(data.get("view_angle", 30.0)),  # type: ignore[arg-type]
                parallel_scale=float(data.get("parallel_scale", 1.0)),  # type: ignore[arg-type]
                parallel=bool(data.get("parallel", False)),
            )
        except (KeyError, TypeError, ValueError):
            return None
        return state if state.framed else None

    @property
    def framed(self) -> bool:
        """Whether this is not VTK's camera before any scene was framed, from ``(1, 1, 1)`` at
        the origin: a window that drew a scene without its camera kept that one in the
        settings, and every later start restored it, looking from inside the surface."""
        return self != UNFRAMED


def _triple(value: object) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in value)  # type: ignore[attr-defined]
    if not all(np.isfinite((x, y, z))):
        raise ValueError("not a finite vector")
    return (x, y, z)


def view_along(center: np.ndarray, radius: float, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Camera position and up vector looking along ``direction`` at ``center``."""
    d = unit(direction)
    return center + DISTANCE * radius * d, unit(perpendicular_vector(d))


def view_across(center: np.ndarray, radius: float, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Camera position and up vector looking perpendicular to ``direction``, which points up."""
    a = unit(direction)
    side = unit(perpendicular_vector(a))
    return center + DISTANCE * radius * side, a


def coordinate_view(center: np.ndarray, radius: float, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Camera position and up vector looking along the coordinate axis ``name`` (x, y or z)."""
    offset, up = COORDINATE_VIEWS[name]
    return center + DISTANCE * radius * np.asarray(offset), np.asarray(up)


def meridian_normal(axis_point: np.ndarray, axis_direction: np.ndarray, profile_points: np.ndarray) -> np.ndarray:
    """The normal of the plane through the axis that holds the drawn profile curve (the
    meridian plane: clipping the surface there shows the profile as the cut's edge)."""
    a = unit(axis_direction)
    if len(profile_points):
        offsets = profile_points - axis_point
        offsets = offsets - np.outer(offsets @ a, a)
        far = offsets[np.argmax(np.linalg.norm(offsets, axis=1))]
        if np.linalg.norm(far) > 1e-9:
            return unit(np.cross(a, far))
    return unit(np.cross(a, perpendicular_vector(a)))


UNFRAMED = CameraState((1.0, 1.0, 1.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
"""VTK's camera before any scene is framed (:attr:`CameraState.framed`)."""
