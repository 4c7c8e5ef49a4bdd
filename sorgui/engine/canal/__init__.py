"""Canal surfaces: envelopes of one-parameter families of spheres (docs/math.md §9).

Modules: ``verdict`` (the exact verdict with its certificate or witness, the kinds, the
families), ``focal`` (the focal-sheet condition), ``lines`` (the condition tested on lines, the
witness), ``spine`` (the SMAT curves, with Singular), ``parametrization`` (rational families,
characteristic circles, parameterizations), ``radical`` (families in square roots), ``torus``
(the torus read off its profile, §9.1). Import the module you need.
"""
