//! A fingerprint of the simulator's exact trajectories: a hash of every
//! world state, the agents' memories, commands and outcome over a rollout of
//! each scripted policy. A speed change must leave it unchanged
//! (docs/speed.md); a study records it with every run it plays.

use std::fmt;
use std::hash::{DefaultHasher, Hash, Hasher};

use crate::tools::scripted::{ScriptedPolicy, play_episode, policy_rng};
use crate::{Env, EnvConfig};

/// Episodes of each policy in the fingerprint a study records with its
/// runs (the full check of docs/speed.md plays 2000).
pub const RECORDED_EPISODES: u64 = 10;

/// The fingerprint of `episodes` episodes of each scripted policy from
/// `seed`: one hash per policy, in [`ScriptedPolicy::ALL`]'s order, and
/// the hash of them all.
pub fn fingerprint(episodes: u64, seed: u64) -> (Vec<(ScriptedPolicy, u64)>, u64) {
    let mut all = DefaultHasher::new();
    let policies = ScriptedPolicy::ALL.map(|policy| {
        let mut env = Env::new(EnvConfig::default(), seed).expect("the default config is valid");
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
        (policy, hash)
    });
    (policies.to_vec(), all.finish())
}

/// The state of an `Env` as the fingerprint hashes it: the world's fields,
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
