"""The Singular layer: locating the executable, running scripts, killing them, reading answers.

These tests run the real Singular (the one shipped by passagemath-singular); nothing is mocked
except the places where Singular is looked for.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.domains import QQ

from sorgui.engine.algebra.polys import number_field, poly_ring
from sorgui.engine.errors import (
    Cancelled,
    SingularError,
    SingularNotFound,
    SingularTimeout,
)
from sorgui.engine.singular import process as singular
from sorgui.engine.singular.process import (
    emit,
    find_singular,
    minpoly_to_singular,
    parse_int,
    parse_intvec,
    parse_list,
    parse_singular,
    poly_to_singular,
    results,
    run_script,
    run_singular,
)

X, Y, A = sympy.symbols("x y a")
NAMES = {"x": X, "y": Y, "a": A}
LOOP = "int i = 0; while (1) { i = i + 1; }"


@pytest.fixture
def clean_cache() -> Iterator[None]:
    """Forget located executables before and after, so no test sees another's answer."""
    singular._locate.cache_clear()
    yield
    singular._locate.cache_clear()


def children() -> set[int]:
    """Process ids of the live (non-zombie) children of this process (Linux ``/proc``)."""
    found = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            fields = stat.rsplit(")", 1)[1].split()
            if int(fields[1]) == os.getpid() and fields[0] != "Z":
                found.add(int(entry.name))
    return found


def alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


# --- locating ---------------------------------------------------------------------------------


def test_find_singular_returns_the_bundled_executable(clean_cache: None) -> None:
    path = find_singular()
    assert path.is_file() and os.access(path, os.X_OK)
    assert find_singular() == path


def test_environment_override_is_used(clean_cache: None, monkeypatch: pytest.MonkeyPatch) -> None:
    real = find_singular()
    monkeypatch.setenv(singular.ENV_VARIABLE, str(real))
    assert find_singular() == real


def test_override_pointing_nowhere_raises_singular_not_found(
    clean_cache: None, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv(singular.ENV_VARIABLE, str(tmp_path / "no-such-Singular"))
    with pytest.raises(SingularNotFound, match="SORGUI_SINGULAR"):
        find_singular()
    with pytest.raises(SingularNotFound):
        run_singular("1;")


def test_no_singular_anywhere_says_how_to_install_it(clean_cache: None, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(singular.ENV_VARIABLE, raising=False)
    monkeypatch.setattr(singular, "_wheel_singular", lambda: None)
    monkeypatch.setenv("PATH", "")
    with pytest.raises(SingularNotFound, match="pip install passagemath-singular"):
        find_singular()


# --- running ----------------------------------------------------------------------------------


def test_results_are_read_only_between_markers() -> None:
    script = (
        'print("noise before"); ring q = 0,(x,y),dp; short = 0;\n'
        + emit("square", "string((x+y)^2)")
        + emit("genus", "string(genus(y^2-x^5-1))")
        + 'int k; for (k = 1; k <= 3; k++) { sorguiEmit("loop", string(k)); }\n'
    )
    found = run_script(script)
    assert found["square"] == ["x^2+2*x*y+y^2"]
    assert found["genus"] == ["2"]
    assert found["loop"] == ["1", "2", "3"]
    assert "noise" not in str(found)


def test_results_ignore_text_outside_markers() -> None:
    assert results("banner\n// ** redefining foo\n") == {}


def test_syntax_error_raises_singular_error() -> None:
    with pytest.raises(SingularError, match="expected poly-expression"):
        run_singular("ring q = 0,(x,y),dp; poly f = x^2+;")


def test_error_inside_a_procedure_raises_singular_error() -> None:
    with pytest.raises(SingularError, match="ground field is not Q"):
        run_script("ring q = (0,a),(x,y,z),dp; minpoly = a^2-2;\ndef P = paraPlaneCurve(x^2+y^2-a*z^2);")


def test_timeout_raises_and_kills_singular() -> None:
    before = children()
    start = time.monotonic()
    with pytest.raises(SingularTimeout, match="1 s"):
        run_singular(LOOP, timeout=1)
    assert time.monotonic() - start < 3
    assert children() <= before


def test_cancel_kills_singular_quickly() -> None:
    before = children()
    cancel = threading.Event()
    timer = threading.Timer(0.3, cancel.set)
    timer.start()
    start = time.monotonic()
    with pytest.raises(Cancelled):
        run_singular(LOOP, timeout=30, cancel=cancel)
    assert time.monotonic() - start < 0.3 + 1.0  # Cancel stops Singular within a second, on a busy machine too
    assert children() <= before
    timer.join()


def test_cancel_before_the_start_runs_nothing() -> None:
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(Cancelled):
        run_singular("1;", cancel=cancel)


def test_kill_reaches_the_whole_process_group(tmp_path: Path) -> None:
    pid_file = tmp_path / "pid"
    script = f'system("sh", "sleep 60 & echo $! > {pid_file}");\n' + LOOP
    with pytest.raises(SingularTimeout):
        run_singular(script, timeout=1)
    pid = int(pid_file.read_text())
    deadline = time.monotonic() + 2
    while alive(pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not alive(pid)


# --- sending and reading polynomials ----------------------------------------------------------


def test_polynomials_go_to_singular_with_integer_coefficients() -> None:
    R = poly_ring(("s", "w"), QQ)
    s, w = R.gens
    text = poly_to_singular(QQ(1, 2) * s**2 - QQ(2, 3) * w + 1, ["x", "y"])
    assert "/" not in text
    assert sympy.expand(parse_singular(text, NAMES) - (3 * X**2 - 4 * Y + 6)) == 0


def test_algebraic_coefficients_become_polynomials_in_the_parameter() -> None:
    K = number_field((2, 3))
    R = poly_ring(("x", "y"), K)
    x, y = R.gens
    theta = K.ext.as_expr()
    c = K.from_sympy(sympy.sqrt(2) / 3 + 1)
    text = poly_to_singular(x**2 - c * y)
    assert "/" not in text
    m = parse_singular(minpoly_to_singular(K), NAMES)
    assert sympy.expand(m.subs(A, theta)) == 0
    value = parse_singular(text, NAMES).subs(A, theta)
    assert sympy.simplify(value / 6 - (X**2 - (sympy.sqrt(2) / 3 + 1) * Y)) == 0


def test_round_trip_through_singular_over_an_extension() -> None:
    K = number_field((2,))
    R = poly_ring(("x", "y"), K)
    x, y = R.gens
    r2 = K.from_sympy(sympy.sqrt(2))
    f = (x + r2 * y) ** 3 - QQ(1, 7) * r2
    script = (
        f"ring q = (0,a),(x,y),dp; minpoly = {minpoly_to_singular(K)}; short = 0;\n"
        f"poly F = {poly_to_singular(f)};\n" + emit("F", "string(F)")
    )
    back = parse_singular(run_script(script)["F"][0], NAMES).subs(A, sympy.sqrt(2))
    ratio = sympy.simplify(back / f.as_expr())
    assert ratio.is_Rational and ratio != 0


def test_parser_reads_singular_output() -> None:
    assert parse_singular("2*x^2-(a)*y", NAMES) == 2 * X**2 - A * Y
    assert parse_singular("(a^2-2)", NAMES) == A**2 - 2
    assert parse_singular("1/2*x^3+(-3*a+1)*y-x", NAMES) == X**3 / 2 + (1 - 3 * A) * Y - X
    assert parse_singular("-(2*a-1)/3", NAMES) == -(2 * A - 1) / 3
    assert parse_list("1,x-y,x+y", NAMES) == [1, X - Y, X + Y]
    assert parse_int(" -3 ") == -3
    assert parse_intvec("1,1,2") == [1, 1, 2]


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('true')",
        "x**2",
        "y6+x",  # short output: a2 would be ambiguous, we ask for short=0
        "x^",
        "(x+1",
        "x+1)",
        "1/0",
        "x^1000000000",
        "",
        "x;y",
        "lambda",
    ],
)
def test_parser_rejects_everything_else(text: str) -> None:
    with pytest.raises(SingularError):
        parse_singular(text, NAMES)


def test_integer_readers_reject_non_integers() -> None:
    with pytest.raises(SingularError):
        parse_int("1.5")
    with pytest.raises(SingularError):
        parse_intvec("1,x")


coefficients = st.fractions(min_value=-50, max_value=50, max_denominator=12)
terms = st.dictionaries(st.tuples(st.integers(0, 4), st.integers(0, 4)), coefficients, min_size=1, max_size=8)


@settings(max_examples=60, deadline=None)
@given(terms)
def test_sending_and_reading_back_is_the_identity_up_to_scale(terms: dict) -> None:
    R = poly_ring(("x", "y"), QQ)
    f = R.from_dict({m: QQ(c.numerator, c.denominator) for m, c in terms.items()})
    back = parse_singular(poly_to_singular(f), NAMES)
    if not f:
        assert back == 0
        return
    ratio = sympy.cancel(back / f.as_expr())
    assert ratio.is_Rational and ratio > 0


def test_sorguis_procedures_are_a_singular_library_shipped_as_package_data() -> None:
    import tomllib

    from sorgui.engine.singular.process import library_path, script_header

    path = library_path()
    text = path.read_text(encoding="utf-8")
    assert path.name == "sorgui.lib" and 'version="' in text
    for proc in ("sorguiAbsQQ", "sorguiAbsNorm", "sorguiParaCurve", "sorguiParametrize", "sorguiRealPointConic"):
        assert f"proc {proc}(" in text
    assert f'LIB "{path}";' in script_header()
    pyproject = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text(encoding="utf-8"))
    assert "engine/singular/*.lib" in pyproject["tool"]["setuptools"]["package-data"]["sorgui"]


@pytest.mark.parametrize(
    ("body", "said"),
    [
        ('cat > /dev/null\necho "%%%% garbage ? not Singular"\n', "did not report"),
        ('exec yes "garbage garbage garbage garbage"\n', "printed more than"),
    ],
)
def test_a_singular_that_prints_garbage_or_floods_is_one_line(tmp_path, monkeypatch, body: str, said: str) -> None:
    """A broken or foreign executable named by ``$SORGUI_SINGULAR``: the analysis says so in one
    line (the rationality undecided), never an internal error, and a flood is cut off."""
    from sorgui.engine import analyze

    fake = tmp_path / "Singular"
    fake.write_text("#!/bin/sh\n" + body)
    fake.chmod(0o755)
    monkeypatch.setenv("SORGUI_SINGULAR", str(fake))
    result = analyze("x^2 + y^2 - z^3", timeout=60)  # a cuspidal profile: Singular is asked
    status = result.rationality.status
    assert status.startswith("undecided: Singular") and said in status and "\n" not in status
