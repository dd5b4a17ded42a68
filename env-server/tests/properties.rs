//! Invariants of the simulator over many seeds, policies and team sizes.

use env_server::Command;
use env_server::features::{current_unum_feature_indices, unum_feature_indices};
use env_server::params::*;
use env_server::tools::scripted::{play_episode, policy_rng};
use env_server::{Env, EnvConfig, Outcome, ScriptedPolicy};
use glam::DVec2;
use proptest::prelude::*;

fn env(seed: u64, offense: usize) -> Env {
    Env::new(
        EnvConfig {
            offense,
            ..EnvConfig::default()
        },
        seed,
    )
    .expect("valid config")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Every normalised feature of every agent stays in [-1, 1] (uniform numbers are raw, as in HFO).
    #[test]
    fn features_stay_in_range(seed in any::<u64>(), policy in 0..5usize, offense in 1..=4usize) {
        let mut env = env(seed, offense);
        let mut rng = policy_rng(seed);
        let raw: Vec<usize> = unum_feature_indices(offense).collect();
        let current_raw: Vec<usize> = current_unum_feature_indices(offense).collect();
        let mut bad = None;
        for _ in 0..3 {
            play_episode(&mut env, ScriptedPolicy::ALL[policy], &mut rng, |env, _| {
                for agent in 0..env.offense() {
                    for (i, f) in env.features(agent).into_iter().enumerate() {
                        if !raw.contains(&i) && !(-1.0..=1.0).contains(&f) {
                            bad.get_or_insert((agent, i, f));
                        }
                    }
                    for (i, f) in env.current_features(agent).into_iter().enumerate() {
                        if !current_raw.contains(&i) && !(-1.0..=1.0).contains(&f) {
                            bad.get_or_insert((agent, 100 + i, f));
                        }
                    }
                    if let Some(f) = env.state(agent).into_iter().find(|f| !(-1.0..=1.0).contains(f)) {
                        bad.get_or_insert((agent, 99, f));
                    }
                }
            });
        }
        prop_assert_eq!(bad, None);
    }

    /// Episodes end by the frame limit, and speeds never exceed the server limits.
    #[test]
    fn limits_hold(seed in any::<u64>(), policy in 0..5usize, offense in 1..=4usize) {
        let mut env = env(seed, offense);
        let mut rng = policy_rng(seed);
        let mut fastest_ball: f64 = 0.0;
        let mut fastest_player: f64 = 0.0;
        for _ in 0..3 {
            let (outcome, frames) = play_episode(&mut env, ScriptedPolicy::ALL[policy], &mut rng, |env, _| {
                let w = env.world();
                fastest_ball = fastest_ball.max(w.ball.vel.length());
                for p in w.players() {
                    fastest_player = fastest_player.max(p.vel.length());
                }
            });
            prop_assert!(outcome.is_terminal());
            prop_assert!(frames <= 199, "{} frames", frames);
        }
        prop_assert!(fastest_ball <= BALL_SPEED_MAX, "ball at {}", fastest_ball);
        prop_assert!(fastest_player <= PLAYER_SPEED_MAX, "player at {}", fastest_player);
    }

    /// A tackle freezes its player: the tackle's cycle and the next nine issue
    /// no command (a successful foul frees it at once), spec 3.5.
    #[test]
    fn tackles_freeze_their_player(seed in any::<u64>(), policy in 0..4usize) {
        let mut env = env(seed, 3);
        let mut rng = policy_rng(seed);
        let mut bad = None;
        for _ in 0..5 {
            let mut before: Option<Vec<u32>> = None;
            play_episode(&mut env, ScriptedPolicy::ALL[policy], &mut rng, |env, _| {
                let now: Vec<u32> = env.world().players().map(|p| p.tackle_freeze).collect();
                if let Some(before) = &before {
                    for (i, command) in env.last_commands().iter().enumerate() {
                        let ok = match command {
                            Command::Tackle { foul, .. } => {
                                before[i] == 0
                                    && (now[i] == TACKLE_CYCLES - 1 || (*foul && now[i] == 0))
                            }
                            _ => {
                                now[i] == before[i].saturating_sub(1)
                                    && (before[i] == 0 || *command == Command::None)
                            }
                        };
                        if !ok {
                            bad.get_or_insert((i, before[i], now[i], *command));
                        }
                    }
                }
                before = Some(now);
            });
        }
        prop_assert_eq!(bad, None);
    }

    /// A goal is only ever scored through the goal mouth.
    #[test]
    fn goals_go_through_the_mouth(seed in any::<u64>(), offense in 1..=4usize) {
        let mut env = env(seed, offense);
        let mut rng = policy_rng(seed);
        for _ in 0..10 {
            let mut path: Vec<DVec2> = Vec::new();
            let (outcome, _) = play_episode(&mut env, ScriptedPolicy::Random, &mut rng, |env, _| {
                path.push(env.world().ball.pos);
            });
            if outcome == Outcome::Goal {
                let (a, b) = (path[path.len() - 2], path[path.len() - 1]);
                let line = PITCH_HALF_LENGTH + BALL_SIZE;
                prop_assert!(a.x <= line && b.x > line);
                let y = a.y + (line - a.x) / (b.x - a.x) * (b.y - a.y);
                prop_assert!(y.abs() <= GOAL_HALF_WIDTH + GOAL_POST_RADIUS, "crossed at y = {}", y);
            }
        }
    }
}

/// Time-outs happen at the frame limit or through the untouched rule, never later.
#[test]
fn episode_start_follows_hfo() {
    let mut env = env(3, 3);
    for _ in 0..200 {
        env.reset();
        let w = env.world();
        assert_eq!(env.frame(), 0);
        assert!(
            (0.0..=10.5 + 1.0).contains(&w.ball.pos.x),
            "ball x {}",
            w.ball.pos.x
        );
        assert!(w.ball.pos.y.abs() <= 27.2 + 1.0);
        assert!(w.keeper.pos.distance(GOAL_CENTER) < 3.0);
        for p in &w.offense {
            assert!(
                p.pos.distance(w.ball.pos) > AGENT_KICKABLE_AREA,
                "nobody starts in possession"
            );
        }
    }
}
