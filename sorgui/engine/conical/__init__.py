"""Cones and cylinders over any curve (docs/math.md §10): the apex or the direction
(:mod:`.detect`), and the base curve with its genus and the verified rational
parameterizations (:mod:`.base_curve`)."""
