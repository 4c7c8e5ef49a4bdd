"""Rounded (decimal) input: the surface a CAD system meant to print (docs/math.md §8).

Modules: ``precision`` (the rounding read off the digits), ``approximate`` (the approximate
symmetry and its verdict), ``near_symmetry`` (the floating-point symmetry algebra and the axis
refinement), ``snapping`` (the nearest exact surface), ``directions`` (the exact directions
an axis is snapped to), ``deviation`` (how far the zero sets are apart), ``dense`` (dense
floating-point polynomial arrays). Import the module you need.
"""
