"""Shared fixtures: the public corpus and the paper's examples."""

from __future__ import annotations

import faulthandler
import json
import os
import sys
from pathlib import Path

import pytest
from hypothesis import settings

import sorgui  # noqa: F401 - first, so that numpy's BLAS starts with the thread count sorgui sets

settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
if os.environ.get("CI"):
    # CI tries the same generated cases on every run (a case found once is added as an
    # @example); random exploration is for runs on a developer's machine.
    settings.load_profile("ci")

CORPUS = Path(__file__).resolve().parent / "data" / "cases.json"


@pytest.hookimpl(trylast=True)
def pytest_runtest_teardown(item: pytest.Item) -> None:
    """Arm :mod:`faulthandler` again after a test that started gmsh: ``gmsh.initialize()``
    puts SIGSEGV back to the default action, so that a later crash in Qt or VTK printed no
    traceback at all (the suite ended in a bare "Segmentation fault")."""
    if "gmsh" not in sys.modules or not faulthandler.is_enabled():
        return
    from _pytest.faulthandler import fault_handler_stderr_fd_key

    fd = item.config.stash.get(fault_handler_stderr_fd_key, None)
    if fd is not None:
        faulthandler.disable()  # enable() alone does nothing while Python thinks it is on
        faulthandler.enable(file=fd)


def corpus_cases() -> list[dict]:
    """The public corpus of cases with known answers (``tests/data/cases.json``, see its README)."""
    return json.loads(CORPUS.read_text(encoding="utf-8"))


@pytest.fixture(scope="session")
def paper_example_1():
    """The paper's Example 1 as a polynomial over QQ, built without the parser."""
    from sympy import QQ

    from sorgui.engine.algebra.polys import XYZ, poly_ring

    text = next(c["input"] for c in corpus_cases() if c["name"] == "paper-example-1")
    R = poly_ring(XYZ, QQ)
    terms = {}
    for term in text.replace("-", "+-").split("+"):
        if not term:
            continue
        factors = term.split("*")
        coeff = int(factors[0])
        exps = [0, 0, 0]
        for factor in factors[1:]:
            name, _, power = factor.partition("^")
            exps["xyz".index(name)] += int(power or 1)
        terms[tuple(exps)] = terms.get(tuple(exps), 0) + coeff
    return R.from_dict({m: QQ(c) for m, c in terms.items()})
