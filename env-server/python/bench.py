"""Frames per second of the simulator from Python, beside `env-server
rollout` on the same machine (a benchmark, not a test).

    python bench.py                       # release builds of both
    python bench.py --env-server PATH --episodes 30000 --batch 64 256

Measures, each --repeat times alternately, keeping the best:
- `env-server rollout --policy random --episodes N --seed 1 --json`: one
  thread, no observations computed;
- the PettingZoo environment played by the same policy and seed (the same
  episodes, observations of the "hfo" set computed every step), and what
  each step costs on top of the rollout's frame: the binding's and
  Python's overhead;
- the batch with the paper's random policy drawn in numpy: on one thread
  of its own (its speed per core, measured alternately with the rollout
  so that both see the same load) and on one thread per core.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import time
from pathlib import Path

import numpy as np

import halffield

ROOT = Path(__file__).resolve().parents[2]

#: The paper's random policy with the ball: Shoot, Shoot, Dribble, Dribble, PassFar, PassNear.
RANDOM_KICKS = np.array(
    [halffield.SHOOT] * 2 + [halffield.DRIBBLE] * 2 + [halffield.PASS, halffield.PASS + 1]
)


def rollout_fps(binary: str, episodes: int) -> tuple[float, int]:
    """The Rust rollout's frames per second and frames."""
    command = [
        binary,
        "rollout",
        "--policy",
        "random",
        "--episodes",
        str(episodes),
        "--seed",
        "1",
        "--json",
    ]
    summary = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
    return summary["frames_per_sec"], summary["frames"]


def single_fps(episodes: int) -> tuple[float, int]:
    """The PettingZoo environment's frames per second under the rollout's
    policy and seed, and its frames (the rollout's)."""
    env = halffield.parallel_env()
    policy = halffield.ScriptedPolicy("random", 1)
    frames = 0
    start = time.perf_counter()
    env.reset(seed=1)
    for episode in range(episodes):
        if episode:
            env.reset()
        while env.agents:
            env.step(policy(env))
            frames += 1
    return frames / (time.perf_counter() - start), frames


def batch_fps(n: int, seconds: float, threads: int | None = None) -> float:
    """The batch's frames per second (all environments) over ``seconds``,
    on ``threads`` threads of its own (rayon's global pool when ``None``)."""
    batch = halffield.BatchEnv(n, threads=threads)
    rng = np.random.default_rng(1)
    _, infos = batch.reset(seed=1)
    frames = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        masks = infos["action_mask"]
        kicks = RANDOM_KICKS[rng.integers(len(RANDOM_KICKS), size=masks.shape[:2])]
        actions = np.where(masks[..., halffield.SHOOT] == 1, kicks, halffield.MOVE)
        _, _, _, _, infos = batch.step(actions)
        frames += n
    return frames / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default_binary = os.environ.get("HALFFIELD_ENV_SERVER") or str(
        Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "env-server"
    )
    parser.add_argument(
        "--env-server", default=default_binary, help="a release build of env-server"
    )
    parser.add_argument("--episodes", type=int, default=30000, help="rollout episodes")
    parser.add_argument(
        "--single-episodes", type=int, default=3000, help="episodes of the single environment"
    )
    parser.add_argument("--batch", type=int, nargs="+", default=[64, 256], help="batch sizes")
    parser.add_argument("--seconds", type=float, default=5.0, help="seconds per batch measurement")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    threads = int(os.environ.get("RAYON_NUM_THREADS") or os.cpu_count() or 1)

    rust, single = [], []
    per_core = {n: [] for n in args.batch}
    all_cores = {n: [] for n in args.batch}
    for _ in range(args.repeat):
        rust.append(rollout_fps(args.env_server, args.episodes)[0])
        single.append(single_fps(args.single_episodes)[0])
        for n in args.batch:
            per_core[n].append(batch_fps(n, args.seconds, threads=1))
            all_cores[n].append(batch_fps(n, args.seconds))
    rust_fps, single_best = max(rust), max(single)

    def row(label: str, fps: float, per_core: float) -> None:
        print(f"{label:<44} {fps:>10,.0f} {per_core:>10,.0f} {per_core / rust_fps:>10.2f}")

    print(f"{os.cpu_count()} cores, rayon's pool of {threads} threads; best of {args.repeat}")
    print(f"{'what':<44} {'frames/s':>10} {'per core':>10} {'vs rollout':>10}")
    row("env-server rollout (Rust, 1 thread)", rust_fps, rust_fps)
    row("ParallelEnv + ScriptedPolicy (1 thread)", single_best, single_best)
    for n in args.batch:
        row(f"BatchEnv({n}, threads=1), numpy policy", max(per_core[n]), max(per_core[n]))
        best = max(all_cores[n])
        row(f"BatchEnv({n}), {threads} threads, numpy policy", best, best / threads)
    step_us, frame_us = 1e6 / single_best, 1e6 / rust_fps
    print(
        f"single env: {step_us:.1f} µs per step, of which the simulator's frame {frame_us:.1f} µs: "
        f"{step_us - frame_us:.1f} µs overhead (observations, binding, Python)"
    )


if __name__ == "__main__":
    main()
