//! A fingerprint of the simulator's exact trajectories: a hash of every
//! world state, command and outcome over a rollout of each baseline policy.
//! A speed change must leave it unchanged (docs/speed.md).
//!
//! `cargo run --release -p env-server --example fingerprint -- [EPISODES] [SEED]`

use env_server::tools::policy::{play_episode, policy_rng};
use env_server::{BaselinePolicy, Env, EnvConfig};
use std::hash::{DefaultHasher, Hash, Hasher};

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
                format!("{:?}{:?}", env.world(), env.last_commands()).hash(&mut hasher);
            });
            format!("{outcome:?}{frames}").hash(&mut hasher);
        }
        let hash = hasher.finish();
        hash.hash(&mut all);
        println!("{:<8} {hash:016x}", policy.name());
    }
    println!("all      {:016x}", all.finish());
}
