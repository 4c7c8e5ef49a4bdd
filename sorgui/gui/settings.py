"""What sorgui remembers between sessions, and the equation files it reads and writes.

One :class:`Settings` object wraps ``QSettings`` in INI format in the user scope
(``~/.config/sorgui/sorgui.ini`` on Linux): the editor content (restored on the next start),
the recent files, the window layout and the camera of the 3D view. Tests point ``QSettings.setPath`` at a temporary
folder, so they never touch the user's file. Equation files are plain UTF-8 text.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import cast

from PySide6.QtCore import QByteArray, QObject, QSettings, Signal
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QMenu, QWidget

ORGANIZATION = "sorgui"
APPLICATION = "sorgui"
MAX_RECENT_FILES = 10
MAX_FILE_BYTES = 4 * 1024 * 1024
"""Equation files larger than this are refused: nobody types a 4 MB polynomial."""

EQUATION_FILTER = "Equations (*.txt *.sor *.poly);;All files (*)"


class EquationFileError(OSError):
    """An equation file could not be read or written; the message is for the user."""


def read_equation(path: str | Path) -> str:
    """The text of an equation file (UTF-8, at most :data:`MAX_FILE_BYTES`; no more is read, so
    a device such as ``/dev/zero``, whose size says nothing, is refused, not read whole)."""
    path = Path(path)
    try:
        with open(path, "rb") as stream:
            data = stream.read(MAX_FILE_BYTES + 1)
        if len(data) > MAX_FILE_BYTES:
            raise EquationFileError(
                f"{path.name} is too large (more than {MAX_FILE_BYTES // 1024} KiB) to be an equation"
            )
        return data.decode("utf-8").strip()
    except UnicodeDecodeError:
        raise EquationFileError(f"{path.name} is not a UTF-8 text file") from None
    except OSError as exc:
        if isinstance(exc, EquationFileError):
            raise
        raise EquationFileError(f"cannot read {path}: {exc.strerror or exc}") from None


def write_equation(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` as UTF-8 with a final newline."""
    path = Path(path)
    try:
        path.write_text(text.rstrip("\n") + "\n", encoding="utf-8")
    except OSError as exc:
        raise EquationFileError(f"cannot write {path}: {exc.strerror or exc}") from None


class Settings(QObject):
    """Typed access to sorgui's ``QSettings``; emits :attr:`recent_files_changed`."""

    recent_files_changed = Signal()

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._store = QSettings(QSettings.Format.IniFormat, QSettings.Scope.UserScope, ORGANIZATION, APPLICATION)

    @property
    def file_name(self) -> str:
        """Where the settings live (for the About box and for tests)."""
        return self._store.fileName()

    # --- editor content ---

    @property
    def equation(self) -> str | None:
        """The editor content at the last exit, or ``None`` on a first start."""
        value = self._store.value("editor/equation")
        return str(value) if value else None

    @equation.setter
    def equation(self, text: str) -> None:
        self._store.setValue("editor/equation", text)

    @property
    def current_file(self) -> str | None:
        """The file the editor content came from or was saved to, if any."""
        value = self._store.value("editor/file")
        return str(value) if value else None

    @current_file.setter
    def current_file(self, path: str | None) -> None:
        self._store.setValue("editor/file", path or "")

    # --- recent files ---

    @property
    def recent_files(self) -> list[str]:
        """Recently opened or saved files, newest first."""
        value = cast("list[str] | str | None", self._store.value("files/recent", []))  # what add_recent_file stored
        if isinstance(value, str):  # QSettings returns a lone string for a one-element list
            value = [value]
        return [str(v) for v in value or []]

    def add_recent_file(self, path: str | Path) -> None:
        """Put ``path`` first in the recent files (absolute, without duplicates)."""
        name = str(Path(path).resolve())
        files = [name] + [f for f in self.recent_files if f != name]
        self._store.setValue("files/recent", files[:MAX_RECENT_FILES])
        self.recent_files_changed.emit()

    def remove_recent_file(self, path: str) -> None:
        """Forget ``path`` (it no longer exists)."""
        self._store.setValue("files/recent", [f for f in self.recent_files if f != path])
        self.recent_files_changed.emit()

    def clear_recent_files(self) -> None:
        self._store.setValue("files/recent", [])
        self.recent_files_changed.emit()

    # --- the 3D view ---

    @property
    def camera(self) -> tuple[str, dict[str, object]] | None:
        """The camera of the 3D view at the last exit, with the equation it was looking at:
        ``(equation, CameraState dict)`` (see :class:`~sorgui.gui.camera.CameraState`)."""
        value = self._store.value("view/camera")
        try:
            data = json.loads(str(value)) if value else None
        except ValueError:
            return None
        if not isinstance(data, dict) or not isinstance(data.get("equation"), str):
            return None
        state = data.get("camera")
        return (data["equation"], state) if isinstance(state, dict) else None

    def set_camera(self, equation: str, state: dict[str, object]) -> None:
        """Remember the camera of the 3D view showing ``equation``."""
        self._store.setValue("view/camera", json.dumps({"equation": equation, "camera": state}))

    def forget_camera(self) -> None:
        """Nothing was shown: the next start frames its first surface afresh."""
        self._store.remove("view/camera")

    @property
    def software_rendering(self) -> bool | None:
        """Whether OpenGL ran in software at the last exit (``None`` if never found out)."""
        value = self._store.value("view/software_rendering")
        return None if value is None else str(value).lower() in ("true", "1")

    @software_rendering.setter
    def software_rendering(self, software: bool) -> None:
        self._store.setValue("view/software_rendering", bool(software))

    @property
    def time_limit(self) -> float | None:
        """The time limit of one analysis in seconds (``None``: never set, the default applies)."""
        return _positive(self._store.value("analysis/time_limit"))

    @time_limit.setter
    def time_limit(self, seconds: float) -> None:
        self._store.setValue("analysis/time_limit", float(seconds))

    @property
    def tolerance(self) -> float | None:
        """The relative tolerance of rounded input (``None``: read off the input's digits)."""
        value = _positive(self._store.value("analysis/tolerance"))
        return value if value is not None and value < 1 else None

    @tolerance.setter
    def tolerance(self, tolerance: float | None) -> None:
        if tolerance is None:
            self._store.remove("analysis/tolerance")
        else:
            self._store.setValue("analysis/tolerance", float(tolerance))

    # --- window layout ---

    def save_layout(self, name: str, state: QByteArray) -> None:
        """Store a widget's saved geometry or state (``saveGeometry()``/``saveState()``)."""
        self._store.setValue(f"layout/{name}", state)

    def layout(self, name: str) -> QByteArray | None:
        value = self._store.value(f"layout/{name}")
        return value if isinstance(value, QByteArray) else None

    def sync(self) -> None:
        """Write pending changes to disk now."""
        self._store.sync()


def recent_label(name: str, files: list[str]) -> str:
    """The file's name in the recent files menu, with its folder's name when another file of the
    list has the same name (two ``eq.sor`` read alike, and a menu shows no tool tip)."""
    path = Path(name)
    if sum(Path(other).name == path.name for other in files) < 2:
        return path.name
    return f"{path.name}  ({path.parent.name or path.parent})"


class RecentFilesMenu(QMenu):
    """File ▸ Open Recent: one action per remembered file, rebuilt when the list changes."""

    file_chosen = Signal(str)

    def __init__(self, settings: Settings, parent: QWidget | None = None) -> None:
        super().__init__("Open &Recent", parent)
        self._settings = settings
        settings.recent_files_changed.connect(self._on_recent_files_change)
        self._on_recent_files_change()

    def _on_recent_files_change(self) -> None:
        self.clear()
        files = self._settings.recent_files
        for index, name in enumerate(files):
            shown = recent_label(name, files)
            label = f"&{index + 1}  {shown}" if index < 9 else shown
            action = QAction(label, self)
            action.setToolTip(name)
            action.setData(name)
            action.triggered.connect(lambda _checked=False, n=name: self.file_chosen.emit(n))
            self.addAction(action)
        if files:
            self.addSeparator()
        clear = self.addAction("&Clear List")
        clear.setEnabled(bool(files))
        clear.triggered.connect(self._settings.clear_recent_files)
        self.setEnabled(bool(files))


def _positive(value: object) -> float | None:
    """A stored positive finite number, or ``None`` (absent or not a number)."""
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) and number > 0 else None
