//! A fingerprint of the simulator's exact trajectories: a hash of every
//! world state, the agents' memories, command and outcome over a rollout of
//! each baseline policy.
//! A speed change must leave it unchanged (docs/speed.md).
//!
//! `cargo run --release -p env-server --example fingerprint -- [EPISODES] [SEED]`

use env_server::tools::baseline::{play_episode, policy_rng};
use env_server::{BaselinePolicy, Env, EnvConfig};
use std::fmt;
use std::hash::{DefaultHasher, Hash, Hasher};

/// The state of an `Env` as the fingerprint prints it: the world's fields,
/// with the agents' memories where the world once held them (so the
/// fingerprint stays comparable across that move).
struct FrameState<'a>(&'a Env);

impl fmt::Debug for FrameState<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (w, memories) = (self.0.world(), self.0.memories());
        let last_shot: Vec<_> = memories.iter().map(|m| m.last_shot).collect();
        let sight: Vec<_> = memories.iter().map(|m| &m.sight).collect();
        f.debug_struct("World")
            .field("ball", &w.ball)
            .field("offense", &w.offense)
            .field("keeper", &w.keeper)
            .field("catch_ban", &w.catch_ban)
            .field("catch_mode", &w.catch_mode)
            .field("offside_line", &w.offside_line)
            .field("last_shot", &last_shot)
            .field("sight", &sight)
            .field("view_phase", &w.view_phase)
            .finish()
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let episodes: u64 = args
        .next()
        .map_or(2000, |a| a.parse().expect("EPISODES: a count"));
    let seed: u64 = args
        .next()
        .map_or(1, |a| a.parse().expect("SEED: an integer"));
    let mut all = DefaultHasher::new();
    for policy in BaselinePolicy::ALL {
        let mut env = Env::new(EnvConfig::default(), seed).expect("default config");
        let mut rng = policy_rng(seed);
        let mut hasher = DefaultHasher::new();
        for _ in 0..episodes {
            let (outcome, frames) = play_episode(&mut env, policy, &mut rng, |env, _| {
                // Debug prints every f64 in its shortest round-trip form: one string per bit pattern.
                format!("{:?}{:?}", FrameState(env), env.last_commands()).hash(&mut hasher);
            });
            format!("{outcome:?}{frames}").hash(&mut hasher);
        }
        let hash = hasher.finish();
        hash.hash(&mut all);
        println!("{:<8} {hash:016x}", policy.name());
    }
    println!("all      {:016x}", all.finish());
}
