"""The script under test, `team_ours.py`, is in the directory above this
one; the harness's package `hfo_oracle` it uses in env-server/oracle."""

import os
import sys

ORACLE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HARNESS_DIR = os.path.join(os.path.dirname(os.path.dirname(ORACLE_DIR)), "env-server", "oracle")
for path in (HARNESS_DIR, ORACLE_DIR):
    if path not in sys.path:
        sys.path.insert(0, path)
