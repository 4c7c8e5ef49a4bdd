"""Static types for the pyvista plotter methods that a type checker cannot read as pyvista declares them.

pyvista defines many methods of its ``Plotter`` as forwarders to the renderer, decorated with
``functools.wraps(Renderer.method)``. typeshed types such a method as ``functools._Wrapped``,
which is no descriptor, so mypy reads ``plotter.method(...)`` as a call that lacks ``self``.
:func:`forwarders` returns the plotter itself, typed with the signatures pyvista documents for
the forwarders sorgui calls; nothing changes at run time.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Protocol, cast

if TYPE_CHECKING:
    import numpy as np
    import pyvista


class Forwarders(Protocol):
    """The forwarding methods of ``pyvista.BasePlotter`` that sorgui calls."""

    def set_background(self, color: pyvista.ColorLike, top: pyvista.ColorLike | None = None) -> None: ...

    def add_axes(self, *, line_width: int = 2, labels_off: bool = False) -> object: ...

    def enable_surface_point_picking(
        self,
        callback: Callable[[np.ndarray], object] | None = None,
        *,
        show_message: bool = True,
        show_point: bool = True,
        left_clicking: bool = False,
        clear_on_no_selection: bool = True,
    ) -> object: ...

    def remove_actor(self, actor: str, reset_camera: bool = False, render: bool = True) -> bool: ...

    def view_isometric(
        self, negative: bool = False, render: bool = True, bounds: Sequence[float] | None = None
    ) -> None: ...

    def reset_camera(self, render: bool = True, bounds: Sequence[float] | None = None) -> None: ...

    def view_vector(
        self,
        vector: Sequence[float] | np.ndarray,
        viewup: Sequence[float] | np.ndarray | None = None,
        render: bool = True,
        bounds: Sequence[float] | None = None,
    ) -> None: ...

    def hide_axes(self) -> None: ...

    def add_legend(
        self,
        labels: Sequence[tuple[str, pyvista.ColorLike]],
        *,
        bcolor: pyvista.ColorLike | None = None,
        face: str | None = None,
        size: tuple[float, float] = (0.2, 0.2),
    ) -> object: ...

    def show_axes(self) -> None: ...


def forwarders(plotter: pyvista.BasePlotter) -> Forwarders:
    """``plotter`` itself, typed with its :class:`Forwarders`."""
    return cast(Forwarders, plotter)
