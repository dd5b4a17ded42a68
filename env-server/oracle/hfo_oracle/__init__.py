"""The real-HFO oracle: plays fixed high-level policies, or a learned team,
on the real RoboCup Half Field Offense and writes the per-decision
statistics that ``env-server rollout --json`` writes for our simulator.

One module per job:

- :mod:`hfo_oracle.schema`: the statistics file's vocabulary (outcomes,
  actions, shot distance bins) and its atomic write;
- :mod:`hfo_oracle.stats`: means, standard deviations, Wilson intervals and
  z statistics (also used by ``compare.py`` and ``learned.py``);
- :mod:`hfo_oracle.agent`: the HFO agent process (needs HFO's ``hfo``),
  playing a policy or a learned agent made by the factory ``--team-factory``
  names;
- :mod:`hfo_oracle.launch`: starting and stopping HFO, rcssserver and the
  agents, one batch of episodes at a time;
- :mod:`hfo_oracle.logs`: the parsers of rcssserver's logs and of the
  agents' choice files;
- :mod:`hfo_oracle.tally`: the join of those logs into the statistics;
- :mod:`hfo_oracle.cli`: the command line (``hfo_oracle.py`` beside this
  package, or ``python3 -m hfo_oracle``).

Standard library only; nothing is imported here, so that the agent
process, which runs under HFO's interpreter, loads only what it uses.
"""
