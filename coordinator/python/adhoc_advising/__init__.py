"""Ad hoc advising among simultaneously learning agents (da Silva, Glatt &
Costa, AAMAS 2017), from Python.

- :class:`GreedyAgent`: a learner of ours frozen from its snapshot file
  (``coordinator run --save-agents``), playing its greedy action.
- :data:`PAPER_ACTIONS`: the paper's actions by the index ``GreedyAgent.act``
  returns.
- :mod:`adhoc_advising.learner`: a learner written in Python as one agent of
  an advising team, run by the Rust agent process (docs/learners.md).
- :func:`run` and :func:`study` (:mod:`adhoc_advising.experiments`):
  experiments and studies in this process, as `coordinator run` and
  `coordinator study`, with Python learners as objects (docs/python.md);
  :func:`replay`: one evaluation episode of a team of snapshots, animated.
- :func:`load` (:mod:`adhoc_advising.results`): what `run`/`study` and the
  command line wrote, as pandas DataFrames.
- :mod:`adhoc_advising.strategy`: an advising strategy written in Python:
  one agent's decisions of when to ask, whom, when to give and what to
  follow (docs/strategies.md).

The simulator is the separate package ``halffield``.
"""

from __future__ import annotations

from adhoc_advising._adhoc_advising import PAPER_ACTIONS, GreedyAgent
from adhoc_advising.experiments import replay, run, study
from adhoc_advising.results import load

__all__ = ["PAPER_ACTIONS", "GreedyAgent", "load", "replay", "run", "study"]
