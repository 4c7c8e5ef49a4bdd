"""The canal answers agree with the surface-of-revolution answers on the whole public corpus
(tests/data/cases.json) and on the canal examples (tests/data/canal-examples.txt): a surface of
revolution is canal with its spine on a line, and a canal
surface whose spine is a line is a surface of revolution. The canal analysis is run without the
symmetry algebra's answer, so the two are independent."""

from __future__ import annotations

from pathlib import Path

import pytest

from sorgui.engine.canal.verdict import analyze_canal
from sorgui.engine.parsing import parse_polynomial
from sorgui.engine.recognition.recognize import recognize

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


CANAL_EXAMPLES = Path(__file__).resolve().parents[1] / "data" / "canal-examples.txt"


def canal_examples() -> list[tuple[str, str]]:
    lines = CANAL_EXAMPLES.read_text(encoding="utf-8").splitlines()
    return [
        (line[3:].split(" |")[0], lines[i + 1])
        for i, line in enumerate(lines)
        if line.startswith("## ") and "degree 24" not in line
    ]


@pytest.mark.parametrize("name,text", canal_examples(), ids=[n for n, _ in canal_examples()])
def test_canal_examples_agree_with_the_symmetry_algebra(name: str, text: str) -> None:
    f = parse_polynomial(text).polynomial
    recognition, _, _ = recognize(f)
    canal = analyze_canal(f, full=False)
    assert canal.is_canal is not None
    assert ("revolution" in canal.kinds) == recognition.is_sor, name
