"""Exact algebra over ``K = QQ`` or ``QQ(√…)``, the ground every other part of the engine stands on.

Modules: ``polys`` (the polynomial facade over sympy's rings and python-flint), ``rationals``
(``QQ`` on flint alone, for the analyses that load no sympy), ``numberfields`` (``QQ(√d₁, …)``
in a radical basis: norms, factorization, square roots), ``radicals`` (rational functions in
square roots), ``fractions`` (rational functions over ``QQ`` as reduced flint fractions),
``linalg`` (vectors and null spaces over ``K``), ``realroots`` (counting real roots exactly),
``legendre`` (rational points of conics: Legendre's equation).
Import the module you need: nothing here is loaded until asked for.
"""
