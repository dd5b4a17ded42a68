import os
from collections.abc import Sequence

PAPER_ACTIONS: list[str]

class GreedyAgent:
    def __init__(self, path: str | os.PathLike[str]) -> None: ...
    def act(self, state: Sequence[float], can_kick: bool) -> int: ...
    @property
    def digest(self) -> int: ...
