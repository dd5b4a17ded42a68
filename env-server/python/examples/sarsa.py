"""SARSA with a shared Q-table for a team of HFO attackers, over the
PettingZoo environment: the paper's setup (3 attackers learning together
against HFO's keeper, the paper's 6-feature state, +1 for a goal and -1
for a capture or out of bounds) in a few dozen lines of numpy.

An agent that cannot kick MOVEs; one that can chooses SHOOT, DRIBBLE or a
PASS by an epsilon-greedy policy over the Q-values of its discretised
state. Each agent learns from decision to decision (the next decision's
value, or the episode's reward at its end).

    python examples/sarsa.py --episodes 3000 --seed 1

prints the goal rate of every block of episodes beside the paper's random
policy's.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import halffield

#: Bin edges of the paper's features: goal distance (normalised over
#: 62.5 m: -1 is 0 m), goal angle, goal opening, teammates' goal openings.
EDGES = (
    np.array([-0.75, -0.6, -0.45, -0.3, 0.0]),  # 8, 12.5, 17, 22, 31 m
    np.array([-0.15, 0.15]),
    np.array([-0.8, -0.6]),
    np.array([-0.8]),
    np.array([-0.8]),
)
#: The kick actions an agent with the ball chooses from.
KICKS = np.array([halffield.SHOOT, halffield.DRIBBLE, halffield.PASS, halffield.PASS + 1])


def discretise(observation: np.ndarray) -> tuple[int, ...]:
    """The table cell of a paper observation (its first feature, able to
    kick, is +1 at every decision)."""
    return tuple(int(np.searchsorted(e, x)) for e, x in zip(EDGES, observation[1:]))


class Team:
    """One Q-table shared by every attacker, and each one's last decision."""

    def __init__(
        self,
        rng: np.random.Generator,
        alpha: float = 0.1,
        gamma: float = 0.95,
        epsilon: float = 0.1,
    ) -> None:
        self.q = np.zeros(tuple(len(e) + 1 for e in EDGES) + (len(KICKS),))
        self.rng, self.alpha, self.gamma, self.epsilon = rng, alpha, gamma, epsilon
        self.pending: dict[str, tuple[tuple[int, ...], int]] = {}

    def act(self, agent: str, observation: np.ndarray, mask: np.ndarray) -> int:
        """The agent's action: MOVE without the ball, else epsilon-greedy."""
        if not mask[halffield.SHOOT]:
            return halffield.MOVE
        cell = discretise(observation)
        values = self.q[cell]
        if self.rng.random() < self.epsilon:
            choice = int(self.rng.integers(len(KICKS)))
        else:
            choice = int(self.rng.choice(np.flatnonzero(values == values.max())))
        self.learn(agent, self.gamma * values[choice])
        self.pending[agent] = (cell, choice)
        return int(KICKS[choice])

    def learn(self, agent: str, target: float) -> None:
        """Moves the agent's last decision's value towards ``target``."""
        if agent in self.pending:
            cell, choice = self.pending.pop(agent)
            self.q[cell][choice] += self.alpha * (target - self.q[cell][choice])

    def end_episode(self, reward: float) -> None:
        """Every pending decision learns the episode's reward."""
        for agent in list(self.pending):
            self.learn(agent, reward)


def train(episodes: int, seed: int, block: int = 250) -> list[float]:
    """Trains a team for ``episodes`` episodes; returns the goal rate of
    every ``block`` episodes."""
    env = halffield.parallel_env(observation="paper")
    team = Team(np.random.default_rng(seed))
    rates, goals = [], 0
    observations, infos = env.reset(seed=seed)
    for episode in range(1, episodes + 1):
        while env.agents:
            actions = {a: team.act(a, observations[a], infos[a]["action_mask"]) for a in env.agents}
            observations, rewards, _, _, infos = env.step(actions)
        team.end_episode(rewards["offense_0"])
        goals += infos["offense_0"]["status"] == "GOAL"
        if episode % block == 0:
            rates.append(goals / block)
            goals = 0
        observations, infos = env.reset()
    return rates


def random_goal_rate(episodes: int, seed: int) -> float:
    """The goal rate of the paper's random policy over ``episodes`` episodes."""
    env = halffield.parallel_env(observation="paper")
    policy = halffield.ScriptedPolicy("random", seed)
    env.reset(seed=seed)
    goals = 0
    for episode in range(episodes):
        if episode:
            env.reset()
        while env.agents:
            _, _, _, _, infos = env.step(policy(env))
        goals += infos["offense_0"]["status"] == "GOAL"
    return goals / episodes


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=3000)
    parser.add_argument("--block", type=int, default=250)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    baseline = random_goal_rate(args.episodes, args.seed)
    rates = train(args.episodes, args.seed, args.block)
    print(f"random policy: {100 * baseline:.1f} % goals over {args.episodes} episodes")
    print("episodes  goal %")
    for i, rate in enumerate(rates, start=1):
        print(f"{i * args.block:8d}  {100 * rate:6.1f}")
    print(f"({time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
