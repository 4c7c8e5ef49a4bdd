"""Lines seen through the surface: the axis where the surface hides it, drawn faint.

An axis runs inside the surface it turns: a cone's and a cylinder's from end to end, a sphere's
and an ellipsoid's between the poles, a torus's behind the ring. Drawn as any other actor, it
was visible only where it leaves the surface (a rounded CAD cone showed a few pixels of it at
the apex). :class:`HiddenLines` draws such lines again in a second renderer, on the render
window's layer 1 with the main renderer's camera: its depth buffer holds only these lines, so
they show everywhere, faint (:data:`HIDDEN_OPACITY`). Where the line is in front, the faint
copy falls on the line itself and changes nothing; where it is hidden, it shows the way a CAD
system shows hidden edges. The layer renders no background and takes no clicks (picking stays
with the surface).

The window's 3D view and the reports' pictures (:mod:`sorgui.export.picture`) draw them alike.
This module imports VTK: only the code that creates a render window imports it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pyvista
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

if TYPE_CHECKING:
    from pyvista.plotting.plotter import BasePlotter

HIDDEN_OPACITY = 0.3
"""The opacity of a line where the surface hides it."""
HIDDEN_LAYER = 1
"""The render window's layer of the hidden lines (the scene's renderer is on layer 0)."""


class HiddenLines:
    """The faint copies of some of a plotter's lines, drawn over the whole scene."""

    def __init__(self, plotter: BasePlotter) -> None:
        renderer = vtkRenderer()
        renderer.SetLayer(HIDDEN_LAYER)
        renderer.SetInteractive(False)
        renderer.SetActiveCamera(plotter.renderer.GetActiveCamera())
        window = plotter.ren_win
        assert window is not None  # the render window is made with the plotter
        window.SetNumberOfLayers(max(window.GetNumberOfLayers(), HIDDEN_LAYER + 1))
        window.AddRenderer(renderer)
        self._renderer = renderer
        self._actors: dict[str, vtkActor] = {}

    def show(self, name: str, mesh: pyvista.PolyData, color: str, line_width: float, visible: bool = True) -> None:
        """Draw the faint copy of the line ``name`` (replacing the one drawn); an empty ``mesh``
        removes it."""
        self.remove(name)
        if mesh.n_points == 0:
            return
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(mesh)
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.PickableOff()
        prop = actor.GetProperty()
        prop.SetColor(*pyvista.Color(color).float_rgb)
        prop.SetOpacity(HIDDEN_OPACITY)
        prop.SetLineWidth(line_width)
        prop.LightingOff()
        actor.SetVisibility(visible)
        self._renderer.AddActor(actor)
        self._actors[name] = actor

    def remove(self, name: str) -> None:
        """Remove the copy of the line ``name``, if drawn."""
        actor = self._actors.pop(name, None)
        if actor is not None:
            self._renderer.RemoveActor(actor)

    def set_visible(self, name: str, visible: bool) -> None:
        """Show or hide the copy of the line ``name`` with the line itself."""
        actor = self._actors.get(name)
        if actor is not None:
            actor.SetVisibility(visible)

    def names(self) -> set[str]:
        """The lines drawn (for tests)."""
        return set(self._actors)
