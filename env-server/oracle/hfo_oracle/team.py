"""A learned agent of ours, frozen from its snapshot file (``coordinator run
--save-agents``), played greedily in the paper's 6-feature state as our
evaluations play it: the one loader that ``hfo_oracle.py --team`` (on the
real HFO) and ``team_ours.py`` (on our simulator) share."""

from __future__ import annotations

from typing import Any


def greedy_agent(snapshot: str) -> Any:
    """The frozen agent of ``snapshot``: ``act(state, can_kick)`` returns the
    index of its greedy action (:data:`hfo_oracle.schema.ACTIONS`).

    The class is ``GreedyAgent`` of ``adhoc_advising``, the Python package
    that binds our agents (``pip install ./coordinator/python``).
    """
    try:
        from adhoc_advising import GreedyAgent
    except ImportError as e:
        raise ImportError(
            "a learned team needs the adhoc_advising package (pip install ./coordinator/python) "
            "in this interpreter"
        ) from e
    return GreedyAgent(snapshot)
