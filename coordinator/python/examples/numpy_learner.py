"""A linear SARSA(lambda) learner in numpy, as one agent of an advising team.

Q(s, a) is a sum of weights over a tile coding of the paper's six features
(each in [-1, 1]): per feature, a few tilings of width ``WIDTH`` offset from
one another. It learns where it decides, as HFO's own SARSA agent does
(example/sarsa_offense): from one kick to the next, the frames between
(moving without the ball) folded into the discounted reward of the kick,
an SMDP step. The agent process runs it as its learner (docs/learners.md):

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
#: A sum without ndarray.sum's Python-level wrapper (a learner's calls are small).
add = np.add.reduce


class LinearSarsa(Learner):
    """SARSA(lambda) with replacing traces over a linear tile coding, from
    decision to decision."""

    name = "numpy-linear-sarsa"
    version = "2"

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
        #: A feature x lies in tile (x + 1 + offset) / WIDTH of each tiling.
        self.shift = 1.0 + np.arange(TILINGS) * WIDTH / TILINGS
        #: Where each feature's tilings start in an action's row of
        #: ``weights.ravel()``, a row per action.
        tilings = np.arange(start.features * TILINGS) * TILES
        self.offsets = tilings + (np.arange(self.actions) * self.features)[:, None]
        #: What a step's replacing traces become at its tiles, by action.
        self.replaced = np.eye(self.actions)[:, :, None]
        #: The tiles of the states met lately: a transition's next state is
        #: the next one's state, and values, choose and learn ask in turn.
        self.tiles: dict[State, np.ndarray] = {}
        #: The kick being learned: its state and action, the discounted
        #: reward since, and the discount of what follows.
        self.kick: tuple[State, int] | None = None
        self.reward, self.discount = 0.0, 1.0

    def active(self, state: State) -> np.ndarray:
        """The indices into ``weights.ravel()`` of the tiles `state` lies in,
        one per feature and tiling, a row per action."""
        tiles = self.tiles.get(state)
        if tiles is None:
            x = np.add.outer(state, self.shift)
            x /= WIDTH
            np.clip(x, 0.0, TILES - 1, out=x)
            tiles = x.astype(np.intp).ravel() + self.offsets
            if len(self.tiles) >= 64:
                self.tiles.clear()
            self.tiles[state] = tiles
        return tiles

    def q(self, state: State) -> np.ndarray:
        return add(self.weights.ravel()[self.active(state)], axis=1)

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
        if t.action in KICKS:
            self.kick, self.reward, self.discount = (t.state, t.action), 0.0, 1.0
        if self.kick is None:
            return  # moving before its first kick of the episode
        self.reward += self.discount * t.reward
        self.discount *= self.gamma
        if t.next_state is None:
            self.update(self.reward)
        elif t.next_action in KICKS:
            ahead = add(self.weights.ravel()[self.active(t.next_state)[t.next_action]])
            self.update(self.reward + self.discount * ahead)

    def update(self, target: float) -> None:
        """The SARSA(lambda) step of the kick being learned towards `target`."""
        state, action = self.kick
        weights, traces = self.weights.ravel(), self.traces.ravel()
        tiles = self.active(state)
        error = target - add(weights[tiles[action]])
        traces[tiles] = self.replaced[action]
        weights += (self.alpha * error) * traces
        traces *= self.lam * self.discount  # to the next kick
        self.kick = None

    def end_episode(self) -> None:
        self.traces[:] = 0.0
        self.kick = None

    def save(self) -> bytes:
        """The weights, as numpy's .npy bytes (snapshots: --save-agents,
        load, a restart after a crash)."""
        out = io.BytesIO()
        np.save(out, self.weights, allow_pickle=False)
        return out.getvalue()

    def restore(self, state: bytes) -> None:
        # Contiguous, so that learn's ravel() is a view of it.
        weights = np.ascontiguousarray(np.load(io.BytesIO(state), allow_pickle=False))
        if weights.shape != self.weights.shape:
            expected = self.weights.shape
            raise ValueError(f"saved weights of shape {weights.shape}, expected {expected}")
        self.weights = weights
        self.traces = np.zeros_like(weights)

    def replay(self, episode: Sequence[Transition]) -> None:
        own = self.traces.copy(), self.kick, self.reward, self.discount
        self.end_episode()
        super().replay(episode)
        self.traces, self.kick, self.reward, self.discount = own


if __name__ == "__main__":
    raise SystemExit(serve(LinearSarsa))
