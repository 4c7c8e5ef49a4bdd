"""The bundled example equations (``sorgui/resources/examples``), shared by the CLI and the GUI."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources


@dataclass(frozen=True)
class Example:
    """One bundled equation: its file stem and a title for menus."""

    name: str
    title: str


EXAMPLES: tuple[Example, ...] = (
    Example("paper-example-1", "Paper, Example 1 (degree 6, row 4)"),
    Example("paper-cubic", "Paper, cubic y² + z² = x³ + 3x² − 2x"),
    Example("torus", "Torus"),
    Example("cone", "Cone y² = 2xz"),
    Example("sphere", "Sphere"),
    Example("cylinder", "Cylinder of revolution"),
    Example("coaxial-blend", "Coaxial blend of a sphere and a cylinder"),
    Example("non-coaxial-blend", "Non-coaxial blend (not a SOR)"),
    Example("ellipsoid", "Ellipsoid (not a SOR)"),
    Example("rolling-ball-blend", "Canal: rolling-ball blend of a cylinder and an oblique plane"),
    Example("pipe-twisted-cubic", "Canal: pipe around a twisted cubic"),
    Example("dupin-cyclide", "Canal: Dupin cyclide"),
)


def example_text(name: str) -> str:
    """The equation text of the example ``name`` (a file stem of ``resources/examples``)."""
    if name not in {e.name for e in EXAMPLES}:
        raise KeyError(f"no example named {name!r}")
    path = resources.files("sorgui") / "resources" / "examples" / f"{name}.txt"
    return path.read_text(encoding="utf-8").strip()
