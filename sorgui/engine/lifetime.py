"""Processes that never outlive the one that started them (Linux ``PR_SET_PDEATHSIG``).

Singular (:mod:`.singular.process`) and the analysis processes of the command line and the window
(:mod:`sorgui.session.child`) ask the kernel to end them when their parent dies, even by
``kill -9``. Light to import: ``ctypes`` only.
"""

from __future__ import annotations

import ctypes
import sys
from collections.abc import Callable

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def die_with_parent(signum: int) -> bool:
    """Ask the kernel to send ``signum`` to this process when the thread that started it dies
    (Linux ``PR_SET_PDEATHSIG``, also after ``kill -9``); ``False`` where that is not possible."""
    return _prctl is not None and _prctl(_PR_SET_PDEATHSIG, int(signum), 0, 0, 0) == 0


def _load_prctl() -> Callable[..., int] | None:
    """Linux's ``prctl`` from the C library, or ``None`` on other systems."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        return ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None


_prctl = _load_prctl()
