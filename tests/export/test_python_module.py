"""The Python export is imported and run: exact check(), NumPy points on the surface."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
import sympy

from sorgui.engine.results import Analysis
from sorgui.engine.values import read_expression
from sorgui.export.files import export_analysis
from tests.export.conftest import relative_residual

RELATIVE = 1e-9
"""|f(p)| / Σ|c·p^m| at the NumPy points: float rounding is ~1e-15, so this is generous."""


def canal_checks(analysis: Analysis) -> list[str]:
    """What check() verifies of the canal families: each spine m(t), and (m(t), ρ(t)) on the SMAT."""
    out = []
    for i, fam in enumerate(analysis.canal.families if analysis.canal else (), 1):
        if fam.parametrization is not None:
            out += [f"canal{i}M"] + ([f"canal{i}Rho"] if fam.radius_squared is not None else [])
    return out


def load(path: Path, name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", ["paper-example-1", "torus", "cone", "paper-cubic"])
def test_module_checks_and_evaluates_on_the_surface(analyses, tmp_path, name: str) -> None:
    analysis = analyses[name]
    path = export_analysis(analysis, tmp_path / f"{name.replace('-', '_')}.py")
    module = load(path, f"exported_{name.replace('-', '_')}")
    checked = module.check()
    assert checked == [
        "P2param",
        *[f"X{i}" for i in range(1, len(analysis.parametrizations) + 1)],
        *[f"C{i}" for i in range(1, len(analysis.conical.parametrizations if analysis.conical else ()) + 1)],
        *canal_checks(analysis),
    ]  # a circular cone is checked as a surface of revolution (X) and by its lines (C)
    assert sympy.expand(module.F - read_expression(analysis.recognition.polynomial)) == 0
    assert "parameter domain" in module.X1.__doc__ and "parameter domain" in module.P2param.__doc__
    s = np.linspace(-3.0, 3.0, 13)[:, None]
    t = np.linspace(-2.5, 4.0, 11)[None, :]
    for i, par in enumerate(analysis.parametrizations, 1):
        x, y, z = getattr(module, f"X{i}")(s, t)
        assert x.shape == y.shape == z.shape == (13, 11)
        points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
        assert np.all(np.isfinite(points))
        assert relative_residual(analysis.recognition.polynomial, points).max() <= RELATIVE
        if par.real:
            assert not np.iscomplexobj(points)
        x0, _y0, _z0 = getattr(module, f"X{i}")(0.5, 2.0)  # scalars work too
        assert np.ndim(x0) == 0


def test_check_fails_for_a_wrong_parameterization(analyses, tmp_path) -> None:
    path = export_analysis(analyses["torus"], tmp_path / "torus_wrong.py")
    text = path.read_text(encoding="utf-8").replace("X1_EXACT = (", "X1_EXACT = (S(1)/7 + ", 1)
    path.write_text(text, encoding="utf-8")
    module = load(path, "exported_torus_wrong")
    with pytest.raises(AssertionError, match="X1"):
        module.check()


def test_module_runs_as_a_script(analyses, tmp_path) -> None:
    import subprocess

    path = export_analysis(analyses["cone"], tmp_path / "cone.py")
    run = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "verified: P2param, X1, C1, canal1M, canal1Rho"


def test_rounded_input_carries_the_nearest_surfaces_maps_checked_on_it(tmp_path) -> None:
    """Rounded input is exactly no surface of revolution: its files print the nearest exact
    surface g's profile, rationality and maps (``nearestX1`` …), and check() substitutes each
    into ``g``; the Markdown report gives g's row of Table 1."""
    from sorgui.engine import analyze
    from sorgui.export.files import export_analysis as export

    text = (Path(__file__).parents[1] / "data" / "rounded-torus-15-digits.txt").read_text(encoding="utf-8")
    analysis = analyze(text)
    nearest = analysis.approximate.nearest
    assert nearest.within_rounding and nearest.analysis.parametrizations
    module = load(export(analysis, tmp_path / "rounded_torus.py"), "exported_rounded_torus")
    count = len(nearest.analysis.parametrizations)
    assert module.check() == ["nearestP2param", *[f"nearestX{i}" for i in range(1, count + 1)]]
    x, y, z = module.nearestX1(np.linspace(-2.0, 2.0, 5), 0.5)
    assert relative_residual(nearest.polynomial, np.stack([x, y, z], axis=1)).max() <= RELATIVE
    report = export(analysis, tmp_path / "rounded_torus.md").read_text(encoding="utf-8")
    assert "## Rationality of the nearest exact surface $g$ (within the rounding)" in report
    assert f"Table 1, row {nearest.analysis.rationality.table_row}:" in report and "nearestX_{1}(s, t) =" in report


def test_a_map_without_its_implicit_equation_is_not_checked_against_it(tmp_path) -> None:
    """A map over ``QQ(√2)`` has no implicit equation (Singular's elimination runs over ``QQ``):
    its module named an equation ``F`` it did not define, and failed with a ``NameError``."""
    from sorgui.engine import analyze

    analysis = analyze("(u, v, sqrt(2)*u*v)")
    assert not analysis.squarefree  # the implicit equation is not known
    path = export_analysis(analysis, tmp_path / "graph.py")
    module = load(path, "exported_graph")
    assert module.check() == []
    assert "# X1: not checked, the equation F it lies on is not known" in path.read_text(encoding="utf-8")
    x, y, z = module.X1(np.array([0.5]), np.array([2.0]))
    assert float(z[0]) == pytest.approx(np.sqrt(2))


def test_the_formula_files_of_a_map_in_angles_say_how_it_was_read(tmp_path) -> None:
    """The typed map in ``cos u`` is listed in ``t = tan(u/2)``: the formula files, which have no
    report beside them, say so."""
    from sorgui.engine import analyze

    analysis = analyze("x=(2+cos(v))*cos(u), y=(2+cos(v))*sin(u), z=sin(v)")
    for suffix in (".py", ".tex", ".m", ".mpl"):
        text = export_analysis(analysis, tmp_path / f"torus{suffix}").read_text(encoding="utf-8")
        assert "u is an angle" in text and "tan(u/2)" in text and "tan(v/2)" in text, suffix
