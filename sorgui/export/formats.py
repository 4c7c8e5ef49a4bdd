"""The export formats by suffix: what ``sorgui analyze -o`` and the window's File → Export offer.

A light module (no sympy, no VTK), so that the window and the command line can name, list and
check formats without importing the writers of :mod:`sorgui.export.files`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Format:
    """One export format: its suffix, its name in file dialogs, and its kind (``report``,
    ``formula``, ``mesh``, ``cad`` or ``picture``)."""

    suffix: str
    name: str
    kind: str

    @property
    def needs_scene(self) -> bool:
        return self.kind in ("mesh", "cad", "picture")

    @property
    def has_patch(self) -> bool:
        """Whether ``NAME.patch.SUFFIX`` writes the parameterization's patch in this format."""
        return self.kind in ("mesh", "cad")


FORMATS: dict[str, Format] = {
    f.suffix: f
    for f in (
        Format(".json", "JSON report", "report"),
        Format(".txt", "Text report", "report"),
        Format(".md", "Markdown report", "report"),
        Format(".html", "HTML report", "report"),
        Format(".tex", "LaTeX document", "formula"),
        Format(".mpl", "Maple", "formula"),
        Format(".m", "Mathematica", "formula"),
        Format(".py", "Python module (NumPy and SymPy)", "formula"),
        Format(".stl", "STL mesh (binary)", "mesh"),
        Format(".obj", "OBJ mesh", "mesh"),
        Format(".ply", "PLY mesh (binary)", "mesh"),
        Format(".vtp", "VTK PolyData (VTP)", "mesh"),
        Format(".step", "STEP AP242 (B-rep)", "cad"),
        Format(".stp", "STEP AP242 (B-rep, .stp)", "cad"),
        Format(".iges", "IGES 5.3 (trimmed surfaces)", "cad"),
        Format(".igs", "IGES 5.3 (trimmed surfaces, .igs)", "cad"),
        Format(".brep", "Open CASCADE BRep", "cad"),
        Format(".png", "PNG picture", "picture"),
    )
}
"""Suffix → format."""


def format_of(path: str | Path, fmt: str | None = None) -> Format:
    """The format of ``path``: ``fmt`` if given (``"stl"``, ``".stl"``, ``"patch.stl"``), else its
    suffix; ``ValueError`` naming the known formats otherwise."""
    if fmt is not None:
        suffix = "." + fmt.lower().lstrip(".").removeprefix("patch.")
    else:
        suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        shown = suffix if suffix else "(no suffix)"
        raise ValueError(f"unknown export format {shown} of {path}; use one of {', '.join(FORMATS)}")
    return FORMATS[suffix]


def is_patch_path(path: str | Path) -> bool:
    """Whether ``path`` names the patch (``….patch.stl``, ``….patch.step``) rather than the surface."""
    return Path(path).stem.lower().endswith(".patch")


def wants_patch(path: Path, fmt: str | None = None) -> bool:
    """Whether ``path`` (``NAME.patch.stl``) or ``fmt`` (``patch.step``) asks for the patch of
    the parameterization instead of the surface."""
    return is_patch_path(path) or (fmt is not None and fmt.lower().lstrip(".").startswith("patch."))
