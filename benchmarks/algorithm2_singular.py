"""Benchmark: ``sorgui analyze --recognition-only`` against the paper's Algorithm II in Singular.

Both run as whole processes on the surfaces of revolution in general position of
:mod:`benchmarks.recognition` (degrees 10 and 20): ``python -m sorgui.cli analyze
--recognition-only -f FILE`` and ``Singular -q SCRIPT``, the Singular executable that sorgui
itself uses. The script is :data:`ALGORITHM_II`, the paper's Algorithm II (docs/math.md §2)
over QQ: normals of the level sets ``f = f(p)`` at random rational points ``p`` of space (the
theorem "SORs are onions": the points need not lie on X), their Plücker coordinates
``(∇f(p) : p × ∇f(p))``, five linearly independent ones, the axis ``(a : ā)`` as the kernel of
the 5×6 system ``n·ā + n̄·a = 0``, the check that it is a line, and then the exact test of the
profile in a frame of the axis. Each figure is the median over ``--repeats`` runs of the wall
time and of the CPU time (user + system of the process and of every process it started). Run
``python -m benchmarks.algorithm2_singular [--repeats N] [--write]`` from the repository root.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

from benchmarks.recognition import surface
from benchmarks.report import ROOT, process_times, run
from sorgui.engine.algebra.polys import poly_str
from sorgui.engine.singular.process import find_singular, poly_to_singular

DEGREES = (10, 20)

ALGORITHM_II = """
ring r = 0, (x, y, z), dp;
poly f = %(f)s;
poly fx = diff(f, x); poly fy = diff(f, y); poly fz = diff(f, z);
// Algorithm II, steps 1-8: normals at random rational points of space, Pluecker coordinates
// N = (n : nb) = (grad f(p) : p x grad f(p)); the axis A = (a : ab) satisfies n.ab + nb.a = 0.
matrix N[5][6];
matrix R[1][6];
int found = 0; int tries = 0; int k;
number px; number py; number pz; number gx; number gy; number gz;
while (found < 5 and tries < 100) {
  tries = tries + 1;
  px = number(random(-99, 99)) / random(1, 9);
  py = number(random(-99, 99)) / random(1, 9);
  pz = number(random(-99, 99)) / random(1, 9);
  gx = number(subst(fx, x, px, y, py, z, pz));
  gy = number(subst(fy, x, px, y, py, z, pz));
  gz = number(subst(fz, x, px, y, py, z, pz));
  N[found + 1, 1] = py * gz - pz * gy;
  N[found + 1, 2] = pz * gx - px * gz;
  N[found + 1, 3] = px * gy - py * gx;
  N[found + 1, 4] = gx; N[found + 1, 5] = gy; N[found + 1, 6] = gz;
  if (size(std(module(transpose(N)))) == found + 1) { found = found + 1; }
  else { for (k = 1; k <= 6; k++) { N[found + 1, k] = 0; } }
}
// Step 9: the kernel of the 5x6 system; steps 10-11: it must be a line (a != 0, a.ab = 0).
module K = syz(N);
int line = (found == 5 and size(K) == 1);
poly a1; poly a2; poly a3; poly b1; poly b2; poly b3;
if (line) {
  a1 = K[1][1]; a2 = K[1][2]; a3 = K[1][3]; b1 = K[1][4]; b2 = K[1][5]; b3 = K[1][6];
  line = ((a1 != 0 or a2 != 0 or a3 != 0) and a1 * b1 + a2 * b2 + a3 * b3 == 0);
}
int sor = 0;
if (line) {
  // Steps 13-15: a frame of the axis over QQ: c = (a x ab)/|a|^2 on the axis, u orthogonal to a,
  // w = a x u. With p = c + x a + y u + z w the squared distance from the axis is
  // |u|^2 (y^2 + |a|^2 z^2), so X is a SOR about A iff g = f(p) is a polynomial in x and
  // y^2 + |a|^2 z^2: p(x, y) = g(x, y, 0) is even in y and g = p(x, sqrt(y^2 + |a|^2 z^2)).
  poly n2 = a1^2 + a2^2 + a3^2;
  poly c1 = (a2 * b3 - a3 * b2) / n2; poly c2 = (a3 * b1 - a1 * b3) / n2;
  poly c3 = (a1 * b2 - a2 * b1) / n2;
  poly u1 = -a2; poly u2 = a1; poly u3 = 0;
  if (a1 == 0 and a2 == 0) { u1 = 1; u2 = 0; }
  poly w1 = a2 * u3 - a3 * u2; poly w2 = a3 * u1 - a1 * u3; poly w3 = a1 * u2 - a2 * u1;
  // Translating first and then applying the linear part is 8 times faster at degree 20 than
  // one map p -> c + L p.
  map translate = r, x + c1, y + c2, z + c3;
  map turn = r, x * a1 + y * u1 + z * w1, x * a2 + y * u2 + z * w2, x * a3 + y * u3 + z * w3;
  poly g = translate(f);
  g = turn(g);
  poly p = subst(g, z, 0);
  poly q = y^2 + n2 * z^2;
  poly h = 0; poly t; intvec e;
  sor = 1;
  for (k = 1; k <= size(p); k++) {
    t = p[k]; e = leadexp(t);
    if (e[2] mod 2 != 0) { sor = 0; break; }
    h = h + leadcoef(t) * x^e[1] * q^(e[2] div 2);
  }
  if (sor) { sor = (h == g); }
}
if (sor) { print("SOR yes"); print(K[1]); } else { print("SOR no"); }
quit;
"""


def stages(args: list[str]) -> str:
    """The stage timings that ``analyze --json`` reports inside its process, checked to be a SOR."""
    report = json.loads(subprocess.run([*args, "--json"], capture_output=True, text=True, cwd=ROOT, check=True).stdout)
    assert report["is_sor"], report
    return ", ".join(f"{name} {seconds:.2f}" for name, seconds in report["timings"].items())


def table(repeats: int) -> str:
    """The markdown table of both whole-process times per degree and their ratios."""
    rows = [
        "| degree | terms | sorgui wall (s) | sorgui CPU (s) | Singular Algorithm II wall (s) "
        "| Singular CPU (s) | Singular ÷ sorgui, wall | Singular ÷ sorgui, CPU "
        "| stages inside sorgui (s) |",
        "|---:|---:|" + "---:|" * 6 + "---|",
    ]
    singular = str(find_singular())
    with tempfile.TemporaryDirectory() as folder:
        for degree in DEGREES:
            f = surface(degree)
            equation, script = Path(folder, f"sor{degree}.txt"), Path(folder, f"sor{degree}.sing")
            equation.write_text(poly_str(f) + "\n", encoding="utf-8")
            script.write_text(ALGORITHM_II % {"f": poly_to_singular(f, ["x", "y", "z"])}, encoding="utf-8")
            analyze = [sys.executable, "-m", "sorgui.cli", "analyze", "--recognition-only", "-f", str(equation)]
            ours = process_times(analyze, repeats)
            theirs = process_times([singular, "-q", "-t", "--no-rc", "--random=4711", str(script)], repeats)
            assert "SOR yes" in theirs[2], theirs[2]
            rows.append(
                f"| {degree} | {len(f)} | {ours[0]:.2f} | {ours[1]:.2f} | {theirs[0]:.2f} "
                f"| {theirs[1]:.2f} | {theirs[0] / ours[0]:.2f} | {theirs[1] / ours[1]:.2f} "
                f"| {stages(analyze)} |"
            )
            print(rows[-1], flush=True)
    return "\n".join(rows)


if __name__ == "__main__":
    run("algorithm2-singular", __doc__.splitlines()[0], table)
