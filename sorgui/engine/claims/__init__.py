"""A saved report's claims checked against its own polynomial (docs/math.md §14).

A report is a file from elsewhere: before anything shows or exports it, every claim it makes
about ``f`` — the symmetry, the axis, the profile, a sphere's centre and radius, a plane, the
parameterizations, the tubular surface, the canal families, a cone's apex — is checked against
``f`` itself, with the symmetry algebra and exact substitutions, in milliseconds; the first claim
that fails raises :class:`~sorgui.engine.errors.ClaimError` naming its field.

Modules: ``formulas`` (the report's strings read, numbers of ``K``, polynomials evaluated
modulo a prime), ``identities`` (identities tested at random points, :mod:`..algebra.modular`),
``recognition`` (symmetry, axis, centre, normal, direction, radius, profile), ``maps``
(rationality, parameterizations, cones and cylinders), ``canal`` (sphere families),
``parametric`` (a parametrization's report against its map, docs/math.md §13) and ``report``
(the whole report: :func:`.report.check_report`).
"""
