"""The line channel a child process of the agent answers over: one JSON
object per line on standard input, one answer per query on standard output."""

from __future__ import annotations

import contextlib
import json
import sys
from typing import IO, Callable


def serve_lines(answer: Callable[[dict], dict | None], requests: IO[str], answers: IO[str]) -> int:
    """Answers each request line with ``answer`` until ``requests`` closes;
    returns the exit status. An exception is reported to the agent (which
    ends with a line naming it) and ends the loop with 1. Meanwhile
    ``print()`` goes to standard error, the agent's log: the channel's
    standard output carries answers only."""
    with contextlib.redirect_stdout(sys.stderr):
        return _serve(answer, requests, answers)


def _serve(answer: Callable[[dict], dict | None], requests: IO[str], answers: IO[str]) -> int:
    for line in requests:
        try:
            reply = answer(json.loads(line))
        except Exception as error:  # noqa: BLE001 - reported to the agent, then fatal
            answers.write(json.dumps({"error": f"{type(error).__name__}: {error}"}) + "\n")
            answers.flush()
            return 1
        if reply is not None:
            answers.write(json.dumps(reply) + "\n")
            answers.flush()
    return 0
