"""VTK's bridge between ``numpy`` arrays and VTK data arrays, with static types.

``vtkmodules.util.numpy_support`` has no annotations; :data:`numpy_to_vtk` and
:data:`vtk_to_numpy` are its two functions themselves (no wrapper), declared with the
signatures VTK documents so that typed code can call them.
"""

from __future__ import annotations

from typing import Protocol, cast

import numpy as np
from numpy.typing import ArrayLike
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkDataArray


class _NumpyToVtk(Protocol):
    def __call__(self, num_array: ArrayLike, deep: bool = False, array_type: int | None = None) -> vtkDataArray: ...


class _VtkToNumpy(Protocol):
    def __call__(self, vtk_array: vtkDataArray) -> np.ndarray: ...


numpy_to_vtk = cast(_NumpyToVtk, numpy_support.numpy_to_vtk)
"""A VTK data array of a contiguous ``numpy`` array: a view of it, or a copy with ``deep=True``."""

vtk_to_numpy = cast(_VtkToNumpy, numpy_support.vtk_to_numpy)
"""A ``numpy`` view of a VTK data array."""
