//! SARSA(lambda) with accumulating eligibility traces over the tile-coded
//! state (docs/algorithms.md 1): the paper's learner, one implementation of
//! [`Learner`].

use proto::Action;

use crate::config::AgentConfig;
use crate::learner::{ActionValues, Experience, Learner, Seen, Step};
use crate::selection::{AgentRng, epsilon_greedy};

/// One traced pair and its eligibility.
#[derive(Clone, Copy, Debug)]
struct EligibilityTrace {
    index: usize,
    action: Action,
    e: f64,
}

/// The SARSA(lambda) update rule with its own trace.
///
/// The trace is a small reused `Vec`, pruned below the threshold, so an
/// update allocates nothing once the `Vec` has grown.
#[derive(Clone, Debug)]
struct Sarsa {
    alpha: f64,
    gamma: f64,
    decay: f64,
    threshold: f64,
    trace: Vec<EligibilityTrace>,
}

impl Sarsa {
    /// A learner with the configuration's alpha, gamma, lambda and trace threshold.
    fn new(config: &AgentConfig) -> Self {
        Self {
            alpha: config.alpha,
            gamma: config.gamma,
            decay: config.gamma * config.lambda,
            threshold: config.trace_threshold,
            trace: Vec::with_capacity(64),
        }
    }

    /// One step for the transition `(s, a) -> r -> (s', a')` over `table`
    /// (one entry per state index); `next = None` marks a terminal step,
    /// whose target is `r` alone.
    ///
    /// `delta = r + gamma Q(s', a') - Q(s, a)`, `e(s, a) += 1`, then for every
    /// traced pair `Q += alpha delta e` and `e *= gamma lambda`.
    fn update(
        &mut self,
        table: &mut [ActionValues],
        from: (usize, Action),
        reward: f64,
        next: Option<(usize, Action)>,
    ) {
        let (index, action) = from;
        let bootstrap = next.map_or(0.0, |(i, a)| self.gamma * table[i].q[a.index()]);
        let delta = reward + bootstrap - table[index].q[action.index()];
        match self
            .trace
            .iter_mut()
            .find(|t| t.index == index && t.action == action)
        {
            Some(t) => t.e += 1.0,
            None => {
                self.trace.push(EligibilityTrace {
                    index,
                    action,
                    e: 1.0,
                });
                table[index].learned |= 1 << action.index();
            }
        }
        let step = self.alpha * delta;
        for t in &mut self.trace {
            table[t.index].q[t.action.index()] += step * t.e;
            t.e *= self.decay;
        }
        let threshold = self.threshold;
        self.trace.retain(|t| t.e >= threshold);
    }

    /// Forgets the trace (episode end).
    fn clear(&mut self) {
        self.trace.clear();
    }

    #[cfg(test)]
    fn trace_len(&self) -> usize {
        self.trace.len()
    }
}

/// The paper's learner: a Q-table over the framework's state index,
/// epsilon-greedy choices, SARSA(lambda) on its own steps and, with a
/// separate trace, on the goal episodes teammates share.
#[derive(Clone, Debug)]
pub struct TabularSarsa {
    table: Vec<ActionValues>,
    epsilon: f64,
    own: Sarsa,
    replay: Sarsa,
}

impl TabularSarsa {
    /// The learner of `config` (alpha, gamma, lambda, epsilon, trace threshold).
    pub fn new(config: &AgentConfig) -> Self {
        Self {
            table: Vec::new(),
            epsilon: config.epsilon,
            own: Sarsa::new(config),
            replay: Sarsa::new(config),
        }
    }

    /// The table's index of a step, grown to hold it.
    fn slot(&mut self, step: Step<'_>) -> (usize, Action) {
        let index = step.at.index.expect("learning needs indexed states");
        if index >= self.table.len() {
            self.table.resize(index + 1, ActionValues::default());
        }
        (index, step.action)
    }
}

impl Learner for TabularSarsa {
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        (at.index)
            .and_then(|i| self.table.get(i))
            .copied()
            .unwrap_or_default()
    }

    fn choose(&mut self, at: Seen<'_>, rng: &mut AgentRng) -> Action {
        epsilon_greedy(&self.values(at).q, self.epsilon, rng)
    }

    fn learn(&mut self, (from, reward, next): Experience<'_>) {
        let from = self.slot(from);
        let next = next.map(|n| self.slot(n));
        self.own.update(&mut self.table, from, reward, next);
    }

    fn end_episode(&mut self) {
        self.own.clear();
    }

    fn replay(&mut self, episode: &[Experience<'_>]) {
        self.replay.clear();
        for &(from, reward, next) in episode {
            let from = self.slot(from);
            let next = next.map(|n| self.slot(n));
            self.replay.update(&mut self.table, from, reward, next);
        }
        self.replay.clear();
    }

    fn table(&self) -> Option<Vec<ActionValues>> {
        Some(self.table.clone())
    }

    fn absorb(&mut self, at: Seen<'_>, values: ActionValues) -> bool {
        let Some(index) = at.index else {
            return false;
        };
        if index >= self.table.len() {
            self.table.resize(index + 1, ActionValues::default());
        }
        self.table[index] = values;
        true
    }

    fn restore(&mut self, values: Vec<ActionValues>) -> Result<(), String> {
        self.table = values;
        self.own.clear();
        self.replay.clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Action::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn three_steps_ending_terminal() {
        // alpha 0.1, gamma 0.9, lambda 0.9: traces decay by 0.81 per step.
        let mut table = vec![ActionValues::default(); 3];
        let (s0, s1, s2) = (0, 1, 2);
        table[s0].q[Shoot.index()] = 0.5;
        table[s1].q[Move.index()] = 0.2;
        table[s2].q[Dribble.index()] = -0.4;
        let mut sarsa = Sarsa::new(&AgentConfig::default());
        let q = |t: &[ActionValues], i: usize, a: Action| t[i].q[a.index()];

        // Step 1: delta = 0 + 0.9 * 0.2 - 0.5 = -0.32; e(s0,S) = 1;
        // Q(s0,S) = 0.5 + 0.1 * -0.32 = 0.468; then e(s0,S) = 0.81.
        sarsa.update(&mut table, (s0, Shoot), 0.0, Some((s1, Move)));
        assert!(close(q(&table, s0, Shoot), 0.468));

        // Step 2: delta = 0 + 0.9 * -0.4 - 0.2 = -0.56; e(s1,M) = 1;
        // Q(s0,S) = 0.468 + 0.1 * -0.56 * 0.81 = 0.468 - 0.04536 = 0.42264;
        // Q(s1,M) = 0.2 + 0.1 * -0.56 = 0.144; then e = 0.6561 and 0.81.
        sarsa.update(&mut table, (s1, Move), 0.0, Some((s2, Dribble)));
        assert!(close(q(&table, s0, Shoot), 0.42264));
        assert!(close(q(&table, s1, Move), 0.144));

        // Step 3, terminal, r = -1: delta = -1 - (-0.4) = -0.6 (no bootstrap);
        // Q(s0,S) = 0.42264 + 0.1 * -0.6 * 0.6561 = 0.42264 - 0.039366 = 0.383274;
        // Q(s1,M) = 0.144 + 0.1 * -0.6 * 0.81 = 0.144 - 0.0486 = 0.0954;
        // Q(s2,D) = -0.4 + 0.1 * -0.6 = -0.46.
        sarsa.update(&mut table, (s2, Dribble), -1.0, None);
        assert!(close(q(&table, s0, Shoot), 0.383274));
        assert!(close(q(&table, s1, Move), 0.0954));
        assert!(close(q(&table, s2, Dribble), -0.46));
        assert_eq!(sarsa.trace_len(), 3);
        sarsa.clear();
        assert_eq!(sarsa.trace_len(), 0);

        // Only updated pairs count as tried.
        assert!(table[s0].is_learned(Shoot) && !table[s0].is_learned(Dribble));
    }

    #[test]
    fn traces_accumulate_and_are_pruned() {
        let mut table = vec![ActionValues::default(); 2];
        let s = 0;
        let mut sarsa = Sarsa::new(&AgentConfig::default());
        // Self-loop with r = 1, Q = 0: delta = 1, e = 1, Q = 0.1, e -> 0.81.
        sarsa.update(&mut table, (s, Dribble), 1.0, Some((s, Dribble)));
        // delta = 1 + 0.9 * 0.1 - 0.1 = 0.99; e = 0.81 + 1 = 1.81;
        // Q = 0.1 + 0.1 * 0.99 * 1.81 = 0.1 + 0.17919 = 0.27919.
        sarsa.update(&mut table, (s, Dribble), 1.0, Some((s, Dribble)));
        assert!(close(table[s].q[Dribble.index()], 0.27919));
        assert_eq!(sarsa.trace_len(), 1);
        // After k updates of another pair, e = 1.81 * 0.81^(k + 1):
        // 1.12e-4 at k = 45 (kept), 9.05e-5 at k = 46 (dropped).
        let other = 1;
        for _ in 0..45 {
            sarsa.update(&mut table, (other, Shoot), 0.0, Some((other, Shoot)));
        }
        assert_eq!(sarsa.trace_len(), 2);
        sarsa.update(&mut table, (other, Shoot), 0.0, Some((other, Shoot)));
        assert_eq!(sarsa.trace_len(), 1);
    }
}
