"""All Singular code of sorgui: find the executable, run scripts, send and read polynomials,
and sorgui's own Singular procedures (:data:`ABSOLUTE_FACTOR_PROCS`,
:data:`PARAMETRIZATION_PROCS`), which :mod:`.curves` drives.

Singular runs as a subprocess (docs/math.md §5: "run Singular as a subprocess with a time limit so
that a long computation can be cancelled"). A script reports its results with
:func:`emit`, which prints each value between markers unique to this Python process; only the
text between the markers is read, so banners, library chatter and echoed input never reach a
parser. Errors (Singular's ``? ...`` lines) raise :class:`SingularError`.

Polynomials go to Singular as strings with integer coefficients (:func:`poly_to_singular`;
a coefficient in ``K = QQ(θ)`` becomes a polynomial in the ring parameter ``a`` with
``minpoly = m(a)``, :func:`minpoly_to_singular`), and come back through
:func:`parse_singular`, a small recursive-descent parser of Singular's ``short=0`` output
(numbers, names, ``+ - * / ^`` and parentheses). Text from the subprocess is never evaluated.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import os
import re
import secrets
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Mapping, Sequence
from functools import lru_cache, reduce
from math import lcm
from pathlib import Path

import sympy
from sympy.polys.domains import QQ
from sympy.polys.domains.domain import Domain

from .errors import Cancelled, SingularError, SingularNotFound, SingularTimeout
from .polys import Poly, is_rational_field

ENV_VARIABLE = "SORGUI_SINGULAR"
"""Environment variable naming a ``Singular`` executable to use instead of the bundled one."""

LIBRARIES = ("normal.lib", "absfact.lib", "paraplanecurves.lib")
"""The Singular libraries every script loads (genus, absFactorize, paraPlaneCurve)."""

POLL_INTERVAL = 0.05
"""Seconds between checks of the cancel event and the time limit while Singular runs."""

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
    for path in (_wheel_singular(), shutil.which("Singular")):
        if path is not None and _is_executable(Path(path)):
            return Path(path)
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


def run_singular(
    script: str, *, timeout: float = 60.0, cancel: threading.Event | None = None
) -> str:
    """Run ``script`` (Singular code) and return its standard output.

    The process runs in its own process group, which is killed when ``timeout`` seconds pass
    (:class:`SingularTimeout`) or ``cancel`` is set (:class:`Cancelled`, within
    :data:`POLL_INTERVAL`). Singular errors (``? ...`` lines) raise :class:`SingularError`.
    """
    if cancel is not None and cancel.is_set():
        raise Cancelled("the Singular computation was cancelled")
    executable = find_singular()
    with tempfile.TemporaryDirectory(prefix="sorgui-singular-") as folder:
        path = Path(folder) / "script.sing"
        path.write_text(script + "\nquit;\n", encoding="utf-8")
        proc = subprocess.Popen(
            [str(executable), *_FLAGS, str(path)],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            cwd=folder,
            start_new_session=True,
            text=True,
        )
        out, err = _wait(proc, timeout, cancel)
    errors = _ERROR_LINE.findall(out) + _ERROR_LINE.findall(err)
    if errors:
        message = "; ".join(e.strip() for e in errors[:4])
        raise SingularError(f"Singular reported an error: {message}")
    if proc.returncode != 0:
        tail = (err or out).strip().splitlines()[-3:]
        raise SingularError(f"Singular exited with status {proc.returncode}: " + " ".join(tail))
    return out


def _wait(
    proc: subprocess.Popen[str], timeout: float, cancel: threading.Event | None
) -> tuple[str, str]:
    """Collect the output of ``proc``, killing its process group on timeout or cancel."""
    deadline = time.monotonic() + timeout
    try:
        while True:
            try:
                return proc.communicate(timeout=POLL_INTERVAL)
            except subprocess.TimeoutExpired:
                pass
            if cancel is not None and cancel.is_set():
                raise Cancelled("the Singular computation was cancelled")
            if time.monotonic() > deadline:
                raise SingularTimeout(
                    f"Singular did not finish within the time limit of {timeout:g} s"
                )
    except BaseException:  # cancel, timeout, KeyboardInterrupt: never leave Singular running
        _kill(proc)
        raise


def _kill(proc: subprocess.Popen[str]) -> None:
    """Kill the whole process group of ``proc`` (Singular may fork helpers) and reap it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.communicate()


def script_header() -> str:
    """The first lines of every script: the libraries, quiet library messages, and the proc
    ``sorguiEmit(name, value)`` that prints the string ``value`` as the result ``name``."""
    libs = " ".join(f'LIB "{lib}";' for lib in LIBRARIES)
    return (
        f"{libs}\nprintlevel = -10;\n"
        "proc sorguiEmit(string name, string value)\n"
        f'{{ print("{_BEGIN} " + name); print(value); print("{_END}"); }}\n'
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


def results(output: str) -> dict[str, list[str]]:
    """The results printed by :func:`emit` in ``output``: for each name, its texts in order
    (a name emitted inside a Singular loop has several)."""
    found: dict[str, list[str]] = {}
    for name, text in _BLOCK.findall(output):
        found.setdefault(name, []).append(text.strip())
    return found


def run_script(
    script: str, *, timeout: float = 60.0, cancel: threading.Event | None = None
) -> dict[str, list[str]]:
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


def _coefficient_list(K: Domain, c: object) -> list:
    """The rational coordinates of ``c ∈ K`` in powers of θ, highest first."""
    if is_rational_field(K):
        return [QQ.convert(c)]
    return [QQ.convert(q) for q in c.to_list()] or [QQ.zero]


def _integer_poly(coeffs: Sequence, parameter: str) -> str:
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

_TOKENS = re.compile(r"\s*(?:(\d+)|([A-Za-z_][A-Za-z_0-9]*)|(.))")
_MAX_EXPONENT = 10_000


def parse_singular(text: str, symbols: Mapping[str, sympy.Expr]) -> sympy.Expr:
    """Read one polynomial (or number) printed by Singular with ``short=0``.

    ``symbols`` maps each allowed name (ring variables, the parameter ``a``) to a sympy
    expression; any other name, or any other character, raises :class:`SingularError`.
    """
    return _Parser(text, symbols).parse()


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


class _Parser:
    """Recursive descent over ``sum := ['-'] product (('+'|'-') product)*``,
    ``product := power (('*'|'/') power)*``, ``power := atom ['^' integer]``,
    ``atom := integer | name | '(' sum ')'``."""

    def __init__(self, text: str, symbols: Mapping[str, sympy.Expr]) -> None:
        self.text = text
        self.symbols = symbols
        self.tokens: list[tuple[str, str]] = []
        for match in _TOKENS.finditer(text.strip()):
            number, name, other = match.groups()
            if number is not None:
                self.tokens.append(("int", number))
            elif name is not None:
                self.tokens.append(("name", name))
            elif other is not None and not other.isspace():
                self.tokens.append(("op", other))
        self.pos = 0

    def fail(self, why: str) -> SingularError:
        return SingularError(f"cannot read Singular's answer {self.text[:200]!r}: {why}")

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.pos] if self.pos < len(self.tokens) else None

    def take(self, op: str) -> bool:
        if self.peek() == ("op", op):
            self.pos += 1
            return True
        return False

    def parse(self) -> sympy.Expr:
        if not self.tokens:
            raise self.fail("it is empty")
        value = self.sum()
        if self.peek() is not None:
            raise self.fail(f"unexpected {self.peek()[1]!r}")
        return value

    def sum(self) -> sympy.Expr:
        terms = [-self.product() if self.take("-") else self.product()]
        while True:
            if self.take("+"):
                terms.append(self.product())
            elif self.take("-"):
                terms.append(-self.product())
            else:
                return sympy.Add(*terms)

    def product(self) -> sympy.Expr:
        value = self.power()
        while True:
            if self.take("*"):
                value = value * self.power()
            elif self.take("/"):
                divisor = self.power()
                if divisor == 0:
                    raise self.fail("division by zero")
                value = value / divisor
            else:
                return value

    def power(self) -> sympy.Expr:
        base = self.atom()
        if self.take("^"):
            token = self.peek()
            if token is None or token[0] != "int" or int(token[1]) > _MAX_EXPONENT:
                raise self.fail("an exponent must be a small integer")
            self.pos += 1
            return base ** int(token[1])
        return base

    def atom(self) -> sympy.Expr:
        token = self.peek()
        if token is None:
            raise self.fail("it ends too early")
        self.pos += 1
        kind, text = token
        if kind == "int":
            return sympy.Integer(int(text))
        if kind == "name":
            if text not in self.symbols:
                raise self.fail(f"unknown name {text!r}")
            return self.symbols[text]
        if text == "(":
            value = self.sum()
            if not self.take(")"):
                raise self.fail("a parenthesis is not closed")
            return value
        raise self.fail(f"unexpected {text!r}")


# --- sorgui's Singular procedures -----------------------------------------------------------
# Sent after script_header(). Rings and variables inside procs are local, so one script can
# handle several curves without name clashes; results leave through sorguiEmit. Never name a
# global ring `r`: it breaks paraplanecurves.lib's `map perm = basering, ...`.

ABSOLUTE_FACTOR_PROCS = """
proc sorguiAbsQQ(poly F, string key, int withGenus)
{
  // absFactorize over QQ; the genus only for an absolutely irreducible curve
  def B = basering;
  def A = absFactorize(F, "a");
  setring A; short = 0;
  sorguiEmit("factors_" + key, string(absolute_factors[1]));
  sorguiEmit("mult_" + key, string(absolute_factors[2]));
  sorguiEmit("minpolys_" + key, string(absolute_factors[3]));
  sorguiEmit("count_" + key, string(absolute_factors[4]));
  int irreducible = (absolute_factors[4] == 1);
  setring B;
  if (withGenus && irreducible) { sorguiEmit("genus_" + key, string(genus(F))); }
}

proc sorguiAbsNorm(poly G, poly m, int d, string key, int withGenus)
{
  // G in QQ[x,y,t] square-free over QQ(t)/m(t), m of degree d: absolute factors of G
  // through the norm of its shift (Trager), each class with the root c(a) of m it needs
  def BN = basering;
  int s = 0;
  poly N = resultant(G, m, t);
  while ((deg(gcd(gcd(N, diff(N, x)), diff(N, y))) > 0) && (s < 30))
  {
    s = s + 1;
    N = resultant(subst(G, x, x + s*t, y, y + s^2*t), m, t);
  }
  sorguiEmit("squarefree_" + key, string(deg(gcd(gcd(N, diff(N, x)), diff(N, y))) <= 0));
  poly Gs = subst(G, x, x + s*t, y, y + s^2*t);
  ring QN = 0,(x,y),dp;
  poly N = imap(BN, N);
  def A = absFactorize(N, "a");
  setring A; short = 0;
  list L = absolute_factors;
  sorguiEmit("count_" + key, string(L[4]));
  int irreducible = (L[4] == d);
  int k; int j; string mu; string h;
  for (k = 2; k <= size(L[1]); k++)
  {
    setring A;
    mu = string(L[3][k]); h = string(L[1][k]);
    ring E = (0,a),(x,y,t),dp;
    execute("minpoly = " + mu + ";");
    short = 0;
    execute("poly H = " + h + ";");
    poly Gs = imap(BN, Gs); poly m = imap(BN, m);
    ideal R = factorize(m, 1);
    for (j = 1; j <= size(R); j++)
    {
      if (deg(R[j]) == 1)
      {
        number c = -leadcoef(subst(R[j], t, 0)) / leadcoef(R[j]);
        if (reduce(subst(Gs, t, c), std(H)) == 0)
        {
          poly U = subst(H, x, x - s*c, y, y - s^2*c);
          sorguiEmit("class_" + key, mu + "|" + string(c) + "|" + string(U));
        }
        kill c;
      }
    }
    setring A; kill E;
  }
  setring BN;
  if (withGenus && irreducible) { sorguiEmit("genus_" + key, string(genus(ideal(G, m)))); }
}
"""
"""``sorguiAbsQQ(F, key, withGenus)`` (``absFactorize`` over ``QQ``; results ``factors_<key>``,
``mult_<key>``, ``minpolys_<key>``, ``count_<key>``, ``genus_<key>``) and ``sorguiAbsNorm(G, m, d,
key, withGenus)`` (the norm route over ``QQ[t]/m(t)``; results ``squarefree_<key>``,
``count_<key>``, one ``class_<key>`` ``"mu|c|factor"`` per class, ``genus_<key>``)."""


PARAMETRIZATION_PROCS = """
proc sorguiEval(poly q, list P)
{
  return(leadcoef(subst(q, var(1), P[1], var(2), P[2], var(3), P[3])));
}

proc sorguiRealPointConic(poly q)
{
  // rationalPointConic, unless it chose an imaginary field for a conic with real points:
  // then a line through an interior point (the pole of a line missing the conic, or simply
  // a secant coordinate line) meets it in a point over a real quadratic field QQ(a).
  def R0 = basering;
  def S = rationalPointConic(q);
  setring S;
  if (npars(S) == 0) { return(S); }
  string sq = string(par(1)^2);
  setring R0;
  execute("number square = " + sq + ";");
  if (square > 0) { return(S); }
  list E1 = number(1), number(0), number(0);
  list E2 = number(0), number(1), number(0);
  list E3 = number(0), number(0), number(1);
  number m11 = sorguiEval(q, E1); number m22 = sorguiEval(q, E2); number m33 = sorguiEval(q, E3);
  number m12 = (sorguiEval(q, list(number(1), number(1), number(0))) - m11 - m22) / 2;
  number m13 = (sorguiEval(q, list(number(1), number(0), number(1))) - m11 - m33) / 2;
  number m23 = (sorguiEval(q, list(number(0), number(1), number(1))) - m22 - m33) / 2;
  number tr = m11 + m22 + m33;
  number e2 = m11*m22 - m12^2 + m11*m33 - m13^2 + m22*m33 - m23^2;
  number dt = m11*(m22*m33 - m23^2) - m12*(m12*m33 - m13*m23) + m13*(m12*m23 - m13*m22);
  if (e2 > 0 && ((tr > 0 && dt > 0) || (tr < 0 && dt < 0))) { return(S); }
  list P = E1; list Q = E2;
  number A = m11; number C = m22; number B = 2*m12;
  number D = B^2 - 4*A*C;
  if (D <= 0)
  {
    P = list(m12*m23 - m13*m22, m13*m12 - m11*m23, m11*m22 - m12^2);
    if (P[2] == 0 && P[3] == 0) { Q = E2; } else { Q = E1; }
    A = sorguiEval(q, P); C = sorguiEval(q, Q);
    B = sorguiEval(q, list(P[1] + Q[1], P[2] + Q[2], P[3] + Q[3])) - A - C;
    D = B^2 - 4*A*C;
  }
  bigint N = bigint(numerator(D)) * bigint(denominator(D));
  bigint s = 1; bigint p = 2;
  while (p <= 1000 && p*p <= N)
  {
    while (N mod (p*p) == 0) { N = N div (p*p); s = s*p; }
    p = p + 1;
  }
  number root = number(s) / denominator(D);
  string pt = "matrix point[1][3];";
  int i;
  for (i = 1; i <= 3; i++)
  {
    pt = pt + "point[1," + string(i) + "] = (" + string(-B) + " + (" + string(root) + ")*a)*("
         + string(P[i]) + ") + 2*(" + string(A) + ")*(" + string(Q[i]) + ");";
  }
  list L = ring_list(R0);
  L[1] = list(0, list("a"), list(list("lp", 1)), ideal(0));
  def RTemp = ring(L);
  setring RTemp;
  list L = ringlist(RTemp);
  L[1][4] = ideal(a^2 - N);
  def S2 = ring(L);
  setring S2;
  execute(pt);
  export(point);
  return(S2);
}

proc sorguiProjConic(poly q)
{
  // projConic of paraplanecurves.lib with sorguiRealPointConic: the pencil through the point.
  def R0 = basering;
  list rl = ring_list(R0);
  rl[3] = list(list("dp",1:3),list("C",0));
  def RP20 = ring(rl);
  setring RP20;
  poly q = imap(R0,q);
  def RP21 = sorguiRealPointConic(q);
  setring RP21;
  list rl1 = ring_list(RP21);
  rl1[2] = list("u","v","w");
  rl1[3] = list(list("dp",1:3),list("C",0));
  def RP2 = ring(rl1);
  setring RP2;
  ideal point = fetch(RP21,point);
  matrix bP = syz(point);
  ideal Ipoint = matrix(maxideal(1))*bP;
  export(Ipoint);
  return(RP2);
}

proc sorguiParametrize(poly f)
{
  // paraPlaneCurve of paraplanecurves.lib (odd degree: itself; even degree: the same steps
  // with sorguiProjConic), for f homogeneous, absolutely irreducible, of genus 0.
  int d = deg(f);
  if ((d mod 2) == 1) { return(paraPlaneCurve(f)); }
  def Roriginal = basering;
  list rl = ring_list(Roriginal);
  rl[2] = list("x","y","z");
  rl[3] = list(list("dp",1:3),list("C",0));
  def RP2 = ring(rl);
  setring RP2;
  poly f = fetch(Roriginal,f);
  if (d == 2)
  {
    def RPc = sorguiProjConic(f);
    setring RPc;
    def rp1 = invertBirMap(Ipoint, ideal(fetch(RP2,f)));
  }
  else
  {
    int k;
    ideal AI = adjointIdeal(f, list(2, "rattestyes/firstchecksdone"));
    def Rrnc = mapToRatNormCurve(f, AI);
    setring Rrnc;
    int m = d-1;
    def RP2conic = rncItProjEven(RNC);
    setring RP2conic;
    def RPc = sorguiProjConic(CONIC);
    def Rbig = RPc + Rrnc;
    setring Rbig;
    ideal PHI = imap(Rrnc,PHI);
    ideal PROJ = imap(RPc,Ipoint);
    for (k = 1; k <= 3; k++) { PROJ = subst(PROJ,var(k),PHI[k]); }
    ideal AI = fetch(RP2,AI);
    for (k = 1; k <= m; k++) { PROJ = subst(PROJ,var(k+3),AI[k]); }
    setring RPc;
    ideal If = ideal(fetch(RP2,f));
    ideal PROJ = imap(Rbig,PROJ);
    def rp1 = invertBirMap(PROJ,If);
  }
  setring rp1;
  list rl1 = ring_list(rp1);
  rl1[2] = list("s","t");
  def RP1 = ring(rl1);
  setring RP1;
  ideal PARA = fetch(rp1,psi);
  export(PARA);
  return(RP1);
}

proc sorguiParaCurve(poly F, int checked)
{
  // the checks (absolutely irreducible, genus 0) unless the caller made them, then PARA and
  // the field's minpoly
  def B = basering;
  int irreducible = 1;
  int g = 0;
  if (!checked)
  {
    def A = absFactorize(F, "a");
    setring A;
    irreducible = (absolute_factors[4] == 1);
    setring B;
  }
  sorguiEmit("irreducible", string(irreducible));
  if (!irreducible) { return(); }
  if (!checked) { g = genus(F); }
  sorguiEmit("genus", string(g));
  if (g != 0) { return(); }
  ring H = 0,(x,y,z),dp;
  poly f = homog(imap(B, F), z);
  def P = sorguiParametrize(f);
  setring P; short = 0;
  if (npars(P) > 0) { sorguiEmit("minpoly", string(minpoly)); }
  sorguiEmit("para", string(PARA));
}
"""
"""``sorguiParaCurve(F, checked)`` for ``F ∈ QQ[x, y]`` (``checked = 1``: the caller knows ``F`` is
absolutely irreducible of genus 0): results ``irreducible``, ``genus``, and for a
rational curve ``para`` (paraPlaneCurve's PARA in ``s, t``) and ``minpoly`` (of ``a``, when the
field is an extension). ``sorguiParametrize`` is paraPlaneCurve with the conic step replaced by
``sorguiRealPointConic``, which prefers a real quadratic field."""
