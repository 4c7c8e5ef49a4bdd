"""sorgui: exact recognition of surfaces of revolution from their implicit equations."""

import os

# The least-squares problems of the engine and the meshes of the render layer are small; with
# more than one OpenBLAS thread on a busy machine the threads spin against each other, the
# window and the worker processes (a 1771 × 121 least-squares problem took 1.2 s with two
# threads and 0.02 s with one). Set before numpy loads OpenBLAS; a user's setting wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.1.0"
