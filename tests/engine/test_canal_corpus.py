"""The canal answers agree with the surface-of-revolution answers on the whole public corpus
(tests/data/cases.json): a surface of revolution is canal with its spine on a line, and a canal
surface whose spine is a line is a surface of revolution. The canal analysis is run without the
symmetry algebra's answer, so the two are independent."""

from __future__ import annotations

import pytest

from sorgui.engine.canal import analyze_canal
from sorgui.engine.parsing import parse_polynomial

from ..conftest import corpus_cases

CASES = [c for c in corpus_cases() if "is_sor" in c["expect"]]


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_canal_agrees_with_the_symmetry_algebra(case: dict) -> None:
    f = parse_polynomial(case["input"]).polynomial
    canal = analyze_canal(f, full=False)
    if case["expect"]["is_sor"]:
        assert canal.is_canal is True, canal.status
        assert "revolution" in canal.kinds
    else:
        assert canal.is_canal is not None
        assert "revolution" not in canal.kinds
