#!/usr/bin/env python3
"""Real-HFO oracle: plays N episodes of a fixed high-level policy, or of a
learned team, on the real RoboCup Half Field Offense (3 offense agents vs
agent2d's goalkeeper) and writes one JSON object in the per-decision
statistics schema shared with `env-server rollout --json` (README.md in
this directory).

The code is the package `hfo_oracle/` beside this script (one module per
job); this script only runs its command line, as `python3 -m hfo_oracle`
does from this directory. Standard library only.
"""

import os
import sys

if __name__ == "__main__":
    # Python puts this script's directory first on sys.path; the package
    # `hfo_oracle/` there is found before this file of the same name.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from hfo_oracle.cli import entry

    entry()
