"""``sorgui analyze --each-line``: one equation per line, one JSON object per line (JSON Lines).

Every line that holds an equation (``#`` starts a comment: no equation contains it) gives
exactly one output object, in input order: the analysis JSON of ``sorgui analyze --json`` with
``"line"`` (1-based) and ``"line_hash"`` added, or an error object; a bad line never stops the
others (:mod:`.answers`). The input is read as it is analysed, a line at a time, in bounded
memory: the length limit of one equation applies to each line, and a longer line is refused
whole (:mod:`.lines`). The lines are analysed by this machine's worker processes
(:mod:`.pool`, ``--jobs``) or on a Dask cluster (:mod:`.cluster`, ``--scheduler``), the same
way, under the time limit of one analysis each (:mod:`.run`). ``-o RESULTS.jsonl`` writes them
to a file that ``--resume`` continues after a crash (:mod:`.results_file`). Standard error gets
the progress and one summary line at the end when it is a terminal, the summary also with
``-o`` (:mod:`.progress`).

Exit status: 0 when every line was analysed, 1 when an analysis failed, else 2 when a line was
not a polynomial.
"""

from .errors import BatchError
from .lines import Line, LineReader, equations, line_hash
from .pool import WARM_UP, warm_up
from .run import run_each_line

__all__ = ["WARM_UP", "BatchError", "Line", "LineReader", "equations", "line_hash", "run_each_line", "warm_up"]
