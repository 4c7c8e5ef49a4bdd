"""Recognizing a surface of revolution exactly (docs/math.md §2–§3).

Modules: ``symmetry`` (the symmetry algebra ``L`` of (★): its dimension, the axis, the other
symmetries), ``paper_method`` (the paper's Algorithm II), ``profile`` (the profile curve and its
axis frames over ``K``), ``recognize`` (axis, profile and factors of one equation). Import the
module you need.
"""
