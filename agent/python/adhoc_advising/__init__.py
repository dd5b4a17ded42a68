"""Ad hoc advising among simultaneously learning agents (da Silva, Glatt &
Costa, AAMAS 2017), from Python.

- :class:`GreedyAgent`: a learner of ours frozen from its snapshot file
  (``coordinator run --save-agents``), playing its greedy action.
- :data:`PAPER_ACTIONS`: the paper's actions by the index ``GreedyAgent.act``
  returns.
- :mod:`adhoc_advising.learner`: a learner written in Python as one agent of
  an advising team, run by the Rust agent process (docs/learners.md).

The simulator is the separate package ``halffield``.
"""

from __future__ import annotations

from adhoc_advising._adhoc_advising import PAPER_ACTIONS, GreedyAgent

__all__ = ["PAPER_ACTIONS", "GreedyAgent"]
