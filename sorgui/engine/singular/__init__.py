"""Singular, the computer algebra system that sorgui runs for plane curves (docs/math.md §5).

Modules: ``process`` (finding the ``Singular`` executable, running one script in a process that
a time limit or a cancel kills, reading its output), ``curves`` (absolute factorization, genus
and rational parameterization of plane curves, with the routes that need no Singular), and
``sorgui.lib``, sorgui's own Singular procedures. Import the module you need.
"""
