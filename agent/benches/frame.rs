//! The per-frame hot path: one `Team::act` for three AdHocTD agents, in
//! training (Q-table lookup, advising, SARSA(lambda) update) and evaluation.

use std::hint::black_box;

use agent::{Agent, AgentConfig, Features, Mode, Observation, Profile, Team};
use criterion::{Criterion, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

const AGENTS: usize = 3;
const EPISODE: usize = 100;

/// Frames of random observations: one kicker (or nobody), features on a
/// coarse grid so that states repeat as they do in play.
fn frames(n: usize) -> Vec<[Observation; AGENTS]> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    (0..n)
        .map(|_| {
            let kicker = rng.random_range(0..=AGENTS);
            std::array::from_fn(|i| {
                let mut state = [0.0; 6];
                state[0] = if i == kicker { 1.0 } else { -1.0 };
                for x in &mut state[1..] {
                    *x = f64::from(rng.random_range(-5..=5)) / 5.0;
                }
                Observation {
                    state,
                    features: Features::NONE,
                    can_kick: i == kicker,
                    position: [0.0, 0.0],
                }
            })
        })
        .collect()
}

fn team() -> Team {
    let config = AgentConfig::of("adhoc-td".parse().unwrap(), Profile::Paper);
    let agents = (0..AGENTS)
        .map(|i| Agent::new(i, AGENTS, config.clone(), i as u64).unwrap())
        .collect();
    Team::new(agents).unwrap()
}

/// Plays `frames` as episodes of [`EPISODE`] frames; the last frame of each
/// episode is terminal with a goal.
fn play(team: &mut Team, frames: &[[Observation; AGENTS]], mode: Mode) {
    for episode in frames.chunks(EPISODE) {
        team.begin_episode(mode);
        for f in episode {
            black_box(team.act(f, 0.0).unwrap());
        }
        team.end_episode(agent::EpisodeOutcome::Goal);
    }
}

fn bench(c: &mut Criterion) {
    let warmup = frames(200 * EPISODE);
    let measured = frames(EPISODE);
    for (name, mode) in [
        ("training", Mode::Training),
        ("evaluation", Mode::Evaluation),
    ] {
        let mut team = team();
        play(&mut team, &warmup, Mode::Training);
        c.bench_function(&format!("team_episode_{EPISODE}_frames_{name}"), |b| {
            b.iter(|| play(&mut team, &measured, mode));
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
