"""The suite's crash reports: after a test that started gmsh, a segmentation fault still prints
every thread's Python stack (``gmsh.initialize()`` resets SIGSEGV; ``tests/conftest.py`` arms
:mod:`faulthandler` again)."""

from __future__ import annotations

import ctypes
import ctypes.util
import faulthandler
import signal
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads sigaction(2) on Linux")


class _SigAction(ctypes.Structure):
    _fields_ = [
        ("handler", ctypes.c_void_p),
        ("mask", ctypes.c_ulong * 16),
        ("flags", ctypes.c_int),
        ("restorer", ctypes.c_void_p),
    ]


def _segv_handler() -> int:
    """The address of the process's SIGSEGV handler (0: the default action)."""
    libc = ctypes.CDLL(ctypes.util.find_library("c"))
    action = _SigAction()
    libc.sigaction(signal.SIGSEGV, None, ctypes.byref(action))
    return action.handler or 0


def test_gmsh_resets_the_segmentation_fault_handler() -> None:
    """The cause, in a new process: its first ``gmsh.initialize()`` (a later one in the same
    process leaves the handler alone, so the suite's own process cannot show it)."""
    pytest.importorskip("gmsh")
    script = (
        "import faulthandler, gmsh, sys; sys.path.insert(0, sys.argv[1]); "
        "from test_faulthandler_armed import _segv_handler as h; faulthandler.enable(); "
        "armed = h(); gmsh.initialize(interruptible=False); gmsh.finalize(); print(armed, h())"
    )
    out = subprocess.run(
        [sys.executable, "-c", script, str(Path(__file__).parent)], capture_output=True, text=True, check=True
    )
    armed, after = map(int, out.stdout.split())
    assert armed != 0 and after == 0


def test_a_test_that_starts_gmsh() -> None:
    gmsh = pytest.importorskip("gmsh")
    gmsh.initialize(interruptible=False)
    gmsh.finalize()


def test_the_next_test_has_it_armed_again() -> None:
    if not faulthandler.is_enabled():
        pytest.skip("pytest runs without its faulthandler plugin")
    assert _segv_handler() != 0
