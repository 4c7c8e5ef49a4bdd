"""Open CASCADE's exceptions as Python sees them.

OCP raises each exception class of Open CASCADE (``Standard_Failure``, ``Geom_UndefinedValue``,
``Geom_UndefinedDerivative``, ``StdFail_NotDone``, ``Standard_ConstructionError``, ...) as a
plain ``Exception`` subclass of its own module, not as a subclass of ``Standard_Failure`` as in
C++: ``except Standard_Failure`` misses a face whose evaluation fails with
``Geom_UndefinedDerivative``. :data:`OCCT_ERRORS` holds them all, for ``except`` clauses.
"""

from __future__ import annotations

from types import ModuleType

import OCP.OCP
from OCP.Standard import Standard_Failure


def _exception_classes() -> tuple[type[Exception], ...]:
    """Every exception class of OCP's modules (about a hundred; read in a few milliseconds)."""
    found: set[type[Exception]] = {Standard_Failure}
    for module in vars(OCP.OCP).values():
        if isinstance(module, ModuleType):
            found.update(c for c in vars(module).values() if isinstance(c, type) and issubclass(c, Exception))
    return tuple(sorted(found, key=lambda c: c.__name__))


OCCT_ERRORS = _exception_classes()
"""The exceptions Open CASCADE raises through OCP."""


def from_occt(exc: BaseException) -> bool:
    """Whether ``exc`` is an Open CASCADE exception (``Standard_Failure`` and its kin, which OCP
    raises as plain ``Exception`` subclasses of its own modules)."""
    return type(exc).__module__.startswith("OCP")
