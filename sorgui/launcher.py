"""The console scripts' entry point: :func:`sorgui.cli.main`, with Ctrl+C during its import
answered as during its run.

Importing the command line takes about 40 ms before :func:`sorgui.cli.main` takes over the
signals; a Ctrl+C in that time printed a ``KeyboardInterrupt`` traceback and the process died
by the signal, where the README promises ``sorgui: interrupted`` and exit status 130. This
module imports nothing else, so that window is Python's own start.
"""

from __future__ import annotations

import sys

INTERRUPTED = 130
"""The exit status of a command ended by Ctrl+C (128 + SIGINT), as :func:`sorgui.cli.main` gives."""


def main() -> int:
    """Run the command line; ``sorgui: interrupted`` and :data:`INTERRUPTED` for a Ctrl+C that
    comes before it has taken over the signals."""
    try:
        from sorgui.cli import main as run

        return run()
    except KeyboardInterrupt:
        return interrupted()


def interrupted() -> int:
    """Say that Ctrl+C ended the command, and its exit status (:data:`INTERRUPTED`): here, and in
    :func:`sorgui.cli.main` once it has taken over the signals."""
    print("sorgui: interrupted", file=sys.stderr)
    return INTERRUPTED
