"""The package under test, `hfo_oracle`, is the directory above this one."""

import os
import sys

ORACLE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ORACLE_DIR not in sys.path:
    sys.path.insert(0, ORACLE_DIR)
