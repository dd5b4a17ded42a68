//! Simulator speed: frames (agent decisions) per second under the paper's random policy.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use env_server::tools::scripted::policy_rng;
use env_server::{Env, EnvConfig, ScriptedPolicy};
use proto::Action;
use std::hint::black_box;

/// Frames stepped per benchmark iteration (episodes restart as they end).
const FRAMES: u64 = 10_000;

fn frames(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulator");
    group.throughput(Throughput::Elements(FRAMES));
    for policy in [ScriptedPolicy::Random, ScriptedPolicy::Shoot] {
        group.bench_function(format!("{policy}-policy-frames"), |b| {
            let mut env = Env::new(EnvConfig::default(), 1).expect("default config");
            let mut rng = policy_rng(1);
            let mut actions = [Action::Move; 3];
            env.reset();
            b.iter(|| {
                for _ in 0..FRAMES {
                    for (i, a) in actions.iter_mut().enumerate() {
                        *a = policy.choose(env.can_kick(i), &mut rng);
                    }
                    if env.step(&actions).is_terminal() {
                        env.reset();
                    }
                }
                black_box(env.frame())
            });
        });
    }
    group.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
