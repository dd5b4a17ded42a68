"""``python3 -m hfo_oracle``: the same as ``hfo_oracle.py`` beside this
package."""

from hfo_oracle.cli import entry

entry()
