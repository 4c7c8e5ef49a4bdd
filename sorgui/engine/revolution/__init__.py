"""A surface of revolution once recognised: its real points, Table 1 and its parameterizations
(docs/math.md §3–§6).

Modules: ``real_locus`` (whether the surface has real points, and of what kind),
``rationality`` (the genera of ``P`` and ``P²``, the row of Table 1, the tubular surface),
``parametrization`` (rational parameterizations of ``X``, verified). Import the module you need.
"""
