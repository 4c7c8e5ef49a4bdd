"""The 3D views' render window: pyvistaqt's ``QtInteractor`` rendering the scene only when it may have changed.

pyvistaqt's ``QOpenGLWidget`` renders the whole VTK scene at every paint of the widget, also
at the paints Qt makes on its own: when a label beside the view changes its text, or the run's
progress row appears, Qt lays the window out again, repaints that region and VTK renders an
unchanged scene once more, 20-60 ms for a degree-12 surface in Mesa's software OpenGL, enough
to hold up the GUI thread for over 100 ms when two such paints follow each other (issue 30).

:class:`RenderWindow` renders in a paint only when something may have changed the scene since
VTK's last frame: a ``render()`` or ``update()`` asked for from Python (pyvista, pyvistaqt and
sorgui's own code change the scene through these), a new size or a new OpenGL context.
Otherwise the paint copies VTK's last frame to the widget, as the C++ ``QVTKOpenGLNativeWidget``
does after a render that VTK made itself. A frame VTK has just rendered (the interactor's, while
the user turns the view, or ``render()``'s) is shown without rendering it twice.

pyvistaqt keeps a Python wrapper of the OpenGL surface of the render window's context, which Qt
deletes with the render window unseen by PySide (a surface is not a ``QObject``). The wrapper
then stays in PySide's table of wrappers, keyed by address: a widget made later at that address
shares the key with it, and Qt's deletion of that widget can crash (SIGSEGV in
``BindingManager::releaseWrapper``). The wrapper is taken out of the table when the context is
deleted, just before its surface.

This module imports pyvistaqt and VTK: only the code that creates a render window imports it.
"""

from __future__ import annotations

from functools import partial
from typing import Any

import shiboken6
from PySide6.QtGui import QSurface
from PySide6.QtOpenGLWidgets import QOpenGLWidget
from pyvistaqt import QtInteractor


def _forget_surface(surface: QSurface, *_destroyed: object) -> None:
    """Take ``surface``'s wrapper out of PySide's table of wrappers (Qt deletes the surface next)."""
    shiboken6.invalidate(surface)


class RenderWindow(QtInteractor):
    """A ``QtInteractor`` whose paints render the scene only when it may have changed."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:  # noqa: ANN401 - QtInteractor's own
        super().__init__(*args, **kwargs)
        self._stale = True
        """Whether the scene may differ from VTK's last frame."""

    def scene_changed(self) -> None:
        """Say that the scene may differ from VTK's last frame: the next paint renders it, whoever
        asks for that paint (a frame made for an export, say, is then never shown)."""
        self._stale = True

    def render(self) -> None:  # type: ignore[override]  # pyvista's render, as in QtInteractor
        """Render the scene now (pyvista's ``render``); a paint renders it again if VTK skipped it."""
        self._stale = True
        super().render()

    def update(self, *args: Any) -> None:  # noqa: ANN401 - QWidget.update's overloads
        """Repaint the widget, rendering the scene (called from Python after a change of the scene)."""
        self._stale = True
        QOpenGLWidget.update(self, *args)

    def initializeGL(self) -> None:  # noqa: N802 (Qt override)
        self._stale = True
        super().initializeGL()  # type: ignore[no-untyped-call]  # pyvistaqt's rwi is untyped
        context, surface = self._ctx, self._surface  # pyvistaqt's, set by its initializeGL
        if context is not None and surface is not None:
            context.destroyed.connect(partial(_forget_surface, surface))

    def resizeGL(self, w: int, h: int) -> None:  # noqa: N802 (Qt override)
        self._stale = True
        super().resizeGL(w, h)  # type: ignore[no-untyped-call]

    def paintGL(self) -> None:  # noqa: N802 (Qt override)
        if self._stale:
            self._stale = False
            super().paintGL()  # type: ignore[no-untyped-call]
            return
        # pyvistaqt's paintGL renders unless it is inside a paint: say it is, so that it copies
        # VTK's last frame to the widget and renders nothing.
        self._in_paint = True
        try:
            super().paintGL()  # type: ignore[no-untyped-call]
        finally:
            self._in_paint = False

    def _cb_frame(self, obj: object, event: str) -> None:
        """VTK finished a frame outside a paint (``render()``, the interactor): show it as it is."""
        rw = self._RenderWindow
        if rw is None or (rw.GetDoubleBuffer() and not rw.GetSwapBuffers()):
            return
        if not self._in_paint:
            self._stale = False
            QOpenGLWidget.update(self)
