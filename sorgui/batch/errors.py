"""The one error of a batch that cannot run as asked."""

from __future__ import annotations


class BatchError(Exception):
    """The batch cannot be run as asked (a results file that would be overwritten or does not
    match the input, a Dask scheduler out of reach); the message is one line, ``status`` the
    exit status (2: the command line or its files, 1: the machinery)."""

    def __init__(self, message: str, status: int = 2) -> None:
        super().__init__(message)
        self.status = status
