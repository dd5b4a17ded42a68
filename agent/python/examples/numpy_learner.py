"""A linear SARSA(lambda) learner in numpy, as one agent of an advising team.

Q(s, a) is a sum of weights over a tile coding of the paper's six features
(each in [-1, 1]): per feature, a few tilings of width ``WIDTH`` offset from
one another. The agent process runs it as its learner (docs/learners.md):

    agent --id 2 --team-size 3 ... -- python3 examples/numpy_learner.py

or, in a team file,
``learner = { command = ["python3", "examples/numpy_learner.py"] }``.
The advising framework around it (budgets, n(s), the ask and give
probabilities) is the Rust agent's; this file only acts and learns.
"""

from __future__ import annotations

import io
from collections.abc import Sequence

import numpy as np

from adhoc_advising.learner import Learner, Start, State, Transition, serve

#: Tiles per feature and tiling, their width, and the tilings per feature.
TILES, WIDTH, TILINGS = 11, 0.2, 4
KICKS = (1, 2, 3, 4)  # SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR


class LinearSarsa(Learner):
    """SARSA(lambda) with replacing traces over a linear tile coding."""

    name = "numpy-linear-sarsa"
    version = "1"

    def __init__(
        self,
        start: Start,
        alpha: float = 0.1,
        gamma: float = 0.9,
        lam: float = 0.9,
        epsilon: float = 0.1,
    ) -> None:
        self.rng = np.random.default_rng(start.seed)
        self.actions = len(start.actions)
        self.features = start.features * TILINGS * TILES
        self.weights = np.zeros((self.actions, self.features))
        self.traces = np.zeros_like(self.weights)
        self.alpha = alpha / (start.features * TILINGS)
        self.gamma, self.lam, self.epsilon = gamma, lam, epsilon
        self.decay = gamma * lam
        #: A feature x lies in tile (x + 1 + offset) / WIDTH of each tiling.
        self.shift = 1.0 + (np.arange(TILINGS) * WIDTH / TILINGS)[None, :]
        self.base = (np.arange(start.features)[:, None] * TILINGS + np.arange(TILINGS)) * TILES
        #: The tiles of the states met lately: a transition's next state is
        #: the next one's state, and values, choose and learn ask in turn.
        self.tiles: dict[State, np.ndarray] = {}

    def active(self, state: State) -> np.ndarray:
        """The indices of the tiles `state` lies in, one per feature and tiling."""
        tiles = self.tiles.get(state)
        if tiles is None:
            x = np.asarray(state)[:, None] + self.shift
            x /= WIDTH
            np.maximum(x, 0.0, out=x)
            np.minimum(x, TILES - 1, out=x)
            tiles = (x.astype(np.intp) + self.base).ravel()
            if len(self.tiles) >= 64:
                self.tiles.clear()
            self.tiles[state] = tiles
        return tiles

    def q(self, state: State) -> np.ndarray:
        return self.weights[:, self.active(state)].sum(axis=1)

    def values(self, state: State, index: int | None) -> list[float | None]:
        q = self.q(state)
        return [None if a not in KICKS else float(q[a]) for a in range(self.actions)]

    def choose(self, state: State, index: int | None) -> int:
        if self.rng.random() < self.epsilon:
            return KICKS[self.rng.integers(len(KICKS))]
        q = self.q(state).tolist()
        best = max(q[a] for a in KICKS)
        ties = [a for a in KICKS if q[a] == best]
        return ties[0] if len(ties) == 1 else ties[self.rng.integers(len(ties))]

    def learn(self, t: Transition) -> None:
        tiles = self.active(t.state)
        target = t.reward
        if t.next_state is not None and t.next_action is not None:
            target += self.gamma * self.weights[t.next_action][self.active(t.next_state)].sum()
        error = target - self.weights[t.action][tiles].sum()
        self.traces *= self.decay
        self.traces[:, tiles] = 0.0
        self.traces[t.action][tiles] = 1.0
        self.weights += (self.alpha * error) * self.traces

    def end_episode(self) -> None:
        self.traces[:] = 0.0

    def save(self) -> bytes:
        """The weights, as numpy's .npy bytes (snapshots: --save-agents,
        load, a restart after a crash)."""
        out = io.BytesIO()
        np.save(out, self.weights, allow_pickle=False)
        return out.getvalue()

    def restore(self, state: bytes) -> None:
        weights = np.load(io.BytesIO(state), allow_pickle=False)
        if weights.shape != self.weights.shape:
            expected = self.weights.shape
            raise ValueError(f"saved weights of shape {weights.shape}, expected {expected}")
        self.weights = weights
        self.traces = np.zeros_like(weights)

    def replay(self, episode: Sequence[Transition]) -> None:
        own = self.traces.copy()
        self.traces[:] = 0.0
        super().replay(episode)
        self.traces = own


if __name__ == "__main__":
    raise SystemExit(serve(LinearSarsa))
