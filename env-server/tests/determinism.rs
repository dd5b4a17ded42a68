//! The same seed and the same actions give the same trajectory, bit for bit.

use env_server::tools::scripted::{play_episode, policy_rng};
use env_server::{Env, EnvConfig, Outcome, ScriptedPolicy};

/// Outcomes and every agent's full feature stream of a few episodes.
fn trace(seed: u64) -> (Vec<(Outcome, u32)>, Vec<Vec<f64>>) {
    let mut env = Env::new(EnvConfig::default(), seed).expect("valid config");
    let mut rng = policy_rng(seed);
    let mut outcomes = Vec::new();
    let mut features = Vec::new();
    for _ in 0..20 {
        let result = play_episode(&mut env, ScriptedPolicy::Random, &mut rng, |env, _| {
            for agent in 0..env.offense() {
                features.push(env.features(agent));
            }
        });
        outcomes.push(result);
    }
    (outcomes, features)
}

#[test]
fn same_seed_same_outcomes_and_features() {
    let (a_out, a_feat) = trace(42);
    let (b_out, b_feat) = trace(42);
    assert_eq!(a_out, b_out);
    assert_eq!(a_feat.len(), b_feat.len());
    let bits = |v: &Vec<Vec<f64>>| v.iter().flatten().map(|f| f.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a_feat), bits(&b_feat));
}

#[test]
fn different_seeds_differ() {
    assert_ne!(trace(1).1, trace(2).1);
}
