"""Rational parametrizations ``(s, t) ↦ P(s, t)`` as input (docs/math.md §13).

``maps`` (the map ``P = X/W`` over ``K``, its derivatives and its normal), ``detect`` (the exact
decision: the symmetry algebra from the normal lines, the apex of a cone, the direction of a
cylinder, the cross-check of the profile), ``implicit`` (the implicit equation: the profile
curve ``(h, ρ)`` or a base curve implicitized by a resultant, else Singular's elimination),
``nearly`` (rounded coefficients: the same system by least squares) and ``pipeline`` (the
analysis of a parametrization, which ends in the analysis of its implicit equation). The text is
read by :mod:`sorgui.engine.parametric_parsing`.
"""
