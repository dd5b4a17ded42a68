use super::*;
use crate::advice::Reachable;
use crate::exchange::{Advice, Answer, Answers, Isolated, ValuesAdvice};
use crate::fidelity::{Fidelity, Profile};
use crate::learner_settings::LearnerSettings;
use crate::link::NetworkConditions;
use crate::persist::Entry;
use crate::selection::ACTIONS;
use crate::strategy::{
    AdHoc, AdviceImitation, AdviceReuse, EarlyAdvising, EpisodeSharing, PeerLearning, Psaf,
    PsafShares, RandomAdvising, Rcmp, ReuseRule, Torrey,
};
use crate::team::{Team, TeamError};
use Action::{Dribble, Move, PassFar, PassNear, Shoot};
use EpisodeOutcome::{Captured, Goal, OutOfBounds, OutOfTime};
use proto::{AdviceAnswer, Body, Envelope, Header, ValuesAnswer};

/// Kick state number `k` (0..5): distinct keys through feature 2.
fn kick_state(k: usize) -> State {
    [1.0, [-1.0, -0.5, 0.0, 0.5, 1.0][k], 0.0, 0.0, 0.0, 0.0]
}

fn move_state(k: usize) -> State {
    let mut s = kick_state(k);
    s[0] = -1.0;
    s
}

fn obs(state: State) -> Observation {
    Observation {
        state,
        features: Features::NONE,
        can_kick: state[0] > 0.0,
        position: [0.0, 0.0],
    }
}

/// Algorithm `name` with the paper's settings.
fn config(name: &str) -> AgentConfig {
    AgentConfig::of(name.parse().unwrap(), Profile::Paper)
}

/// Algorithm `name` with its settings (of type `S`) changed by `change`.
fn with<S: 'static>(name: &str, change: impl FnOnce(&mut S)) -> AgentConfig {
    let mut c = config(name);
    change(
        c.algorithm
            .get_mut::<S>()
            .expect("the algorithm's settings type"),
    );
    c
}

/// The asker of the requests these tests put to an advisor directly.
const ASKER: usize = 2;

fn agent(id: usize, team_size: usize, config: AgentConfig) -> Agent {
    Agent::new(id, team_size, config, 42 + id as u64).unwrap()
}

/// Entry with the given Q values, all kick actions tried, `visits` visits.
fn known(q: [f64; ACTIONS], visits: u64) -> Entry {
    Entry {
        q,
        tried: 0b11110,
        visits,
    }
}

/// Replaces an agent's table with `entries` (keyed by state), one finished
/// training episode, and starts a training episode.
fn teach(a: &mut Agent, entries: &[(State, Entry)]) {
    let mut entries: Vec<(u64, Entry)> = entries.iter().map(|(s, e)| (a.key(s), *e)).collect();
    entries.sort_unstable_by_key(|&(k, _)| k);
    let snapshot = Snapshot {
        entries,
        training_episodes: 1,
        ..a.snapshot()
    };
    a.restore(snapshot).unwrap();
    a.begin_episode(Mode::Training);
}

/// An exchange that records every call and answers each request with `answers`.
#[derive(Default)]
struct Script {
    answers: Vec<Action>,
    asked: Vec<(usize, Vec<usize>, Option<Action>)>,
    shared: Vec<(usize, usize, Vec<Transition>)>,
}

impl AdviceExchange for Script {
    fn ask(
        &mut self,
        from: usize,
        to: &[usize],
        _: &State,
        _: &Features,
        along: Along,
        answers: &mut Answers,
    ) -> u64 {
        self.asked.push((from, to.to_vec(), along.intended()));
        // The scripted answers come from the advisors asked, in turn.
        answers.advice.extend(
            self.answers
                .iter()
                .zip(to.iter().cycle())
                .map(|(&action, &advisor)| Advice { advisor, action }),
        );
        to.len() as u64
    }

    fn share(&mut self, from: usize, to: usize, share: &Share) {
        self.shared.push((from, to, share.transitions().to_vec()));
    }
}

fn script(answers: &[Action]) -> Script {
    Script {
        answers: answers.to_vec(),
        ..Script::default()
    }
}

/// Answers holding one piece of advice.
fn only(advice: Advice) -> Answers {
    Answers {
        advice: vec![advice],
        ..Answers::default()
    }
}

fn finish_one_episode(a: &mut Agent) {
    a.begin_episode(Mode::Training);
    a.end_episode(OutOfTime);
    a.begin_episode(Mode::Training);
}

#[test]
fn advisee_spends_its_ask_budget_only_when_advised() {
    let mut a = agent(
        0,
        3,
        with("adhoc-visit", |a: &mut AdHoc| {
            a.ask_budget = 2;
        }),
    );
    finish_one_episode(&mut a);
    // No answer: a request is sent, nothing is spent, the state is not marked.
    let mut silent = script(&[]);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
    assert_eq!(silent.asked, vec![(0, vec![1, 2], None)]);
    assert_eq!(
        (a.counters().advice_requests, a.counters().ask_spent),
        (1, 0)
    );
    // Unvisited states ask with P_ask = 1.5^0 = 1. Two advised states spend the budget of 2.
    let mut ex = script(&[PassNear, PassNear]);
    assert_eq!(a.act(&obs(kick_state(1)), 0.0, &[], &mut ex), PassNear);
    assert_eq!(a.act(&obs(kick_state(2)), 0.0, &[], &mut ex), PassNear);
    a.act(&obs(kick_state(3)), 0.0, &[], &mut ex);
    assert_eq!(ex.asked.len(), 2, "the third state finds the budget spent");
    let c = a.counters();
    // Both teammates reply to each of the three requests, with advice or without.
    assert_eq!(
        (c.advice_requests, c.ask_spent, c.advice_replies_received),
        (3, 2, 6)
    );
}

#[test]
fn asks_at_most_once_per_state_per_episode() {
    // v_a = 0: P_ask = 1 whatever n(s), so only the advised-state rule stops asking.
    let mut a = agent(
        1,
        3,
        with("adhoc-td", |a: &mut AdHoc| {
            a.v_a = 0.0;
        }),
    );
    finish_one_episode(&mut a);
    let mut ex = script(&[Dribble]);
    assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut ex), Dribble);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    assert_eq!(ex.asked.len(), 1);
    a.end_episode(OutOfTime);
    a.begin_episode(Mode::Training);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    assert_eq!(ex.asked.len(), 2, "a new episode may ask again");
}

#[test]
fn no_asking_before_a_finished_episode_without_the_ball_or_when_evaluating() {
    let mut a = agent(0, 3, config("adhoc-td"));
    let mut ex = script(&[Dribble]);
    a.begin_episode(Mode::Training);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    assert!(ex.asked.is_empty(), "no training episode finished yet");
    a.end_episode(OutOfTime);
    a.begin_episode(Mode::Training);
    assert_eq!(a.act(&obs(move_state(1)), 0.0, &[], &mut ex), Move);
    assert!(ex.asked.is_empty(), "cannot kick");
    a.begin_episode(Mode::Evaluation);
    a.act(&obs(kick_state(2)), 0.0, &[], &mut ex);
    assert!(ex.asked.is_empty(), "evaluation");
}

#[test]
fn advisor_needs_visits_and_budget() {
    let mut a = agent(
        0,
        3,
        with("adhoc-td", |a: &mut AdHoc| {
            a.give_budget = 2;
        }),
    );
    // Greedy PassFar; spread over tried kicks = 1 - 0 = 1; Psi = sqrt(10000) * 1 = 100;
    // P_give = 1 - 2.5^-100 = 1.0 in f64.
    let q = [0.0, 0.0, 0.5, 0.2, 1.0];
    teach(
        &mut a,
        &[
            (kick_state(0), known(q, 10_000)),
            (kick_state(1), known(q, 0)),
        ],
    );
    assert_eq!(a.advise(ASKER, &kick_state(1), &[], None), None, "n(s) = 0");
    assert_eq!(
        a.advise(ASKER, &kick_state(2), &[], None),
        None,
        "unknown state"
    );
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), Some(PassFar));
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), Some(PassFar));
    assert_eq!(
        a.advise(ASKER, &kick_state(0), &[], None),
        None,
        "give budget of 2 spent"
    );
    assert_eq!(a.counters().advice_given, 2);
    assert_eq!(a.spent_budget(), 2);
}

#[test]
fn visit_based_advisor_uses_log2_visits() {
    // n = 1: Psi = log2 1 = 0, P_give = 0.
    let mut a = agent(0, 3, config("adhoc-visit"));
    teach(
        &mut a,
        &[(kick_state(0), known([0.0, 0.0, 1.0, 0.0, 0.0], 1))],
    );
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), None);
    // n = 2: Psi = 1; v_g = 1e9: P_give = 1 - 1e-9 (a draw above it is vanishingly rare).
    let mut b = agent(
        0,
        3,
        with("adhoc-visit", |a: &mut AdHoc| {
            a.v_g = 1e9;
        }),
    );
    teach(
        &mut b,
        &[(kick_state(0), known([0.0, 0.0, 1.0, 0.0, 0.0], 2))],
    );
    assert_eq!(b.advise(ASKER, &kick_state(0), &[], None), Some(Dribble));
}

#[test]
fn mistake_correcting_spends_nothing_when_advice_equals_intended() {
    // Advisor side: greedy Shoot, P_give = 1 (see advisor_needs_visits_and_budget).
    let mc = with("adhoc-td", |a: &mut AdHoc| {
        a.mistake_correcting = true;
    });
    let mut advisor = agent(1, 3, mc.clone());
    teach(
        &mut advisor,
        &[(kick_state(0), known([0.0, 1.0, 0.0, 0.0, 0.0], 10_000))],
    );
    assert_eq!(
        advisor.advise(ASKER, &kick_state(0), &[], Some(Shoot)),
        None
    );
    assert_eq!(advisor.counters().advice_given, 0);
    assert_eq!(
        advisor.advise(ASKER, &kick_state(0), &[], Some(Dribble)),
        Some(Shoot)
    );
    assert_eq!(advisor.counters().advice_given, 1);

    // Advisee side: it sends its own epsilon-greedy choice (epsilon 0: greedy
    // Dribble) and, without an answer, plays it.
    let mut advisee = agent(0, 3, AgentConfig { epsilon: 0.0, ..mc });
    teach(
        &mut advisee,
        &[(kick_state(0), known([0.0, 0.0, 0.7, 0.0, 0.0], 0))],
    );
    let mut silent = script(&[]);
    assert_eq!(
        advisee.act(&obs(kick_state(0)), 0.0, &[], &mut silent),
        Dribble
    );
    assert_eq!(silent.asked, vec![(0, vec![1, 2], Some(Dribble))]);
    assert_eq!(advisee.counters().ask_spent, 0);
}

#[test]
fn torrey_students_ask_their_fixed_teacher_at_every_fresh_kick_state() {
    for i in 0..3 {
        let mut a = agent(i, 3, config("torrey"));
        // No finished episode needed, no ask budget.
        a.begin_episode(Mode::Training);
        let mut ex = script(&[]);
        a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
        a.act(&obs(move_state(0)), 0.0, &[], &mut ex);
        a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
        assert_eq!(ex.asked, vec![(i, vec![(i + 1) % 3], None); 2], "agent {i}");
        // Once advised, a state is not shown again in this episode.
        let mut ex = script(&[Dribble]);
        a.act(&obs(kick_state(1)), 0.0, &[], &mut ex);
        a.act(&obs(kick_state(1)), 0.0, &[], &mut ex);
        assert_eq!(ex.asked.len(), 1);
    }
}

#[test]
fn torrey_teacher_advises_above_the_threshold_within_its_budget() {
    let mut t = agent(
        1,
        3,
        with("torrey", |t: &mut Torrey| {
            t.give_budget = 1;
        }),
    );
    // Spreads: 0.01 (not above t = 0.01) and 0.02; visits play no role.
    teach(
        &mut t,
        &[
            (kick_state(0), known([0.0, 0.0, 0.01, 0.0, 0.0], 0)),
            (kick_state(1), known([0.0, 0.0, 0.0, 0.02, 0.0], 0)),
        ],
    );
    assert_eq!(t.advise(ASKER, &kick_state(0), &[], None), None);
    assert_eq!(t.advise(ASKER, &kick_state(1), &[], None), Some(PassNear));
    assert_eq!(
        t.advise(ASKER, &kick_state(1), &[], None),
        None,
        "budget of 1 spent"
    );

    // In a team, agent 0's teacher is agent 1 (agent 2 knows too, but is not asked).
    let mut agents: Vec<Agent> = (0..3).map(|i| agent(i, 3, config("torrey"))).collect();
    let q = [0.0, 0.0, 0.0, 0.0, 0.5];
    teach(&mut agents[1], &[(kick_state(0), known(q, 0))]);
    teach(
        &mut agents[2],
        &[(kick_state(0), known([0.0, 0.5, 0.0, 0.0, 0.0], 0))],
    );
    let mut team = Team::new(agents).unwrap();
    team.begin_episode(Mode::Training);
    let frame = [obs(kick_state(0)), obs(move_state(0)), obs(move_state(0))];
    assert_eq!(team.act(&frame, 0.0).unwrap()[0], PassFar);
    let given: Vec<u64> = team
        .agents()
        .iter()
        .map(|a| a.counters().advice_given)
        .collect();
    assert_eq!(given, vec![0, 1, 0]);
}

#[test]
fn episode_sharing_spends_one_unit_per_transition_per_receiver() {
    let sharing = |s: &mut EpisodeSharing| s.sharing_budget = 5;
    let mut a = agent(0, 3, with("episode-sharing", sharing));
    let mut ex = script(&[]);
    a.begin_episode(Mode::Training);
    // Frames s0..s3 then the terminal step: transitions t0..t3.
    let states = [move_state(0), move_state(1), kick_state(2), move_state(3)];
    let mut actions = Vec::new();
    for s in states {
        actions.push(a.act(&obs(s), 0.0, &[], &mut ex));
    }
    a.end_episode(Goal);
    a.share_episode(&mut ex);
    // Budget 5 over 2 receivers: t0->1, t0->2, t1->1, t1->2, t2->1.
    let lens: Vec<(usize, usize, usize)> = ex
        .shared
        .iter()
        .map(|(f, t, v)| (*f, *t, v.len()))
        .collect();
    assert_eq!(lens, vec![(0, 1, 3), (0, 2, 2)]);
    assert_eq!(a.counters().shared_sent, 5);
    assert_eq!(a.spent_budget(), 5);
    let first = ex.shared[0].2[0];
    assert_eq!(
        first,
        Transition {
            state: states[0],
            action: Move,
            reward: 0.0,
            next: Some((states[1], Move))
        }
    );
    assert_eq!(ex.shared[0].2[2].next, Some((states[3], actions[3])));

    // Budget spent: the next goal episode shares nothing.
    a.begin_episode(Mode::Training);
    a.act(&obs(move_state(0)), 0.0, &[], &mut ex);
    a.end_episode(Goal);
    a.share_episode(&mut ex);
    assert_eq!(ex.shared.len(), 2);
}

#[test]
fn only_goal_episodes_are_shared_and_the_terminal_step_has_no_next() {
    let mut a = agent(2, 3, config("episode-sharing"));
    let mut ex = script(&[]);
    for outcome in [Captured, OutOfTime, Goal] {
        a.begin_episode(Mode::Training);
        a.act(&obs(move_state(0)), 0.0, &[], &mut ex);
        a.act(&obs(move_state(1)), 0.0, &[], &mut ex);
        a.end_episode(outcome);
        a.share_episode(&mut ex);
    }
    // Only the goal episode, to agents 0 and 1, two transitions each.
    assert_eq!(
        ex.shared
            .iter()
            .map(|(_, t, v)| (*t, v.len()))
            .collect::<Vec<_>>(),
        vec![(0, 2), (1, 2)]
    );
    let last = ex.shared[0].2[1];
    assert_eq!((last.reward, last.next), (1.0, None));
}

#[test]
fn received_episode_is_replayed_with_a_fresh_trace() {
    let mut a = agent(1, 3, config("episode-sharing"));
    a.begin_episode(Mode::Training);
    // Own pending step in another state, untouched by the replay.
    a.act(&obs(move_state(4)), 0.0, &[], &mut Isolated);
    let (s0, s1) = (kick_state(0), move_state(1));
    a.receive_shared(&[
        Transition {
            state: s0,
            action: Shoot,
            reward: 0.0,
            next: Some((s1, Move)),
        },
        Transition {
            state: s1,
            action: Move,
            reward: 1.0,
            next: None,
        },
    ]);
    // t0: delta = 0 + 0.9 * 0 - 0 = 0, e(s0,S) -> 0.81.
    // t1: delta = 1 - 0 = 1: Q(s1,M) = 0.1 * 1 * 1 = 0.1, Q(s0,S) = 0.1 * 1 * 0.81 = 0.081.
    let q = |a: &mut Agent, s: &State, x: Action| a.entry(s).unwrap().q[x.index()];
    assert!((q(&mut a, &s1, Move) - 0.1).abs() < 1e-12);
    assert!((q(&mut a, &s0, Shoot) - 0.081).abs() < 1e-12);
    assert_eq!(a.entry(&s0).unwrap().visits, 0, "replay is not a visit");
    assert_eq!(a.counters().shared_received, 2);
    // The own trace only holds the own step: a terminal -1 moves only Q(s4, Move).
    a.end_episode(Captured);
    assert!((q(&mut a, &move_state(4), Move) + 0.1).abs() < 1e-12);
    assert!((q(&mut a, &s0, Shoot) - 0.081).abs() < 1e-12);
}

#[test]
fn learns_move_steps_and_counts_visits() {
    let mut a = agent(0, 1, config("no-advice"));
    a.begin_episode(Mode::Training);
    assert_eq!(a.act(&obs(move_state(0)), 0.0, &[], &mut Isolated), Move);
    assert_eq!(a.act(&obs(move_state(1)), 0.0, &[], &mut Isolated), Move);
    a.end_episode(Captured);
    // Terminal delta = -1: Q(s1,M) = -0.1, Q(s0,M) = -0.1 * 0.81 = -0.081.
    let e0 = a.entry(&move_state(0)).unwrap();
    let e1 = a.entry(&move_state(1)).unwrap();
    assert!((e0.q[Move.index()] + 0.081).abs() < 1e-12);
    assert!((e1.q[Move.index()] + 0.1).abs() < 1e-12);
    assert_eq!((e0.visits, e1.visits), (1, 1));
    assert_eq!(a.training_episodes(), 1);
}

#[test]
fn evaluation_plays_greedy_in_tie_order() {
    let mut a = agent(0, 1, config("no-advice"));
    teach(
        &mut a,
        &[(kick_state(0), known([0.0, 0.0, 0.0, 0.3, 0.3], 0))],
    );
    a.begin_episode(Mode::Evaluation);
    // PassNear and PassFar tie at 0.3: PassFar comes first in the tie order.
    assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut Isolated), PassFar);
    // Unknown state: all zero, Shoot first.
    assert_eq!(a.act(&obs(kick_state(1)), 0.0, &[], &mut Isolated), Shoot);
    assert_eq!(a.act(&obs(move_state(1)), 0.0, &[], &mut Isolated), Move);
}

#[test]
fn random_baseline_never_learns_nor_advises() {
    let mut a = agent(0, 3, config("random"));
    let mut seen = [false; ACTIONS];
    for mode in [Mode::Training, Mode::Evaluation] {
        a.begin_episode(mode);
        for k in 0..200 {
            seen[a
                .act(&obs(kick_state(k % 5)), 0.0, &[], &mut Isolated)
                .index()] = true;
            assert_eq!(
                a.act(&obs(move_state(k % 5)), 0.0, &[], &mut Isolated),
                Move
            );
        }
        a.end_episode(Goal);
    }
    assert_eq!(seen, [false, true, true, true, true]);
    assert!(a.states_met() == 0);
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), None);
}

/// Plays `episodes` episodes of random frames over 9 kick and 9 move states.
fn play(team: &mut Team, rng: &mut AgentRng, episodes: usize, mode: Mode) -> Vec<Action> {
    let values = [-0.5, 0.0, 0.5];
    let mut log = Vec::new();
    for _ in 0..episodes {
        team.begin_episode(mode);
        let mut reward = 0.0;
        for _ in 0..rng.random_range(1..25) {
            let kicker = rng.random_range(0..4); // 3: nobody has the ball
            let frame: Vec<Observation> = (0..3)
                .map(|i| {
                    let mut s = [0.0; 6];
                    s[1] = values[rng.random_range(0..values.len())];
                    s[2] = values[rng.random_range(0..values.len())];
                    s[0] = if i == kicker { 1.0 } else { -1.0 };
                    let position = [rng.random_range(0.0..10.0), 0.0];
                    Observation {
                        state: s,
                        features: Features::NONE,
                        can_kick: i == kicker,
                        position,
                    }
                })
                .collect();
            log.extend_from_slice(team.act(&frame, reward).unwrap());
            reward = 0.0;
        }
        team.end_episode([Captured, OutOfTime, Goal][rng.random_range(0..3)]);
    }
    log
}

fn team(strategy: &str, seed: u64) -> Team {
    let c = config(strategy);
    Team::new(
        (0..3)
            .map(|i| Agent::new(i, 3, c.clone(), seed + i as u64).unwrap())
            .collect(),
    )
    .unwrap()
}

fn digests(team: &Team) -> Vec<u64> {
    team.agents().iter().map(Agent::digest).collect()
}

#[test]
fn evaluation_changes_no_learned_state() {
    for strategy in ["adhoc-td", "torrey", "episode-sharing"] {
        let mut t = team(strategy, 7);
        let mut rng = AgentRng::seed_from_u64(1);
        play(&mut t, &mut rng, 40, Mode::Training);
        let before = digests(&t);
        let sizes: Vec<usize> = t.agents().iter().map(|a| a.states_met()).collect();
        // New states included: they must not even get an entry.
        play(&mut t, &mut rng, 20, Mode::Evaluation);
        assert_eq!(digests(&t), before, "{strategy:?}");
        assert_eq!(
            t.agents()
                .iter()
                .map(|a| a.states_met())
                .collect::<Vec<_>>(),
            sizes
        );
    }
}

#[test]
fn same_seed_same_run_bit_for_bit() {
    for strategy in ["adhoc-visit", "adhoc-td", "torrey", "episode-sharing"] {
        let run = |seed| {
            let mut t = team(strategy, seed);
            let log = play(&mut t, &mut AgentRng::seed_from_u64(3), 60, Mode::Training);
            (log, digests(&t))
        };
        let (a, b) = (run(11), run(11));
        assert_eq!(a, b, "{strategy:?}");
        assert_ne!(a.1, run(12).1, "{strategy:?}: the seed matters");
        // Advice actually flowed in these runs.
        let t = {
            let mut t = team(strategy, 11);
            play(&mut t, &mut AgentRng::seed_from_u64(3), 60, Mode::Training);
            t
        };
        assert!(
            t.agents().iter().any(|a| a.spent_budget() > 0),
            "{strategy:?}"
        );
    }
}

/// A team of three advice-imitation agents with a budget of 40 and short
/// imitation rounds, on small DQNs.
fn imitating(seed: u64) -> Team {
    let mut c = with("advice-imitation", |s: &mut AdviceImitation| {
        s.ask_budget = 40;
        s.initial_iterations_per_advice = 2.0;
        s.periodic_iterations_per_advice = 1.0;
    });
    let LearnerSettings::Dqn(dqn) = &mut c.learner else {
        panic!(
            "advice-imitation learns with the DQN by default: {:?}",
            c.learner
        );
    };
    dqn.hidden = vec![16];
    dqn.warmup = 32;
    let agents = (0..3).map(|i| Agent::new(i, 3, c.clone(), seed + i as u64).unwrap());
    Team::new(agents.collect()).unwrap()
}

#[test]
fn advice_imitation_collects_imitates_and_reuses_for_free() {
    let run = |seed| {
        let mut t = imitating(seed);
        let log = play(&mut t, &mut AgentRng::seed_from_u64(3), 150, Mode::Training);
        let counters: Vec<_> = t.agents().iter().map(|a| *a.counters()).collect();
        let reused: Vec<u64> = t
            .agents()
            .iter()
            .map(|a| a.request_outcomes().reused)
            .collect();
        (log, counters, reused)
    };
    let (log, counters, reused) = run(5);
    for c in &counters {
        // It asked unconditionally for its first 4 samples (a tenth of the
        // budget), then only where its imitation was unsure, and answered
        // its teammates.
        assert!(c.ask_spent >= 4 && c.ask_spent <= 40, "{c:?}");
        assert!(
            c.advice_requests >= c.ask_spent && c.advice_given > 0,
            "{c:?}"
        );
    }
    // Reuse comes only after an imitation round, in reuse episodes, and
    // spends nothing.
    assert!(reused.iter().all(|&r| r > 0), "reused {reused:?}");
    // One seed, one run.
    assert_eq!(run(5), (log, counters, reused));
}

#[test]
fn network_conditions_lose_late_and_lost_advice_and_nothing_else() {
    let run = |latency: &str, loss: f64| {
        let network = NetworkConditions {
            latency: latency.parse().unwrap(),
            loss,
            timeout_ms: 5.0,
        };
        let c = AgentConfig {
            network: Some(network),
            ..config("adhoc-td")
        };
        let agents = (0..3).map(|i| Agent::new(i, 3, c.clone(), 11 + i as u64).unwrap());
        let mut t = Team::new(agents.collect()).unwrap();
        let log = play(&mut t, &mut AgentRng::seed_from_u64(3), 60, Mode::Training);
        let sum = |f: fn(&AdviceCounters) -> u64| t.agents().iter().map(|a| f(a.counters())).sum();
        let counts: [u64; 3] = [
            sum(|c| c.advice_requests),
            sum(|c| c.advice_given),
            sum(|c| c.advice_replies_received),
        ];
        (log, digests(&t), counts)
    };
    let free = {
        let mut t = team("adhoc-td", 11);
        let log = play(&mut t, &mut AgentRng::seed_from_u64(3), 60, Mode::Training);
        (log, digests(&t))
    };
    // No loss and every round trip within the timeout: bit for bit.
    for latency in ["fixed:0", "fixed:2.5", "uniform:0,2.5"] {
        let (log, digests, counts) = run(latency, 0.0);
        assert_eq!((log, digests), free, "{latency}");
        // Both teammates reply to every request, with advice or without.
        assert!(counts[0] > 0);
        assert_eq!(counts[2], 2 * counts[0], "{latency}");
    }
    // Every request lost: the advisors never hear of them.
    let [asked, given, received] = run("fixed:0", 1.0).2;
    assert!(asked > 0);
    assert_eq!((given, received), (0, 0));
    // Every reply late (3 + 3 ms > 5): given, never received.
    let [_, given, received] = run("fixed:3", 0.0).2;
    assert!(given > 0);
    assert_eq!(received, 0);
    // Some lost or late: fewer replies than the two per request.
    let [asked, _, received] = run("lognormal:2,0.5", 0.2).2;
    assert!(
        0 < received && received < 2 * asked,
        "{received} of {asked}"
    );
}

#[test]
fn reachable_within_distance_filters_advisors() {
    // v_a = 0: P_ask = 1 on every visit.
    let c = with("adhoc-td", |a: &mut AdHoc| {
        a.v_a = 0.0;
        a.reachable = Reachable::WithinDistance(5.0);
    });
    let mut agents: Vec<Agent> = (0..3).map(|i| agent(i, 3, c.clone())).collect();
    finish_one_episode(&mut agents[0]);
    // Only agent 2 could answer (greedy Dribble, P_give = 1).
    teach(
        &mut agents[2],
        &[(kick_state(0), known([0.0, 0.0, 1.0, 0.0, 0.0], 10_000))],
    );
    let mut team = Team::new(agents).unwrap();
    let at = |x: f64, s: State| Observation {
        position: [x, 0.0],
        ..obs(s)
    };
    team.begin_episode(Mode::Training);
    // Agent 2 at distance 8: out of reach, no advice.
    team.act(
        &[
            at(0.0, kick_state(0)),
            at(4.0, move_state(0)),
            at(8.0, move_state(0)),
        ],
        0.0,
    )
    .unwrap();
    assert_eq!(team.agents()[0].counters().ask_spent, 0);
    // A new episode with agent 2 at distance 3.
    team.end_episode(OutOfTime);
    team.begin_episode(Mode::Training);
    let actions = team
        .act(
            &[
                at(0.0, kick_state(0)),
                at(9.0, move_state(0)),
                at(3.0, move_state(0)),
            ],
            0.0,
        )
        .unwrap();
    assert_eq!(actions[0], Dribble);
    assert_eq!(team.agents()[0].counters().ask_spent, 1);
}

#[test]
fn snapshot_restores_into_a_fresh_agent_of_the_same_tiling() {
    let mut t = team("adhoc-td", 5);
    play(&mut t, &mut AgentRng::seed_from_u64(9), 30, Mode::Training);
    let trained = &t.agents()[2];
    let bytes = trained.snapshot().encode().unwrap();
    let mut fresh = agent(2, 3, config("adhoc-td"));
    fresh.restore(Snapshot::decode(&bytes).unwrap()).unwrap();
    assert_eq!(fresh.digest(), trained.digest());
    assert_eq!(fresh.snapshot().entries, trained.snapshot().entries);
    let five = AgentConfig {
        tiles_per_feature: 5,
        tile_step: 0.4,
        ..AgentConfig::default()
    };
    let err = agent(0, 1, five)
        .restore(Snapshot::decode(&bytes).unwrap())
        .unwrap_err();
    assert!(matches!(err, PersistError::Incompatible { .. }), "{err}");
    // A learner's own state is not for SARSA(lambda).
    let foreign = Snapshot {
        learner_state: Some(vec![1, 2, 3]),
        ..Snapshot::decode(&bytes).unwrap()
    };
    let err = fresh.restore(foreign).unwrap_err();
    assert!(
        err.to_string().contains("keeps no state of its own"),
        "{err}"
    );
}

#[test]
fn bad_construction_and_frames_are_errors() {
    assert_eq!(
        Agent::new(3, 3, AgentConfig::default(), 0).unwrap_err().key,
        "team_size"
    );
    let dup = with("adhoc-td", |a: &mut AdHoc| {
        a.reachable = Reachable::Agents(vec![1, 1]);
    });
    assert_eq!(Agent::new(0, 3, dup, 0).unwrap_err().key, "reachable");
    let c = AgentConfig::default();
    let swapped = vec![agent(1, 2, c.clone()), agent(0, 2, c.clone())];
    assert_eq!(
        Team::new(swapped).unwrap_err(),
        TeamError::Id { index: 0, id: 1 }
    );
    let sizes = vec![agent(0, 2, c.clone()), agent(1, 3, c.clone())];
    assert_eq!(
        Team::new(sizes).unwrap_err(),
        TeamError::Size {
            id: 1,
            built_for: 3,
            size: 2
        }
    );
    let mut t = Team::new(vec![agent(0, 1, c)]).unwrap();
    assert_eq!(
        t.act(&[], 0.0).unwrap_err(),
        TeamError::Observations {
            expected: 1,
            got: 0
        }
    );
}

/// Random episodes like [`play`]'s: frames of 3 observations and how each ended.
fn random_episodes(
    rng: &mut AgentRng,
    episodes: usize,
) -> Vec<(Vec<Vec<Observation>>, EpisodeOutcome)> {
    let values = [-0.5, 0.0, 0.5];
    (0..episodes)
        .map(|_| {
            let frames = (0..rng.random_range(1..25))
                .map(|_| {
                    let kicker = rng.random_range(0..4);
                    (0..3)
                        .map(|i| {
                            let mut s = [0.0; 6];
                            s[1] = values[rng.random_range(0..values.len())];
                            s[2] = values[rng.random_range(0..values.len())];
                            s[0] = if i == kicker { 1.0 } else { -1.0 };
                            Observation {
                                state: s,
                                features: Features::NONE,
                                can_kick: i == kicker,
                                position: [rng.random_range(0.0..10.0), 0.0],
                            }
                        })
                        .collect()
                })
                .collect();
            (frames, [Captured, OutOfTime, Goal][rng.random_range(0..3)])
        })
        .collect()
}

/// Plays `episodes` with the two-phase API, advisors answering in the order
/// of each request and shared episodes delivered from `take_shared`.
fn play_two_phase(
    agents: &mut [Agent],
    episodes: &[(Vec<Vec<Observation>>, EpisodeOutcome)],
    mode: Mode,
) -> Vec<Action> {
    let mut log = Vec::new();
    for (frames, outcome) in episodes {
        agents.iter_mut().for_each(|a| a.begin_episode(mode));
        for frame in frames {
            let positions: Vec<[f64; 2]> = frame.iter().map(|o| o.position).collect();
            for (i, obs) in frame.iter().enumerate() {
                let action = match agents[i].act_begin(obs, 0.0, &positions, &|_| true) {
                    Decision::Act(action) => action,
                    Decision::Ask {
                        to, state, along, ..
                    } => {
                        let advice = to
                            .iter()
                            .filter_map(|&j| {
                                let action = agents[j].advise(i, &state, &[], along.intended())?;
                                Some(Advice { advisor: j, action })
                            })
                            .collect();
                        let answers = Answers {
                            advice,
                            ..Answers::default()
                        };
                        agents[i].act_complete(&answers, to.len() as u64)
                    }
                };
                log.push(action);
            }
        }
        agents.iter_mut().for_each(|a| a.end_episode(*outcome));
        for i in 0..agents.len() {
            for (to, share) in agents[i].take_shared() {
                match share {
                    Share::Episode(t) => agents[to].receive_shared(&t),
                    Share::Batch(t) => assert!(agents[to].receive_batch(i, &t)),
                }
            }
        }
    }
    log
}

/// Plays `episodes` through [`Team::act`].
fn play_team(
    team: &mut Team,
    episodes: &[(Vec<Vec<Observation>>, EpisodeOutcome)],
    mode: Mode,
) -> Vec<Action> {
    let mut log = Vec::new();
    for (frames, outcome) in episodes {
        team.begin_episode(mode);
        for frame in frames {
            log.extend_from_slice(team.act(frame, 0.0).unwrap());
        }
        team.end_episode(*outcome);
    }
    log
}

#[test]
fn two_phase_frames_equal_act_for_the_same_seed() {
    for strategy in [
        "adhoc-visit",
        "adhoc-td",
        "torrey",
        "episode-sharing",
        "random",
    ] {
        for mistake_correcting in [false, true] {
            let mut c = config(strategy);
            if mistake_correcting && c.algorithm.set("mistake_correcting", true).is_err() {
                continue;
            }
            let build = || -> Vec<Agent> {
                (0..3)
                    .map(|i| Agent::new(i, 3, c.clone(), 21 + i as u64).unwrap())
                    .collect()
            };
            let episodes = random_episodes(&mut AgentRng::seed_from_u64(4), 50);
            let mut team = Team::new(build()).unwrap();
            let mut agents = build();
            let mut team_log = Vec::new();
            let mut split_log = Vec::new();
            for mode in [Mode::Training, Mode::Evaluation] {
                team_log.extend(play_team(&mut team, &episodes, mode));
                split_log.extend(play_two_phase(&mut agents, &episodes, mode));
            }
            let label = format!("{strategy:?}, mistake correcting {mistake_correcting}");
            assert_eq!(team_log, split_log, "{label}");
            assert_eq!(
                digests(&team),
                agents.iter().map(Agent::digest).collect::<Vec<_>>(),
                "{label}"
            );
            assert!(
                agents
                    .iter()
                    .all(|a| *a.counters() == *team.agents()[a.id()].counters()),
                "{label}"
            );
        }
    }
}

#[test]
fn unreachable_advisors_are_left_out_and_nobody_reachable_asks_nobody() {
    let mut a = agent(0, 3, config("adhoc-td"));
    finish_one_episode(&mut a);
    // Unvisited state: P_ask = 1.
    let decision = a.act_begin(&obs(kick_state(0)), 0.0, &[], &|j| j != 1);
    assert_eq!(
        decision,
        Decision::Ask {
            to: vec![2],
            state: kick_state(0),
            features: Features::NONE,
            along: Along::Nothing
        }
    );
    let advice = Advice {
        advisor: 2,
        action: PassNear,
    };
    assert_eq!(a.act_complete(&only(advice), 1), PassNear);
    assert_eq!(a.counters().ask_spent, 1);
    // Nobody reachable: the agent acts on its own and sends no request.
    let decision = a.act_begin(&obs(kick_state(1)), 0.0, &[], &|_| false);
    assert!(matches!(decision, Decision::Act(a) if a.is_kick()));
    assert_eq!(a.counters().advice_requests, 1);
}

#[test]
fn an_abandoned_ask_completes_to_nothing() {
    let mut a = agent(0, 3, config("adhoc-td"));
    finish_one_episode(&mut a);
    let before = a.digest();
    assert!(matches!(
        a.act_begin(&obs(kick_state(0)), 0.0, &[], &|_| true),
        Decision::Ask { .. }
    ));
    // The episode ends before the answers arrive: they change nothing.
    a.end_episode(OutOfTime);
    let after_end = a.digest();
    let late = Advice {
        advisor: 1,
        action: Dribble,
    };
    assert_eq!(a.act_complete(&only(late), 2), Move);
    assert_eq!(a.digest(), after_end);
    assert_eq!(a.counters().ask_spent, 0);
    assert_ne!(before, after_end, "the episode count moved on");
}

/// `config` under the authors' fidelity rules.
fn authors(config: AgentConfig) -> AgentConfig {
    AgentConfig {
        fidelity: Fidelity::of(Profile::Authors),
        ..config
    }
}

#[test]
fn an_authors_torrey_teacher_advises_a_random_kick_where_it_knows_no_kick() {
    let paper = config("torrey");
    let mut t = agent(1, 3, paper.clone());
    teach(&mut t, &[]);
    assert_eq!(t.advise(ASKER, &kick_state(0), &[], None), None);
    // The authors': unseen states and states without a kick entry are
    // advised, each answer a uniformly random kick, one budget unit each.
    let mut t = agent(1, 3, authors(config("torrey")));
    let only_move = Entry {
        tried: 0b00001,
        ..Entry::default()
    };
    let one_kick = Entry {
        tried: 0b00010,
        ..Entry::default()
    };
    teach(
        &mut t,
        &[(kick_state(1), only_move), (kick_state(2), one_kick)],
    );
    let mut seen = [0u32; ACTIONS];
    for _ in 0..200 {
        for s in [kick_state(0), kick_state(1)] {
            seen[t.advise(ASKER, &s, &[], None).expect("advised").index()] += 1;
        }
    }
    assert_eq!(seen[Move.index()], 0);
    assert!(
        Action::KICK_TIE_ORDER.iter().all(|a| seen[a.index()] > 50),
        "{seen:?}"
    );
    assert_eq!(t.counters().advice_given, 400);
    // One tried kick action: spread 0, no advice.
    assert_eq!(t.advise(ASKER, &kick_state(2), &[], None), None);
}

#[test]
fn an_authors_torrey_student_intends_its_greedy_action() {
    let torrey = with("torrey", |t: &mut Torrey| {
        t.mistake_correcting = true;
    });
    // epsilon 1: an epsilon-greedy intent would be a random draw; the greedy
    // one is always the best value, Dribble.
    let intents = |config: AgentConfig| {
        let mut a = agent(
            0,
            3,
            AgentConfig {
                epsilon: 1.0,
                ..config
            },
        );
        teach(
            &mut a,
            &[(kick_state(0), known([0.0, 0.0, 0.7, 0.0, 0.0], 1))],
        );
        let mut intents = Vec::new();
        for _ in 0..50 {
            a.begin_episode(Mode::Training);
            let mut silent = script(&[]);
            let played = a.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
            let intended = silent.asked[0].2.expect("an intent");
            assert_eq!(played, intended, "played without advice");
            intents.push(intended);
        }
        intents
    };
    assert_eq!(intents(authors(torrey.clone())), vec![Dribble; 50]);
    assert!(intents(torrey).iter().any(|&a| a != Dribble));
    // The ad hoc advisees keep their epsilon-greedy intent.
    let ad_hoc = with("adhoc-td", |a: &mut AdHoc| {
        a.mistake_correcting = true;
    });
    let intents: Vec<Action> = (0..50)
        .map(|seed| {
            let config = AgentConfig {
                epsilon: 1.0,
                ..authors(ad_hoc.clone())
            };
            let mut a = Agent::new(0, 3, config, seed).unwrap();
            teach(
                &mut a,
                &[(kick_state(0), known([0.0, 0.0, 0.7, 0.0, 0.0], 0))],
            );
            let mut silent = script(&[]);
            a.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
            silent.asked[0].2.expect("an intent")
        })
        .collect();
    assert!(intents.iter().any(|&a| a != Dribble));
}

#[test]
fn an_authors_advisor_breaks_ties_at_random() {
    // Shoot and PassNear tie at 0.5; Torrey's spread 0.5 is above t.
    let q = [0.0, 0.5, 0.0, 0.5, 0.0];
    let answers = |config: AgentConfig| {
        let mut t = agent(1, 3, config);
        teach(&mut t, &[(kick_state(0), known(q, 1))]);
        (0..100)
            .map(|_| t.advise(ASKER, &kick_state(0), &[], None).expect("advised"))
            .collect::<Vec<_>>()
    };
    let torrey = config("torrey");
    assert_eq!(answers(torrey.clone()), vec![Shoot; 100]);
    let random = answers(authors(torrey));
    assert!(random.contains(&Shoot) && random.contains(&PassNear));
    assert!(random.iter().all(|a| [Shoot, PassNear].contains(a)));
}

#[test]
fn an_authors_advisee_breaks_vote_ties_in_their_order() {
    // A fresh advisee asks about an unvisited state for sure (P_ask = 1).
    let vote = |config: &AgentConfig, seed: u64, votes: &[Action]| {
        let mut a = Agent::new(0, 3, config.clone(), seed).unwrap();
        finish_one_episode(&mut a);
        let mut ex = script(votes);
        let played = a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
        assert_eq!(ex.asked.len(), 1);
        played
    };
    let visit = config("adhoc-visit");
    let fixed = authors(visit.clone());
    for seed in 0..10 {
        assert_eq!(vote(&fixed, seed, &[Shoot, PassFar]), PassFar);
        assert_eq!(vote(&fixed, seed, &[PassNear, Shoot]), Shoot);
        assert_eq!(vote(&fixed, seed, &[PassNear, Dribble]), Dribble);
    }
    // The paper's rule: at random, both sides of a tie come up.
    let random = visit;
    let winners: Vec<Action> = (0..40)
        .map(|seed| vote(&random, seed, &[PassNear, Shoot]))
        .collect();
    assert!(winners.contains(&PassNear) && winners.contains(&Shoot));
}

#[test]
fn an_authors_episode_sharing_receiver_bootstraps_on_move() {
    let (s0, s1) = (kick_state(0), kick_state(1));
    let replay = |config: AgentConfig| {
        let mut a = agent(1, 3, config);
        // Q(s1, Dribble) = 1, Q(s1, Move) = 0.
        teach(&mut a, &[(s1, known([0.0, 0.0, 1.0, 0.0, 0.0], 1))]);
        a.receive_shared(&[Transition {
            state: s0,
            action: Shoot,
            reward: 0.0,
            next: Some((s1, Dribble)),
        }]);
        a.entry(&s0).unwrap().q[Shoot.index()]
    };
    let sharing = config("episode-sharing");
    // delta = 0 + 0.9 * Q(s1, next) - 0, times alpha 0.1 and trace 1.
    assert!((replay(sharing.clone()) - 0.09).abs() < 1e-12);
    assert_eq!(replay(authors(sharing)), 0.0);
}

/// A method written outside the core: ask everyone at every step with the
/// ball while `ask_budget` lasts, follow the first advice that arrives,
/// answer every request about a visited state.
#[derive(Debug)]
struct AskAlways {
    ask_budget: u64,
}

impl crate::AdvisingStrategy for AskAlways {
    fn asks(&mut self, at: &crate::AskContext<'_>, _: &mut AgentRng) -> bool {
        at.counters.ask_spent < self.ask_budget
    }

    fn advisors(&self, me: usize, n: usize, _: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
        out.extend((0..n).filter(|&j| j != me));
    }

    fn gives(&mut self, at: &crate::GiveContext<'_>, _: &mut AgentRng) -> bool {
        at.visits > 0
    }

    fn follow(
        &mut self,
        replies: &crate::Replies<'_>,
        _: crate::VoteTies,
        _: &mut AgentRng,
    ) -> Option<Advice> {
        replies.advice.first().copied()
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}

#[test]
fn a_method_defined_outside_the_core_makes_every_decision() {
    let mut a =
        agent(0, 3, config("no-advice")).with_strategy(Box::new(AskAlways { ask_budget: 2 }));
    // It asks even the same state twice and before any finished episode
    // (no ad hoc rule applies), follows the first advice, and stops when
    // its own budget is spent.
    let mut ex = script(&[Dribble, PassFar, PassFar]);
    assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut ex), Dribble);
    assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut ex), Dribble);
    a.act(&obs(kick_state(1)), 0.0, &[], &mut ex);
    assert_eq!(ex.asked.len(), 2);
    assert_eq!(ex.asked[0], (0, vec![1, 2], None));
    assert_eq!(a.counters().ask_spent, 2);
    // As an advisor it answers about a state it visited, with its greedy
    // action, and about nothing else.
    assert!(a.advise(ASKER, &kick_state(0), &[], None).is_some());
    assert_eq!(a.advise(ASKER, &kick_state(4), &[], None), None);
    assert_eq!(a.spent_budget(), 1);
}

#[test]
fn early_advising_asks_at_every_step_until_its_budget_is_spent() {
    let early = with("early-advising", |b: &mut EarlyAdvising| {
        b.ask_budget = 3;
    });
    let mut a = agent(0, 3, early);
    // From the first episode on, the same state again and again.
    let mut ex = script(&[Dribble]);
    for _ in 0..5 {
        a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    }
    assert_eq!(
        ex.asked.len(),
        3,
        "one request per step while the budget lasts"
    );
    assert_eq!(a.counters().ask_spent, 3);
    // Unanswered requests spend nothing: it keeps asking.
    let mut b = agent(0, 3, config("early-advising"));
    let mut silent = script(&[]);
    for _ in 0..5 {
        b.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
    }
    assert_eq!((silent.asked.len(), b.counters().ask_spent), (5, 0));
}

#[test]
fn random_advising_asks_with_its_probability() {
    let random = |p| {
        with("random-advising", |b: &mut RandomAdvising| {
            b.ask_probability = p;
        })
    };
    let asked = |p| {
        let mut a = agent(0, 3, random(p));
        let mut silent = script(&[]);
        for k in 0..2000 {
            a.act(&obs(kick_state(k % 5)), 0.0, &[], &mut silent);
        }
        silent.asked.len()
    };
    assert_eq!(asked(0.0), 0);
    assert_eq!(asked(1.0), 2000);
    let half = asked(0.5);
    // Binomial(2000, 0.5): 1000 +- 4.5 standard deviations.
    assert!((900..=1100).contains(&half), "{half}");
    let e = random(1.5).validate().unwrap_err();
    assert_eq!(e.key, "ask_probability");
}

#[test]
fn budgeted_advisors_answer_about_visited_states_within_their_budget() {
    let mut a = agent(
        1,
        3,
        with("early-advising", |b: &mut EarlyAdvising| {
            b.give_budget = 1;
        }),
    );
    teach(
        &mut a,
        &[(kick_state(0), known([0.0, 0.1, 0.9, 0.2, 0.0], 1))],
    );
    assert_eq!(
        a.advise(ASKER, &kick_state(1), &[], None),
        None,
        "never visited"
    );
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), Some(Dribble));
    assert_eq!(
        a.advise(ASKER, &kick_state(0), &[], None),
        None,
        "budget spent"
    );
}

#[test]
fn backing_off_saves_requests_nobody_answers() {
    let requests = |backoff: bool| {
        let mut a = agent(
            0,
            3,
            with("adhoc-td", |a: &mut AdHoc| {
                a.backoff = backoff;
                a.v_a = 0.0;
            }),
        );
        finish_one_episode(&mut a);
        let mut silent = script(&[]);
        // 31 chances to ask (v_a = 0: P_ask = 1), no answer ever.
        for k in 0..31 {
            a.act(&obs(kick_state(k % 5)), 0.0, &[], &mut silent);
            a.begin_episode(Mode::Training);
        }
        silent.asked.len()
    };
    assert_eq!(requests(false), 31);
    // Asks, lets 1 pass, asks, lets 3 pass, asks, lets 7, asks, lets 15: 4 + 1.
    assert_eq!(requests(true), 5);
}

#[test]
fn backing_off_ends_when_advice_comes() {
    let mut a = agent(
        0,
        3,
        with("adhoc-td", |a: &mut AdHoc| {
            a.backoff = true;
            a.v_a = 0.0;
        }),
    );
    finish_one_episode(&mut a);
    let mut silent = script(&[]);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
    a.begin_episode(Mode::Training);
    a.act(&obs(kick_state(1)), 0.0, &[], &mut silent);
    assert_eq!(silent.asked.len(), 1, "the second chance passes");
    a.begin_episode(Mode::Training);
    let mut answering = script(&[Shoot]);
    a.act(&obs(kick_state(2)), 0.0, &[], &mut answering);
    a.begin_episode(Mode::Training);
    a.act(&obs(kick_state(3)), 0.0, &[], &mut answering);
    assert_eq!(answering.asked.len(), 2, "advice resets the back-off");
}

#[test]
fn reused_advice_saves_requests() {
    let reuse = |rule| {
        with("advice-reuse", |r: &mut AdviceReuse| {
            r.reuse_rule = rule;
            r.reuse_decay = 0.5;
        })
    };
    for rule in [ReuseRule::QChange, ReuseRule::Decay] {
        let mut a = agent(0, 3, reuse(rule));
        finish_one_episode(&mut a);
        let mut ex = script(&[PassFar, PassFar]);
        // Advised once in the state; later visits replay the advice
        // without asking, and without spending the ask budget.
        assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut ex), PassFar);
        a.begin_episode(Mode::Training);
        assert_eq!(a.act(&obs(kick_state(0)), 0.0, &[], &mut ex), PassFar);
        assert_eq!(ex.asked.len(), 1, "{rule:?}: the second visit reuses");
        assert_eq!(a.counters().ask_spent, 1);
    }
    // q-change: once its values stop moving, it forgets and may ask again.
    let mut a = agent(0, 3, reuse(ReuseRule::QChange));
    finish_one_episode(&mut a);
    let mut ex = script(&[PassFar]);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    let mut reused = 0;
    for _ in 0..200 {
        a.begin_episode(Mode::Training);
        if a.act(&obs(kick_state(0)), 0.0, &[], &mut ex) == PassFar && ex.asked.len() == 1 {
            reused += 1;
        }
        a.end_episode(OutOfTime);
    }
    assert!(reused >= 1, "reused at least once");
    assert!(ex.asked.len() > 1, "asked again once its values settled");
    // decay: the reuse probability halves at every reuse, so reuses stop.
    let mut a = agent(0, 3, reuse(ReuseRule::Decay));
    finish_one_episode(&mut a);
    let mut ex = script(&[PassFar]);
    a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    let before = ex.asked.len();
    for _ in 0..200 {
        a.begin_episode(Mode::Training);
        a.act(&obs(kick_state(0)), 0.0, &[], &mut ex);
    }
    assert!(ex.asked.len() > before, "the memory's hold decays");
}

#[test]
fn rcmp_asks_while_its_heads_disagree() {
    let mut rcmp = with("rcmp", |r: &mut Rcmp| {
        r.ask_budget = 10_000;
    });
    // The tabular variant.
    rcmp.learner = crate::LearnerSettings::Ensemble {
        heads: 5,
        mask_probability: 0.5,
    };
    let mut a = agent(0, 3, rcmp);
    // Nobody answers: the agent learns alone, one kick per episode that
    // always scores, and asks while its heads disagree about the state.
    let mut silent = script(&[]);
    let mut asked = Vec::new();
    for _ in 0..300 {
        a.begin_episode(Mode::Training);
        let before = silent.asked.len();
        a.act(&obs(kick_state(0)), 0.0, &[], &mut silent);
        a.end_episode(Goal);
        asked.push(silent.asked.len() > before);
    }
    assert!(asked[0], "nothing learned: infinitely uncertain");
    let early = asked[..20].iter().filter(|&&x| x).count();
    let late = asked[280..].iter().filter(|&&x| x).count();
    assert!(early >= 5 && late == 0, "early {early}, late {late}");
}

#[test]
fn psaf_rows_are_shared_and_the_partaker_takes_the_most_visited() {
    let sharing = |v_g| {
        with("psaf", |p: &mut Psaf| {
            p.shares = PsafShares::Row;
            p.v_g = v_g;
        })
    };
    let q = [0.0, 0.2, 0.9, 0.1, 0.0];
    let mut partaker = agent(0, 3, sharing(0.5));
    // v_g large: P_give = 1 - (1 + v_g)^(-log2 n) is 1 at any n > 1.
    let mut sharer = agent(1, 3, sharing(1e9));
    teach(&mut sharer, &[(kick_state(0), known(q, 40))]);
    let mut novice = agent(2, 3, sharing(1e9));
    teach(&mut novice, &[(kick_state(0), known([0.5; 5], 2))]);
    finish_one_episode(&mut partaker);
    let Decision::Ask { state, .. } = partaker.act_begin(&obs(kick_state(0)), 0.0, &[], &|_| true)
    else {
        panic!("a partaker that never visited the state asks");
    };
    let mut values = Vec::new();
    for (advisor, a) in [(1, &mut sharer), (2, &mut novice)] {
        let Answer::Values(ValuesAnswer::Values(v)) = a.answer(ASKER, &state, &[], Along::Nothing)
        else {
            panic!("a sharer answers with its values");
        };
        values.push(ValuesAdvice { advisor, values: v });
    }
    assert_eq!((values[0].values.q, values[0].values.visits), (q, 40));
    let answers = Answers {
        values,
        ..Answers::default()
    };
    partaker.act_complete(&answers, 2);
    // It took the values of the sharer with the most visits as its own.
    assert_eq!(partaker.entry(&kick_state(0)).unwrap().q, q);
    assert_eq!(partaker.counters().ask_spent, 1);
    assert_eq!(sharer.counters().advice_given, 1);
    // Values from sharers that visited the state less are left alone.
    let mut strategy = Psaf {
        shares: PsafShares::Row,
        ..Psaf::default()
    };
    let replies = Replies {
        values: &answers.values,
        ..Replies::default()
    };
    assert_eq!(strategy.adopt(&replies, 100), None);
}

#[test]
fn psaf_shares_the_best_value_where_more_confident_and_the_partaker_plays_it() {
    let psaf = with("psaf", |_: &mut Psaf| {});
    let q = [0.0, 0.2, 0.9, 0.1, 0.0];
    let mut partaker = agent(0, 3, psaf.clone());
    let mut sharer = agent(1, 3, psaf.clone());
    teach(&mut sharer, &[(kick_state(0), known(q, 40))]);
    let mut novice = agent(2, 3, psaf);
    teach(&mut novice, &[(kick_state(0), known([0.5; 5], 40))]);
    finish_one_episode(&mut partaker);
    let Decision::Ask { state, along, .. } =
        partaker.act_begin(&obs(kick_state(0)), 0.0, &[], &|_| true)
    else {
        panic!("a partaker that never visited the state asks");
    };
    assert_eq!(along, Along::ActionVisits([0; 5]), "its visits go along");
    // The sharer's confidence, 40 visits of Dribble x (1 - 1 / (0.9 + 1)),
    // beats the partaker's 0; the novice's values do not spread.
    let mut answers = Answers::default();
    answers.take(1, sharer.answer(ASKER, &state, &[], along));
    answers.take(2, novice.answer(ASKER, &state, &[], along));
    assert_eq!(answers.best.len(), 1);
    assert_eq!(
        (answers.best[0].action, answers.best[0].value),
        (Dribble, 0.9)
    );
    assert_eq!(answers.declined, 1);
    let played = partaker.act_complete(&answers, 2);
    assert_eq!(played, Dribble, "greedy on the value it took");
    assert_eq!(
        partaker.entry(&kick_state(0)).unwrap().q[Dribble.index()],
        0.9
    );
    assert_eq!(partaker.counters().ask_spent, 1);
    assert_eq!(sharer.counters().advice_given, 1);
    assert_eq!(novice.counters().advice_given, 0);
}

/// A team of three early-advising agents whose give budget is `give`,
/// announcing when it is spent if `announce`, after `episodes` episodes.
fn early_team(give: u64, announce: bool, episodes: usize) -> Team {
    let mut c = with("early-advising", |b: &mut EarlyAdvising| {
        b.give_budget = give;
        b.ask_budget = 100_000;
    });
    c.announce_exhausted = announce;
    let agents = (0..3).map(|i| Agent::new(i, 3, c.clone(), 30 + i as u64).unwrap());
    let mut t = Team::new(agents.collect()).unwrap();
    play(
        &mut t,
        &mut AgentRng::seed_from_u64(6),
        episodes,
        Mode::Training,
    );
    t
}

#[test]
fn every_request_is_counted_once_by_what_became_of_it() {
    let t = early_team(5, false, 200);
    for a in t.agents() {
        let o = a.request_outcomes();
        let c = a.counters();
        assert_eq!(
            o.answered + o.declined + o.futile + o.lost,
            c.advice_requests
        );
        // Advisors answer states they visited while their budget lasts;
        // then every request is futile.
        assert!(o.answered > 0 && o.declined > 0, "{o:?}");
        assert!(o.futile > o.answered, "{o:?}");
        assert_eq!(o.lost, 0, "no network conditions: nothing is lost");
    }
    // Lost replies are lost.
    let mut c = config("early-advising");
    c.network = Some(NetworkConditions {
        latency: "fixed:0".parse().unwrap(),
        loss: 0.5,
        timeout_ms: 5.0,
    });
    let agents = (0..3).map(|i| Agent::new(i, 3, c.clone(), 30 + i as u64).unwrap());
    let mut t = Team::new(agents.collect()).unwrap();
    play(&mut t, &mut AgentRng::seed_from_u64(6), 50, Mode::Training);
    let lost: u64 = t.agents().iter().map(|a| a.request_outcomes().lost).sum();
    assert!(lost > 0);
}

#[test]
fn an_exhausted_advisor_announces_once_and_is_asked_no_more() {
    let (quiet, told) = (early_team(5, false, 200), early_team(5, true, 200));
    let sum = |t: &Team, f: fn(&Agent) -> u64| t.agents().iter().map(f).sum::<u64>();
    // The same answers while budgets last; then the told team stops asking.
    assert_eq!(
        sum(&quiet, |a| a.counters().advice_given),
        sum(&told, |a| a.counters().advice_given)
    );
    assert_eq!(sum(&told, |a| a.request_outcomes().futile), 0);
    assert!(sum(&quiet, |a| a.request_outcomes().futile) > 0);
    let messages = |t: &Team| t.traffic().iter().map(|m| m.messages).sum::<u64>();
    assert!(messages(&told) < messages(&quiet));
    // A newcomer in a slot is asked again.
    let mut told = told;
    let c = told.agents()[1].config().clone();
    told.replace(Agent::new(1, 3, c, 99).unwrap()).unwrap();
    play(
        &mut told,
        &mut AgentRng::seed_from_u64(7),
        30,
        Mode::Training,
    );
    assert!(
        told.agents()[1].counters().advice_given > 0,
        "the newcomer is asked"
    );
}

#[test]
fn a_peer_learner_following_an_announced_advisor_asks_the_others() {
    // Agent 1's budget runs out at once; agent 2's lasts.
    let budget = |give| {
        let mut c = with("peer-learning", |p: &mut PeerLearning| {
            p.give_budget = Some(give);
        });
        c.announce_exhausted = true;
        c
    };
    let gives = [1_000_000, 3, 1_000_000];
    let agents = (0..3).map(|i| Agent::new(i, 3, budget(gives[i]), 40 + i as u64).unwrap());
    let mut t = Team::new(agents.collect()).unwrap();
    let mut rng = AgentRng::seed_from_u64(8);
    let answered = |t: &Team| t.agents()[0].request_outcomes().answered;
    play(&mut t, &mut rng, 100, Mode::Training);
    let before = answered(&t);
    play(&mut t, &mut rng, 100, Mode::Training);
    assert!(answered(&t) > before + 50, "{before} then {}", answered(&t));
}

#[test]
fn the_announcement_is_taken_once_and_again_after_a_restore() {
    let mut c = with("early-advising", |b: &mut EarlyAdvising| b.give_budget = 1);
    c.announce_exhausted = true;
    let mut a = agent(1, 3, c);
    teach(
        &mut a,
        &[(kick_state(0), known([0.0, 0.0, 1.0, 0.0, 0.0], 1))],
    );
    assert!(!a.take_announcement());
    assert_eq!(a.advise(ASKER, &kick_state(0), &[], None), Some(Dribble));
    assert!(a.take_announcement());
    assert!(!a.take_announcement(), "once");
    assert_eq!(
        a.answer(ASKER, &kick_state(0), &[], Along::Nothing),
        Answer::Action(proto::AdviceAnswer::Exhausted)
    );
    a.restore(a.snapshot()).unwrap();
    assert!(a.take_announcement(), "a restored agent tells again");
}

#[test]
fn an_hfo_agent_asks_with_its_features_for_teams_of_up_to_four() {
    let hfo = AgentConfig {
        learner: crate::LearnerSettings::Dqn(crate::DqnSettings {
            observation: ObservationSet::Hfo,
            ..crate::DqnSettings::default()
        }),
        ..config("adhoc-td")
    };
    let mut a = agent(0, 3, hfo.clone());
    finish_one_episode(&mut a);
    let features = Features::new(&[0.25; 27]).unwrap();
    let seen = Observation {
        features,
        ..obs(kick_state(0))
    };
    // Unvisited state: P_ask = 1, and the request carries the features.
    let Decision::Ask { features: sent, .. } = a.act_begin(&seen, 0.0, &[], &|_| true) else {
        panic!("an unvisited state asks");
    };
    assert_eq!(sent, features);
    let e = Agent::new(0, 5, hfo, 1).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid agent config `observation`: `hfo` is given to teams of at most 4 agents, this \
         one has 5"
    );
}

/// What a [`Recorder`] was shown.
#[derive(Debug, Default)]
struct Record {
    /// Each `asks`: the state, HFO's features and the values.
    asked: Vec<(State, Vec<f32>, Option<ActionValues>)>,
    /// Each `gives`: the asker, its state and features.
    given: Vec<(usize, State, Vec<f32>)>,
    /// Each episode's end: its mode, outcome, final reward and return.
    ended: Vec<(Mode, EpisodeOutcome, f64, f64)>,
    /// Each batch received, with its sender.
    received: Vec<(usize, Vec<Transition>)>,
    /// Each report of an advice outcome: the asker, followed, advantage.
    outcomes: Vec<(usize, bool, f64)>,
    /// The advantage of each of its own decisions learned from.
    advantages: Vec<f64>,
}

/// A strategy that records what the seam shows it: it asks `advisors` at
/// every step with the ball, answers every request, and sends `sends` at
/// every training episode's end.
#[derive(Debug, Default)]
struct Recorder {
    record: std::sync::Arc<std::sync::Mutex<Record>>,
    by_values: bool,
    reports: bool,
    advisors: Vec<usize>,
    sends: Sends,
}

impl Recorder {
    /// The strategy and a view of its record.
    fn boxed(
        self,
    ) -> (
        Box<dyn AdvisingStrategy>,
        std::sync::Arc<std::sync::Mutex<Record>>,
    ) {
        let record = self.record.clone();
        (Box::new(self), record)
    }
}

impl AdvisingStrategy for Recorder {
    fn asks_by_values(&self) -> bool {
        self.by_values
    }

    fn asks(&mut self, at: &AskContext<'_>, _: &mut AgentRng) -> bool {
        let seen = (*at.state, at.features.to_vec(), at.values);
        self.record.lock().unwrap().asked.push(seen);
        !self.advisors.is_empty()
    }

    fn advisors(&self, _: usize, _: usize, _: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clone_from(&self.advisors);
    }

    fn gives(&mut self, at: &GiveContext<'_>, _: &mut AgentRng) -> bool {
        let seen = (at.asker, *at.state, at.features.to_vec());
        self.record.lock().unwrap().given.push(seen);
        true
    }

    fn reports_advice_outcomes(&self) -> bool {
        self.reports
    }

    fn learns_from_outcomes(&self) -> bool {
        true
    }

    fn learn_outcome(&mut self, outcome: &Outcome) {
        self.record
            .lock()
            .unwrap()
            .advantages
            .push(outcome.advantage);
    }

    fn advice_outcome(&mut self, asker: usize, followed: bool, advantage: f64) {
        let outcome = (asker, followed, advantage);
        self.record.lock().unwrap().outcomes.push(outcome);
    }

    fn end_episode(&mut self, end: &EndContext<'_>) -> Sends {
        let seen = (
            Mode::Training,
            end.outcome,
            end.final_reward,
            end.episode_return,
        );
        self.record.lock().unwrap().ended.push(seen);
        self.sends.clone()
    }

    fn end_evaluation(&mut self, end: &EndContext<'_>) {
        let seen = (
            Mode::Evaluation,
            end.outcome,
            end.final_reward,
            end.episode_return,
        );
        self.record.lock().unwrap().ended.push(seen);
    }

    fn received(&mut self, from: usize, batch: &Batch) -> Option<Vec<Transition>> {
        self.record
            .lock()
            .unwrap()
            .received
            .push((from, batch.transitions.clone()));
        None
    }

    fn spent_budget(&self, _: &AdviceCounters) -> u64 {
        0
    }
}

#[test]
fn asking_sees_the_observation_and_the_values_only_on_demand() {
    let features = Features::new(&[0.5, -0.25, 0.75]).unwrap();
    let seen = Observation {
        features,
        ..obs(kick_state(1))
    };
    for by_values in [false, true] {
        let mut a = agent(0, 3, config("no-advice"));
        teach(
            &mut a,
            &[(kick_state(1), known([0.0, 0.4, 0.1, 0.3, 0.2], 3))],
        );
        let (strategy, record) = Recorder {
            by_values,
            ..Recorder::default()
        }
        .boxed();
        let mut a = a.with_strategy(strategy);
        a.act(&seen, 0.0, &[], &mut Isolated);
        let record = record.lock().unwrap();
        let (state, sent, values) = &record.asked[0];
        assert_eq!(
            (*state, sent.as_slice()),
            (kick_state(1), features.as_slice())
        );
        let learned = by_values.then_some(ActionValues {
            q: [0.0, 0.4, 0.1, 0.3, 0.2],
            learned: 0b11110,
        });
        assert_eq!(*values, learned, "by values: {by_values}");
    }
}

#[test]
fn giving_sees_the_asker_and_its_observation() {
    let (strategy, record) = Recorder::default().boxed();
    let mut advisor = agent(1, 3, config("no-advice")).with_strategy(strategy);
    finish_one_episode(&mut advisor);
    let features = [0.5f32, 0.125];
    let answer = advisor.answer(2, &kick_state(3), &features, Along::Nothing);
    assert!(matches!(answer, Answer::Action(AdviceAnswer::Advice(_))));
    let record = record.lock().unwrap();
    assert_eq!(record.given, vec![(2, kick_state(3), features.to_vec())]);
}

#[test]
fn an_episode_s_end_tells_its_return_and_outcome_in_both_modes() {
    let (strategy, record) = Recorder::default().boxed();
    let mut a = agent(0, 3, config("no-advice")).with_strategy(strategy);
    for mode in [Mode::Training, Mode::Evaluation] {
        a.begin_episode(mode);
        // The first frame's reward is ignored; the others and the final
        // reward add up: 0.5 - 0.25 + 1.
        for (k, reward) in [7.0, 0.5, -0.25].into_iter().enumerate() {
            a.act(&obs(move_state(k)), reward, &[], &mut Isolated);
        }
        a.end_episode(Goal);
    }
    a.begin_episode(Mode::Training);
    a.end_episode(OutOfBounds);
    let record = record.lock().unwrap();
    assert_eq!(
        record.ended,
        vec![
            (Mode::Training, Goal, 1.0, 1.25),
            (Mode::Evaluation, Goal, 1.0, 1.25),
            (Mode::Training, OutOfBounds, -1.0, -1.0),
        ]
    );
}

/// Agent `id` of a team of 2 learning with a small DQN.
fn dqn_agent(id: usize) -> Agent {
    let dqn = AgentConfig {
        learner: crate::LearnerSettings::Dqn(crate::DqnSettings {
            hidden: vec![8],
            ..crate::DqnSettings::default()
        }),
        ..config("no-advice")
    };
    agent(id, 2, dqn)
}

/// `n` kick transitions, each ending its episode.
fn kicks(n: usize) -> Vec<Transition> {
    (0..n)
        .map(|k| Transition {
            state: kick_state(k % 5),
            action: Shoot,
            reward: 1.0,
            next: None,
        })
        .collect()
}

#[test]
fn a_batch_sent_arrives_counted_and_its_receiver_learns_it_at_once() {
    let batch = kicks(3);
    let (strategy, _) = Recorder {
        sends: vec![(1, Share::Batch(batch.clone().into()))],
        ..Recorder::default()
    }
    .boxed();
    let (receiver, record) = Recorder::default().boxed();
    let agents = vec![
        dqn_agent(0).with_strategy(strategy),
        dqn_agent(1).with_strategy(receiver),
    ];
    let mut team = Team::new(agents).unwrap();
    team.begin_episode(Mode::Training);
    team.act(&[obs(move_state(0)), obs(move_state(1))], 0.0)
        .unwrap();
    let before = team.agents()[1].snapshot();
    team.end_episode(OutOfTime);
    let (sender, receiver) = (&team.agents()[0], &team.agents()[1]);
    assert_eq!(sender.counters().shared_sent, 3);
    assert_eq!(receiver.counters().shared_received, 3);
    assert_eq!(record.lock().unwrap().received, vec![(0, batch.clone())]);
    // One message, as the zenoh transport sends it.
    let body = Body::ExperienceBatch(proto::ExperienceBatch {
        from: 0,
        to: 1,
        transitions: batch.clone(),
        notes: Vec::new(),
        standing: None,
    });
    let header = Header::new(proto::experiment_id("in-process"), 0, 0, 1);
    let bytes = proto::encode(&Envelope { header, body }).len() as u64;
    assert_eq!(team.traffic()[0].messages, 1);
    assert_eq!(team.traffic()[0].bytes, bytes);
    // The receiver's network moved (its learner's own state changed).
    assert_ne!(receiver.snapshot().learner_state, before.learner_state);
    // A learner that cannot learn a batch says so.
    let mut sarsa = agent(1, 2, config("no-advice"));
    sarsa.begin_episode(Mode::Training);
    assert!(!sarsa.receive_batch(0, &batch.into()));
}

#[test]
fn a_strategy_s_batches_are_bounded_and_one_per_receiver() {
    let (strategy, _) = Recorder {
        sends: vec![
            (1, Share::Batch(kicks(MAX_BATCH + 10).into())),
            (2, Share::Episode(kicks(2))),
            (1, Share::Batch(kicks(1).into())),
        ],
        ..Recorder::default()
    }
    .boxed();
    let mut a = agent(0, 3, config("no-advice")).with_strategy(strategy);
    a.begin_episode(Mode::Training);
    a.end_episode(Goal);
    let sent = a.take_shared();
    assert_eq!(sent.len(), 2);
    assert_eq!(sent[0], (1, Share::Batch(kicks(MAX_BATCH).into())));
    assert_eq!(sent[1], (2, Share::Episode(kicks(2))));
    assert_eq!(a.counters().shared_sent, MAX_BATCH as u64 + 2);
}

#[test]
fn advisors_hear_how_their_advice_turned_out_when_the_advisee_reports() {
    for reports in [false, true] {
        let (advisee, own) = Recorder {
            reports,
            advisors: vec![1],
            ..Recorder::default()
        }
        .boxed();
        let (advisor, record) = Recorder::default().boxed();
        let agents = vec![
            agent(0, 2, config("no-advice")).with_strategy(advisee),
            agent(1, 2, config("no-advice")).with_strategy(advisor),
        ];
        let mut team = Team::new(agents).unwrap();
        team.begin_episode(Mode::Training);
        // Agent 0 kicks twice, asking agent 1 each time; agent 1 moves.
        for k in 0..2 {
            team.act(&[obs(kick_state(k)), obs(move_state(k))], 0.0)
                .unwrap();
        }
        team.end_episode(Goal);
        let outcomes = &record.lock().unwrap().outcomes;
        let messages = team.traffic()[0].messages;
        if !reports {
            assert!(outcomes.is_empty());
            assert_eq!(messages, 2, "two requests");
            continue;
        }
        // Both decisions played the advice (the majority of one), with the
        // advantages the advisee learned from.
        let advantages: Vec<f64> = outcomes.iter().map(|&(.., a)| a).collect();
        assert_eq!(advantages, own.lock().unwrap().advantages);
        assert_eq!(outcomes.len(), 2);
        assert!(
            outcomes
                .iter()
                .all(|&(asker, followed, _)| asker == 0 && followed)
        );
        assert_eq!(messages, 2 + 2, "two requests and two reports");
    }
}

/// A DQN that notes the decisions each batch it learns closes (a batch's
/// kicks: every decision begins with one).
#[derive(Debug)]
struct CountingDqn {
    dqn: crate::Dqn,
    batches: std::sync::Arc<std::sync::Mutex<Vec<usize>>>,
}

impl crate::Learner for CountingDqn {
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        self.dqn.values(at)
    }
    fn choose(&mut self, at: Seen<'_>, rng: &mut AgentRng) -> Action {
        self.dqn.choose(at, rng)
    }
    fn learn(&mut self, transition: Experience<'_>) {
        self.dqn.learn(transition);
    }
    fn end_episode(&mut self) {
        self.dqn.end_episode();
    }
    fn replay(&mut self, episode: &[Experience<'_>]) {
        self.dqn.replay(episode);
    }
    fn learn_batch(&mut self, batch: &[Experience<'_>]) -> bool {
        let kicks = batch.iter().filter(|(s, ..)| s.action.is_kick()).count();
        self.batches.lock().unwrap().push(kicks);
        self.dqn.learn_batch(batch)
    }
    fn table(&self) -> Option<Vec<ActionValues>> {
        self.dqn.table()
    }
    fn restore(&mut self, values: Vec<ActionValues>) -> Result<(), String> {
        self.dqn.restore(values)
    }
    fn save_state(&self) -> Option<Vec<u8>> {
        self.dqn.save_state()
    }
    fn load_state(&mut self, state: &[u8]) -> Result<(), String> {
        self.dqn.load_state(state)
    }
}

/// A team of three ef-ontl agents (transfers every 5 episodes, 8 tuples
/// learned of up to 64 kept) on small DQNs that note their batches.
fn transferring(seed: u64) -> (Team, Vec<std::sync::Arc<std::sync::Mutex<Vec<usize>>>>) {
    let mut c = with("ef-ontl", |s: &mut crate::EfOntl| {
        s.interval = 5;
        s.buffer = 64;
        s.transfer_batch = 8;
    });
    let LearnerSettings::Dqn(dqn) = &mut c.learner else {
        panic!("ef-ontl learns with the DQN by default: {:?}", c.learner);
    };
    dqn.hidden = vec![16];
    dqn.warmup = 32;
    let dqn = dqn.clone();
    let mut noted = Vec::new();
    let agents = (0..3).map(|i| {
        let batches = std::sync::Arc::default();
        noted.push(std::sync::Arc::clone(&batches));
        let seed = seed + i as u64;
        let learner = CountingDqn {
            dqn: crate::Dqn::new(&dqn, c.gamma, 6, seed),
            batches,
        };
        Agent::with_learner(i, 3, c.clone(), seed, Box::new(learner)).unwrap()
    });
    let team = Team::new(agents.collect()).unwrap();
    (team, noted)
}

#[test]
fn ef_ontl_transfers_and_each_receiver_learns_transfer_batch_tuples() {
    let run = |seed| {
        let (mut t, noted) = transferring(seed);
        let log = play(&mut t, &mut AgentRng::seed_from_u64(3), 30, Mode::Training);
        let counters: Vec<AdviceCounters> = t.agents().iter().map(|a| *a.counters()).collect();
        let learned: Vec<Vec<usize>> = noted.iter().map(|n| n.lock().unwrap().clone()).collect();
        let states: Vec<_> = (t.agents().iter())
            .map(|a| a.snapshot().learner_state)
            .collect();
        let traffic: Vec<_> = t.traffic().iter().map(|m| (m.messages, m.bytes)).collect();
        (log, counters, learned, states, traffic)
    };
    let (log, counters, learned, states, traffic) = run(5);
    // Transfers at the ends of episodes 6, 11, 16, 21 and 26 (after the
    // standings of 5, 10, ...): one teacher each, two receivers.
    let batches: Vec<usize> = learned.iter().flatten().copied().collect();
    assert_eq!(batches, vec![8; 10], "{learned:?}");
    assert!(learned.iter().filter(|l| !l.is_empty()).count() >= 2);
    let received: u64 = counters.iter().map(|c| c.shared_received).sum();
    let sent: u64 = counters.iter().map(|c| c.shared_sent).sum();
    assert!(received > 0 && received == sent, "{counters:?}");
    // Each receiver got the teacher's whole buffer (at most 64), of which
    // it learned 8.
    assert!((80..=640).contains(&received), "{counters:?}");
    for c in &counters {
        assert_eq!(c.advice_requests + c.advice_given + c.ask_spent, 0);
    }
    // Standings at the ends of episodes 5, 10, ..., 30 (6 messages each),
    // candidates at 5 transfers (2 each).
    let messages: u64 = traffic.iter().map(|m| m.0).sum();
    assert_eq!(messages, 6 * 6 + 5 * 2);
    // One seed, one run; another seed, another.
    assert_eq!(run(5), (log, counters, learned, states.clone(), traffic));
    assert_ne!(run(6).3, states);
}
