import os
from collections.abc import Callable, Sequence

PAPER_ACTIONS: list[str]

class GreedyAgent:
    def __init__(self, path: str | os.PathLike[str]) -> None: ...
    def act(self, state: Sequence[float], can_kick: bool) -> int: ...
    @property
    def digest(self) -> int: ...

STATE_FEATURES: int

def run(
    *,
    out: str,
    objects: list[
        tuple[
            tuple[Callable[[int, int, int, int], object], str] | None,
            tuple[Callable[[int, int, int, int], object], str] | None,
        ]
    ],
    algorithm: str | None = None,
    team_file: str | None = None,
    team_tables: str | None = None,
    mistake_correcting: bool = False,
    learner: str | None = None,
    runs: int = 50,
    episodes: int = 5000,
    eval_every: int = 20,
    eval_episodes: int = 100,
    seed: int = 1,
    profile: str = "paper",
    ci_level: float | None = None,
    offense: int | None = None,
    evaluation_memory: str = "carried",
    advice_latency: str | None = None,
    advice_loss: float | None = None,
    advice_timeout_ms: int | None = None,
    threads: int | None = None,
    save_agents: str | None = None,
    progress: bool = False,
) -> str: ...
def study(
    *,
    out: str,
    preset: str | None = None,
    config: str | None = None,
    runs: int | None = None,
    episodes: int | None = None,
    threads: int | None = None,
    progress: bool = False,
) -> str | None: ...
def replay(
    *,
    objects: list[
        tuple[
            tuple[Callable[[int, int, int, int], object], str] | None,
            tuple[Callable[[int, int, int, int], object], str] | None,
        ]
    ],
    algorithm: str | None = None,
    team_file: str | None = None,
    team_tables: str | None = None,
    seed: int = 1,
    episode: int = 1,
    profile: str = "paper",
) -> tuple[str, str, str, str]: ...
