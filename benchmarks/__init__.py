"""Benchmarks of sorgui, run from the repository root as ``python -m benchmarks.NAME``.

They import ``sorgui``, ``tests`` (the surface builders) and each other as packages; the
figures and the exact commands are in ``docs/benchmarks.md``.
"""

import sorgui  # noqa: F401,E402 - first, so that numpy's BLAS starts with the thread count sorgui sets
