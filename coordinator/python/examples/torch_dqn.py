"""A Double DQN in PyTorch, as one agent of an advising team.

A small MLP maps the paper's six features to the values of the four kick
actions (SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR). It learns where it decides,
as the numpy example (numpy_learner.py) and HFO's own SARSA agent do: from
one kick to the next, the frames between (moving without the ball) folded
into the discounted reward of the kick, an SMDP step. Each kick it ends
goes into a replay buffer, and each one (``train_every``) is followed by a
gradient step of Double DQN (van Hasselt et al., 2016) on a minibatch from
it: the online network chooses the next kick, a target network, copied
from it every ``target_every`` steps, values it; Huber loss, Adam.
Exploration is epsilon-greedy, epsilon falling linearly over the first
decisions. CPU only, one thread: its networks are small and its batches
one a kick.

Seeded from the framework's seed (``Start.seed``), on one thread and with
PyTorch's deterministic algorithms, a run is reproducible: the same seed
gives the same run files in process. Its own ``torch.Generator`` and
``random.Random`` are seeded, not PyTorch's global generator, so that two
runs playing at once in one process (``run(..., threads=2)``) do not draw
from one generator in an order that depends on the threads. ``save`` and
``restore`` keep the networks, the optimiser and the counters (not the
replay buffer) in snapshots.

In process, ``adhoc_advising.run(team=[..., {"algorithm": "adhoc-td",
"learner": DoubleDqn}])``; as a learner process over zenoh, in a team file,
``learner = { command = ["python3", "examples/torch_dqn.py"] }``
(docs/learners.md); there ``import torch`` must finish within the 8 s a
learner has to answer ``start``. The advising framework around it (budgets, n(s), the
ask and give probabilities) is the Rust agent's; this file only acts and
learns.
"""

from __future__ import annotations

import io
import random
from collections.abc import Sequence

import torch
from torch import nn
from torch.nn import functional

from adhoc_advising.learner import Learner, Start, State, Transition, serve

KICKS = (1, 2, 3, 4)  # SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR; output k - 1 of the network


def network(features: int, hidden: int, generator: torch.Generator) -> nn.Sequential:
    """An MLP from the features to the kicks' values, its weights drawn from
    `generator` as PyTorch's default initialisation draws them."""
    net = nn.Sequential(
        nn.Linear(features, hidden),
        nn.ReLU(),
        nn.Linear(hidden, hidden),
        nn.ReLU(),
        nn.Linear(hidden, len(KICKS)),
    )
    with torch.no_grad():
        for layer in net:
            if isinstance(layer, nn.Linear):
                bound = layer.in_features**-0.5
                layer.weight.uniform_(-bound, bound, generator=generator)
                layer.bias.uniform_(-bound, bound, generator=generator)
    return net


class DoubleDqn(Learner):
    """Double DQN with a replay buffer and a target network, from decision
    to decision."""

    name = "torch-double-dqn"
    version = "1"

    def __init__(
        self,
        start: Start,
        gamma: float = 0.9,
        hidden: int = 64,
        lr: float = 1e-3,
        batch: int = 32,
        replay: int = 10_000,
        warmup: int = 64,
        target_every: int = 100,
        train_every: int = 1,
        epsilon_start: float = 1.0,
        epsilon_end: float = 0.05,
        epsilon_decay: int = 1_000,
    ) -> None:
        """The settings under the names the DQN literature uses: `gamma`
        discounts each frame, as in numpy_learner.py; `hidden` units in each
        of the two hidden layers; Adam's `lr`; `batch` kicks per gradient
        step, drawn from the last `replay` kicks; the first step once
        `warmup` kicks are kept, then one every `train_every` kicks; the
        target network copied every `target_every` steps; epsilon falling
        linearly from `epsilon_start` to `epsilon_end` over the first
        `epsilon_decay` decisions. Other settings: a factory,
        ``functools.partial(DoubleDqn, hidden=128)``."""
        if not 0 < batch <= replay or warmup < 1 or train_every < 1 or target_every < 1:
            raise ValueError(
                f"batch {batch}, replay {replay}, warmup {warmup}, train_every {train_every},"
                f" target_every {target_every}: 0 < batch <= replay, the others at least 1"
            )
        torch.set_num_threads(1)
        torch.use_deterministic_algorithms(True)
        self.generator = torch.Generator().manual_seed(start.seed)
        self.rng = random.Random(start.seed)
        self.actions = len(start.actions)
        self.gamma, self.batch, self.warmup = gamma, batch, warmup
        self.target_every, self.train_every = target_every, train_every
        self.epsilon = (epsilon_start, epsilon_end, epsilon_decay)
        self.online = network(start.features, hidden, self.generator)
        self.target = network(start.features, hidden, self.generator)
        self.target.load_state_dict(self.online.state_dict())
        self.optimizer = torch.optim.Adam(self.online.parameters(), lr=lr)
        #: The replay buffer: kick k's state, action (0-3), discounted reward,
        #: discount of what follows (0 when the episode ended) and next state.
        self.states = torch.zeros(replay, start.features)
        self.kicks = torch.zeros(replay, dtype=torch.long)
        self.rewards = torch.zeros(replay)
        self.discounts = torch.zeros(replay)
        self.next_states = torch.zeros(replay, start.features)
        self.stored = 0  # kicks stored so far; the buffer holds the last `replay`
        self.updates = 0  # gradient steps taken
        self.decisions = 0  # `choose` calls: epsilon's clock
        #: The kicks' values of the states met lately, until the next update:
        #: values and choose ask about one state in turn.
        self.cache: dict[State, list[float]] = {}
        #: The kick being learned: its state and action, the discounted
        #: reward since, and the discount of what follows.
        self.kick: tuple[State, int] | None = None
        self.reward, self.discount = 0.0, 1.0

    def q(self, state: State) -> list[float]:
        """The online network's values of the four kicks in `state`."""
        q = self.cache.get(state)
        if q is None:
            with torch.inference_mode():
                q = self.online(torch.tensor(state)).tolist()
            if len(self.cache) >= 64:
                self.cache.clear()
            self.cache[state] = q
        return q

    def values(self, state: State, index: int | None) -> list[float | None]:
        """None for every action before the first gradient step (an untrained
        network's spread would give advice), then the kicks' values."""
        if self.updates == 0:
            return [None] * self.actions
        q = self.q(state)
        return [None if a not in KICKS else q[a - 1] for a in range(self.actions)]

    def choose(self, state: State, index: int | None) -> int:
        first, last, span = self.epsilon
        epsilon = first + (last - first) * min(1.0, self.decisions / max(span, 1))
        self.decisions += 1
        if self.updates == 0 or self.rng.random() < epsilon:
            return self.rng.choice(KICKS)
        q = self.q(state)
        return KICKS[max(range(len(KICKS)), key=q.__getitem__)]

    def learn(self, t: Transition) -> None:
        if t.action in KICKS:
            self.kick, self.reward, self.discount = (t.state, t.action), 0.0, 1.0
        if self.kick is None:
            return  # moving before its first kick of the episode
        self.reward += self.discount * t.reward
        self.discount *= self.gamma
        if t.next_state is None:
            self.store(None)
        elif t.next_action in KICKS:
            self.store(t.next_state)

    def store(self, next_state: State | None) -> None:
        """Keeps the kick being learned, ending in `next_state` (None: the
        episode ended), and takes a gradient step."""
        state, action = self.kick  # type: ignore[misc]
        k = self.stored % len(self.kicks)
        self.states[k] = torch.tensor(state)
        self.kicks[k] = action - 1
        self.rewards[k] = self.reward
        if next_state is None:
            self.discounts[k] = 0.0
        else:
            self.discounts[k] = self.discount
            self.next_states[k] = torch.tensor(next_state)
        self.stored += 1
        self.kick = None
        if self.stored >= self.warmup and (self.stored - self.warmup) % self.train_every == 0:
            self.update()

    def update(self) -> None:
        """One Double DQN step on a minibatch drawn from the buffer."""
        size = min(self.stored, len(self.kicks))
        k = torch.randint(size, (self.batch,), generator=self.generator)
        states, kicks, next_states = self.states[k], self.kicks[k], self.next_states[k]
        q = self.online(states).gather(1, kicks[:, None]).squeeze(1)
        with torch.no_grad():
            best = self.online(next_states).argmax(1, keepdim=True)
            ahead = self.target(next_states).gather(1, best).squeeze(1)
            target = self.rewards[k] + self.discounts[k] * ahead
        loss = functional.smooth_l1_loss(q, target)
        self.optimizer.zero_grad(set_to_none=True)
        loss.backward()
        self.optimizer.step()
        self.updates += 1
        if self.updates % self.target_every == 0:
            self.target.load_state_dict(self.online.state_dict())
        self.cache.clear()

    def end_episode(self) -> None:
        self.kick = None

    def replay(self, episode: Sequence[Transition]) -> None:
        own = self.kick, self.reward, self.discount
        self.kick = None
        super().replay(episode)
        self.kick, self.reward, self.discount = own

    def save(self) -> bytes:
        """The networks, the optimiser and the counters, as ``torch.save``'s
        bytes (snapshots: --save-agents, load, a restart after a crash)."""
        out = io.BytesIO()
        state = {
            "online": self.online.state_dict(),
            "target": self.target.state_dict(),
            "optimizer": self.optimizer.state_dict(),
            "counters": torch.tensor([self.stored, self.updates, self.decisions]),
        }
        torch.save(state, out)
        return out.getvalue()

    def restore(self, state: bytes) -> None:
        saved = torch.load(io.BytesIO(state), weights_only=True)
        self.online.load_state_dict(saved["online"])
        self.target.load_state_dict(saved["target"])
        self.optimizer.load_state_dict(saved["optimizer"])
        # The buffer is not saved: it fills again before the next step.
        _, self.updates, self.decisions = saved["counters"].tolist()
        self.stored = 0
        self.cache.clear()


if __name__ == "__main__":
    raise SystemExit(serve(DoubleDqn))
