"""The suite's crash reports: after a test that started gmsh, a segmentation fault still prints
every thread's Python stack (``gmsh.initialize()`` resets SIGSEGV; ``tests/conftest.py`` arms
:mod:`faulthandler` again)."""

from __future__ import annotations

import ctypes
import ctypes.util
import faulthandler
import signal
import sys

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
    gmsh = pytest.importorskip("gmsh")
    gmsh.initialize(interruptible=False)
    gmsh.finalize()
    assert _segv_handler() == 0


def test_the_next_test_has_it_armed_again() -> None:
    if not faulthandler.is_enabled():
        pytest.skip("pytest runs without its faulthandler plugin")
    assert _segv_handler() != 0
