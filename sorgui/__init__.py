"""sorgui: exact recognition of surfaces of revolution from their implicit equations."""

import os
import sys

# The least-squares problems of the engine and the meshes of the render layer are small; with
# more than one OpenBLAS thread on a busy machine the threads spin against each other, the
# window and the worker processes (a 1771 × 121 least-squares problem took 1.2 s with two
# threads and 0.02 s with one). Set before numpy loads OpenBLAS; a user's setting wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# The engine passes python-flint's numbers between sympy's domains and flint's polynomials, which
# needs sympy's rationals to be flint's. sympy reads this when it is first imported.
os.environ["SYMPY_GROUND_TYPES"] = "flint"

MAX_PRINTED_DIGITS = 200_000
"""Python refuses to convert integers of more than 4,300 digits to and from text by default.
Every process of sorgui reads or prints the numbers that accepted input leads to (the engine's
analysis, an export decoding its JSON, the window), so the limit is raised to this bound here,
before any of them runs; the engine's limits on input keep its numbers below it
(:mod:`sorgui.engine.limits`)."""
if 0 < sys.get_int_max_str_digits() < MAX_PRINTED_DIGITS:
    sys.set_int_max_str_digits(MAX_PRINTED_DIGITS)

__version__ = "0.1.0"
