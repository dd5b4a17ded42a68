//! A fingerprint of the simulator's exact trajectories
//! (`env_server::tools::fingerprint`): one hash per scripted policy and one
//! of them all. A speed change must leave it unchanged (docs/speed.md).
//!
//! `cargo run --release -p env-server --example fingerprint -- [EPISODES] [SEED]`

use env_server::tools::fingerprint::fingerprint;

fn main() {
    let mut args = std::env::args().skip(1);
    let episodes: u64 = args
        .next()
        .map_or(2000, |a| a.parse().expect("EPISODES: a count"));
    let seed: u64 = args
        .next()
        .map_or(1, |a| a.parse().expect("SEED: an integer"));
    let (policies, all) = fingerprint(episodes, seed);
    for (policy, hash) in policies {
        println!("{:<8} {hash:016x}", policy.name());
    }
    println!("all      {all:016x}");
}
