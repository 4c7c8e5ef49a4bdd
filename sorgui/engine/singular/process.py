"""All Singular code of sorgui: find the executable, run scripts, send and read polynomials.

sorgui's own Singular procedures live in the library ``sorgui.lib`` beside this module
(shipped as package data); every script loads it, and :mod:`.curves` calls its procedures.

Singular runs as a subprocess (docs/math.md §5: "run Singular as a subprocess with a time limit
so that a long computation can be cancelled"). It never outlives sorgui: it leads a process
group that is killed on a time limit, a cancel or any exception (``KeyboardInterrupt``, or the
command line's handlers of ``SIGTERM`` and ``SIGHUP``), and on Linux the kernel kills it when
the thread that started it dies, even by ``kill -9`` (``PR_SET_PDEATHSIG``); a CPU-time limit
(``RLIMIT_CPU``) a little above the wall-clock limit bounds it on every POSIX system.

The script goes to Singular's standard input, so nothing is written to disk and nothing is
left behind. A script reports its results with :func:`emit`, which prints each value between markers unique
to this Python process; only the text between the markers is read, so banners, library
chatter and echoed input never reach a parser. Errors (Singular's ``? ...`` lines) raise
:class:`SingularError`.

Polynomials go to Singular as strings with integer coefficients (:func:`poly_to_singular`;
a coefficient in ``K = QQ(θ)`` becomes a polynomial in the ring parameter ``a`` with
``minpoly = m(a)``, :func:`minpoly_to_singular`), and come back through
:func:`parse_singular`, the reader of :mod:`.expressions` restricted to Singular's ``short=0``
output. Text from the subprocess is never evaluated.
"""

from __future__ import annotations

import contextlib
import importlib.metadata
import importlib.resources
import importlib.util
import os
import re
import resource
import secrets
import selectors
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from functools import lru_cache, reduce
from math import ceil, lcm
from pathlib import Path
from typing import Any

import sympy
from flint import fmpq
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from ..algebra.polys import Poly, is_rational_field
from ..errors import (
    Cancelled,
    ExpressionError,
    SingularError,
    SingularNotFound,
    SingularTimeout,
)
from ..expressions import read, singular_syntax
from ..lifetime import die_with_parent

ENV_VARIABLE = "SORGUI_SINGULAR"
"""Environment variable naming a ``Singular`` executable to use instead of the bundled one."""

LIBRARIES = ("normal.lib", "absfact.lib", "paraplanecurves.lib")
"""The Singular libraries every script loads (genus, absFactorize, paraPlaneCurve)."""

LIBRARY = "sorgui.lib"
"""sorgui's own procedures (package data of :mod:`sorgui.engine`), loaded after :data:`LIBRARIES`."""

CPU_MARGIN = 5
"""Seconds of CPU time Singular may use beyond its wall-clock limit before the kernel stops it."""

POLL_INTERVAL = 0.05
"""Seconds between checks of the cancel event and the time limit while Singular runs."""

MAX_OUTPUT = 256 * 2**20
"""Bytes of output Singular may print for one script; more is no answer (a broken or foreign
executable flooding its output), and Singular is killed."""

_FLAGS = ("-q", "-t", "--no-rc", "--no-warn", "--random=4711")
# -q: no banner or library messages; -t: no terminal handling; --no-rc: ignore ~/.singularrc;
# --no-warn: drop "// ** redefining ..." warnings; --random: a fixed seed, so that the randomised
# steps of paraplanecurves.lib (rational points on conics) give reproducible answers.

_TOKEN = secrets.token_hex(8)
_BEGIN = f"@@sorgui-{_TOKEN}-begin@@"
_END = f"@@sorgui-{_TOKEN}-end@@"
_BLOCK = re.compile(re.escape(_BEGIN) + r" (\w+)\n(.*?)\n" + re.escape(_END), re.DOTALL)
_ERROR_LINE = re.compile(r"^\s*\?\s?(.*)$", re.MULTILINE)


# --- locating the executable ----------------------------------------------------------------


def find_singular() -> Path:
    """The ``Singular`` executable: ``$SORGUI_SINGULAR``, else the one in the passagemath-singular
    wheel, else ``Singular`` on ``PATH``. Raises :class:`SingularNotFound` when there is none."""
    return _locate(os.environ.get(ENV_VARIABLE) or None)


@lru_cache(maxsize=8)
def _locate(override: str | None) -> Path:
    """Cached per override value; a failed search raises and is therefore never cached."""
    if override is not None:
        path = Path(override).expanduser()
        if _is_executable(path):
            return path
        raise SingularNotFound(
            f"${ENV_VARIABLE} is set to {override!r}, which is not an executable file; "
            f"unset it or point it to a Singular binary"
        )
    for candidate in (_wheel_singular(), shutil.which("Singular")):
        if candidate is not None and _is_executable(Path(candidate)):
            return Path(candidate)
    raise SingularNotFound(
        "Singular was not found: install it with `pip install passagemath-singular` "
        f"(which ships the executable), install a system Singular, or set ${ENV_VARIABLE}"
    )


def _wheel_singular() -> Path | None:
    """``sage_wheels/bin/Singular`` of the passagemath-singular distribution, if installed."""
    try:
        files = importlib.metadata.distribution("passagemath-singular").files or []
    except importlib.metadata.PackageNotFoundError:
        files = []
    for entry in files:
        if entry.parts[-3:] == ("sage_wheels", "bin", "Singular"):
            return Path(str(entry.locate()))
    spec = importlib.util.find_spec("sage_wheels")
    for folder in (spec.submodule_search_locations or []) if spec else []:
        candidate = Path(folder) / "bin" / "Singular"
        if candidate.exists():
            return candidate
    return None


def _is_executable(path: Path) -> bool:
    return path.is_file() and os.access(path, os.X_OK)


# --- running scripts ------------------------------------------------------------------------


def run_singular(script: str, *, timeout: float = 60.0, cancel: threading.Event | None = None) -> str:
    """Run ``script`` (Singular code) and return its standard output.

    The process runs in its own process group, which is killed when ``timeout`` seconds pass
    (:class:`SingularTimeout`) or ``cancel`` is set (:class:`Cancelled`, within
    :data:`POLL_INTERVAL`), or when any exception reaches this function; it dies with the
    calling thread (:func:`_child_limits`). Singular errors (``? ...`` lines) raise
    :class:`SingularError`.
    """
    if cancel is not None and cancel.is_set():
        raise Cancelled("the Singular computation was cancelled")
    try:
        proc = subprocess.Popen(
            [str(find_singular()), *_FLAGS],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            cwd=tempfile.gettempdir(),
            start_new_session=True,
            preexec_fn=_child_limits(timeout),
        )
    except OSError as exc:  # a limit on processes (ulimit -u) or on memory
        raise SingularError(f"Singular could not be started: {exc.strerror or exc}") from None
    out, err = _wait(proc, script + "\nquit;\n", timeout, cancel)
    errors = _ERROR_LINE.findall(out) + _ERROR_LINE.findall(err)
    if errors:
        message = "; ".join(e.strip() for e in errors[:4])
        raise SingularError(f"Singular reported an error: {message}")
    if proc.returncode != 0:
        tail = (err or out).strip().splitlines()[-3:]
        raise SingularError(f"Singular exited with status {proc.returncode}: " + " ".join(tail))
    return out


def _wait(
    proc: subprocess.Popen[bytes], script: str, timeout: float, cancel: threading.Event | None
) -> tuple[str, str]:
    """Send ``script`` to ``proc`` and collect its output (at most :data:`MAX_OUTPUT`), killing
    its process group on timeout, cancel, a flood of output or any exception."""
    deadline = time.monotonic() + timeout
    try:
        assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
        with selectors.DefaultSelector() as selector:
            data = script.encode("utf-8")
            sent = 0
            os.set_blocking(proc.stdin.fileno(), False)
            selector.register(proc.stdin, selectors.EVENT_WRITE)
            chunks: dict[int, list[bytes]] = {proc.stdout.fileno(): [], proc.stderr.fileno(): []}
            for stream in (proc.stdout, proc.stderr):
                selector.register(stream, selectors.EVENT_READ)
            size = 0
            while selector.get_map():
                for key, _events in selector.select(POLL_INTERVAL):
                    if key.fileobj is proc.stdin:
                        try:
                            sent += os.write(key.fd, data[sent : sent + 65536])
                        except BrokenPipeError:
                            sent = len(data)
                        if sent >= len(data):
                            selector.unregister(proc.stdin)
                            proc.stdin.close()
                        continue
                    chunk = os.read(key.fd, 65536)
                    if not chunk:
                        selector.unregister(key.fileobj)
                        continue
                    chunks[key.fd].append(chunk)
                    size += len(chunk)
                    if size > MAX_OUTPUT:
                        raise SingularError(
                            f"Singular printed more than {MAX_OUTPUT // 2**20} MB: not an answer of sorgui's script"
                        )
                if cancel is not None and cancel.is_set():
                    raise Cancelled("the Singular computation was cancelled")
                if time.monotonic() > deadline:
                    raise SingularTimeout(f"Singular did not finish within the time limit of {timeout:g} s")
            while proc.poll() is None:  # its output is closed: it is exiting
                if time.monotonic() > deadline:
                    raise SingularTimeout(f"Singular did not finish within the time limit of {timeout:g} s")
                time.sleep(0.001)
        out, err = (b"".join(chunks[s.fileno()]).decode("utf-8", "replace") for s in (proc.stdout, proc.stderr))
        proc.stdout.close()
        proc.stderr.close()
        return out, err
    except BaseException:  # cancel, timeout, KeyboardInterrupt: never leave Singular running
        _kill(proc)
        raise


def _kill(proc: subprocess.Popen[bytes]) -> None:
    """Kill the whole process group of ``proc`` (Singular may fork helpers) and reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    for stream in (proc.stdin, proc.stdout, proc.stderr):
        if stream is not None:
            with contextlib.suppress(OSError, ValueError):
                stream.close()
    proc.wait()


def _child_limits(timeout: float) -> Callable[[], None]:
    """What the child runs before ``exec``: die with the parent thread, at most ``timeout`` +
    :data:`CPU_MARGIN` seconds of CPU time."""
    parent = os.getpid()
    seconds = min(ceil(timeout) + CPU_MARGIN, 2**31 - 1)

    def limit() -> None:
        if die_with_parent(signal.SIGKILL) and os.getppid() != parent:
            os._exit(1)  # the parent died before the kernel was asked
        resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds + 1))

    return limit


def library_path() -> Path:
    """The file of sorgui's Singular library :data:`LIBRARY`."""
    return Path(str(importlib.resources.files(__package__) / LIBRARY))


def script_header() -> str:
    """The first lines of every script: the libraries (Singular's and sorgui's), quiet library
    messages, and the proc ``sorguiEmit(name, value)`` that prints the string ``value`` as the
    result ``name``."""
    libs = " ".join(f'LIB "{lib}";' for lib in (*LIBRARIES, library_path()))
    return (
        "proc sorguiEmit(string name, string value)\n"
        f'{{ print("{_BEGIN} " + name); print(value); print("{_END}"); }}\n'
        f"{libs}\nprintlevel = -10;\n"
    )


def emit(name: str, value: str) -> str:
    """Singular code reporting the string expression ``value`` as the result named ``name``.

    Run ``short = 0;`` in the current ring first so that powers print as ``x^2``. Inside
    loops, call ``sorguiEmit`` directly with a computed name; a repeated name is collected as
    a list by :func:`results`.
    """
    if not re.fullmatch(r"\w+", name):
        raise ValueError(f"result names are identifiers, not {name!r}")
    return f'sorguiEmit("{name}", {value});\n'


class Results(dict[str, list[str]]):
    """The results of a script by name; a name Singular did not report raises
    :class:`SingularError` (its output was garbled, or it stopped early), never ``KeyError``."""

    def __missing__(self, name: str) -> list[str]:
        raise SingularError(f"Singular did not report {name!r}: its output is not what sorgui's script prints")


def results(output: str) -> Results:
    """The results printed by :func:`emit` in ``output``: for each name, its texts in order
    (a name emitted inside a Singular loop has several)."""
    found = Results()
    for name, text in _BLOCK.findall(output):
        found.setdefault(name, []).append(text.strip())
    return found


def run_script(script: str, *, timeout: float = 60.0, cancel: threading.Event | None = None) -> Results:
    """:func:`run_singular` on ``script_header() + script``, returning :func:`results`."""
    return results(run_singular(script_header() + script, timeout=timeout, cancel=cancel))


# --- sending polynomials --------------------------------------------------------------------


def poly_to_singular(f: Poly, names: Sequence[str] | None = None, parameter: str = "a") -> str:
    """``f`` as Singular input with integer coefficients, scaled by a positive rational.

    Over ``K = QQ(θ)`` each coefficient becomes a polynomial in ``parameter`` (standing for the
    primitive element θ, in a ring with ``minpoly`` from :func:`minpoly_to_singular`). Scaling
    does not change the curve ``f = 0``; it keeps ``/`` out of the script.
    """
    names = [str(n) for n in (names or f.ring.symbols)]
    K = f.ring.domain
    coeffs = {m: _coefficient_list(K, c) for m, c in f.items()}
    denominator = reduce(lcm, (int(QQ.denom(q)) for cs in coeffs.values() for q in cs), 1)
    terms = []
    for monom, cs in sorted(coeffs.items(), reverse=True):
        number = _integer_poly([q * denominator for q in cs], parameter)
        powers = [f"{v}^{e}" if e > 1 else v for v, e in zip(names, monom) if e]
        terms.append("*".join([f"({number})", *powers]))
    return "+".join(terms) or "0"


def minpoly_to_singular(K: Domain, parameter: str = "a") -> str:
    """The minimal polynomial ``m`` of the primitive element of ``K`` in ``parameter``
    (integer coefficients), for ``minpoly = ...;`` or ``ideal(F, m)``."""
    if is_rational_field(K):
        raise ValueError("QQ has no minimal polynomial")
    coeffs = [QQ.convert(c) for c in K.mod.to_list()]
    denominator = reduce(lcm, (int(QQ.denom(q)) for q in coeffs), 1)
    return _integer_poly([q * denominator for q in coeffs], parameter)


def _coefficient_list(K: Domain, c: Any) -> list[fmpq]:
    """The rational coordinates of ``c ∈ K`` in powers of θ, highest first."""
    if is_rational_field(K):
        return [QQ.convert(c)]
    return [QQ.convert(q) for q in c.to_list()] or [QQ.zero]


def _integer_poly(coeffs: Sequence[fmpq], parameter: str) -> str:
    """A univariate polynomial (integer coefficients, highest degree first) as Singular text."""
    n = len(coeffs) - 1
    parts = []
    for i, q in enumerate(coeffs):
        if q:
            e = n - i
            power = "" if e == 0 else f"*{parameter}" + (f"^{e}" if e > 1 else "")
            parts.append(f"({int(q)}){power}")
    return "+".join(parts) or "0"


# --- reading polynomials --------------------------------------------------------------------


def parse_singular(text: str, symbols: Mapping[str, sympy.Expr]) -> sympy.Expr:
    """Read one polynomial (or number) printed by Singular with ``short=0``.

    ``symbols`` maps each allowed name (ring variables, the parameter ``a``) to a sympy
    expression; any other name, or any other character, raises :class:`SingularError`.
    The reader is :mod:`.expressions`, shared with the exporters.
    """
    try:
        return read(text, singular_syntax(symbols))
    except ExpressionError as exc:
        raise SingularError(f"cannot read Singular's answer {text[:200]!r}: {exc.message}") from None


def parse_list(text: str, symbols: Mapping[str, sympy.Expr]) -> list[sympy.Expr]:
    """Read a comma-separated list of polynomials (``string(ideal)``)."""
    return [parse_singular(part, symbols) for part in text.split(",")]


def parse_int(text: str) -> int:
    """Read an integer printed by Singular."""
    if not re.fullmatch(r"\s*-?\d+\s*", text):
        raise SingularError(f"expected an integer from Singular, got {text!r}")
    return int(text)


def parse_intvec(text: str) -> list[int]:
    """Read an ``intvec`` printed by Singular as ``string(v)`` (``1,2,3``)."""
    return [parse_int(part) for part in text.split(",")]
