//! An ensemble of SARSA(lambda) heads over the same tiles, for RCMP's
//! epistemic uncertainty (da Silva et al., AAAI 2020; docs/algorithms.md
//! section 7): each head learns a transition with probability `p` (its
//! bootstrap mask), the agent acts on the heads' mean, and the variance of
//! the heads' values measures how much the agent does not know yet.

use proto::Action;
use rand::{Rng, SeedableRng};

use crate::config::AgentConfig;
use crate::learner::{ActionValues, Experience, Learner, Seen};
use crate::sarsa::TabularSarsa;
use crate::selection::{AgentRng, epsilon_greedy};

/// K SARSA(lambda) learners and the generator of their masks.
#[derive(Clone, Debug)]
pub struct EnsembleSarsa {
    heads: Vec<TabularSarsa>,
    mask_probability: f64,
    epsilon: f64,
    masks: AgentRng,
}

impl EnsembleSarsa {
    /// `heads` learners of `config` (1 to 64), each learning a transition with
    /// probability `mask_probability`, the masks drawn from `seed`.
    pub fn new(config: &AgentConfig, heads: usize, mask_probability: f64, seed: u64) -> Self {
        Self {
            heads: (0..heads.max(1))
                .map(|_| TabularSarsa::new(config))
                .collect(),
            mask_probability,
            epsilon: config.epsilon,
            masks: AgentRng::seed_from_u64(seed),
        }
    }

    /// Each head's values in `at`.
    fn each(&mut self, at: Seen<'_>) -> Vec<ActionValues> {
        self.heads.iter_mut().map(|h| h.values(at)).collect()
    }

    /// Which heads learn the next transition, one bit each (at least one: a
    /// transition no head learns would be lost).
    fn mask(&mut self) -> u64 {
        let p = self.mask_probability;
        let n = self.heads.len();
        let mut mask = (0..n).fold(0u64, |m, k| {
            let learns = p >= 1.0 || self.masks.random::<f64>() < p;
            m | u64::from(learns) << k
        });
        if mask == 0 {
            mask = 1 << self.masks.random_range(0..n);
        }
        mask
    }
}

impl Learner for EnsembleSarsa {
    /// The heads' mean; an action is learned once any head learned it.
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        let k = self.heads.len() as f64;
        self.each(at)
            .into_iter()
            .fold(ActionValues::default(), |mut sum, v| {
                for (s, q) in sum.q.iter_mut().zip(v.q) {
                    *s += q / k;
                }
                sum.learned |= v.learned;
                sum
            })
    }

    fn choose(&mut self, at: Seen<'_>, rng: &mut AgentRng) -> Action {
        epsilon_greedy(&self.values(at).q, self.epsilon, rng)
    }

    fn learn(&mut self, transition: Experience<'_>) {
        let mask = self.mask();
        for (k, head) in self.heads.iter_mut().enumerate() {
            if mask & (1 << k) != 0 {
                head.learn(transition);
            }
        }
    }

    fn end_episode(&mut self) {
        self.heads.iter_mut().for_each(Learner::end_episode);
    }

    fn replay(&mut self, episode: &[Experience<'_>]) {
        let mask = self.mask();
        for (k, head) in self.heads.iter_mut().enumerate() {
            if mask & (1 << k) != 0 {
                head.replay(episode);
            }
        }
    }

    /// The heads' mean in every state: a snapshot holds one table.
    fn table(&self) -> Option<Vec<ActionValues>> {
        let tables: Vec<Vec<ActionValues>> = self.heads.iter().filter_map(|h| h.table()).collect();
        let len = tables.iter().map(Vec::len).max().unwrap_or(0);
        let k = self.heads.len() as f64;
        let mean = (0..len)
            .map(|i| {
                let mut sum = ActionValues::default();
                for v in tables.iter().filter_map(|t| t.get(i)) {
                    for (s, q) in sum.q.iter_mut().zip(v.q) {
                        *s += q / k;
                    }
                    sum.learned |= v.learned;
                }
                sum
            })
            .collect();
        Some(mean)
    }

    /// Every head takes the values (they then agree there).
    fn absorb(&mut self, at: Seen<'_>, values: ActionValues) -> bool {
        self.heads.iter_mut().all(|h| h.absorb(at, values))
    }

    /// Every head starts from the snapshot's table (they agree on it).
    fn restore(&mut self, values: Vec<ActionValues>) -> Result<(), String> {
        for head in &mut self.heads {
            head.restore(values.clone())?;
        }
        Ok(())
    }

    /// The variance of the heads' values of the action it would play (the
    /// kick action of the largest mean among those any head learned);
    /// infinite where no head learned a kick action.
    fn uncertainty(&mut self, at: Seen<'_>) -> Option<f64> {
        let heads = self.each(at);
        let k = heads.len() as f64;
        let learned = heads.iter().fold(0u8, |m, v| m | v.learned);
        let mean = |i: usize| heads.iter().map(|v| v.q[i]).sum::<f64>() / k;
        let best = (Action::KICK_TIE_ORDER.iter())
            .map(|a| a.index())
            .filter(|&i| learned & (1 << i) != 0)
            .max_by(|&i, &j| mean(i).total_cmp(&mean(j)));
        let Some(i) = best else {
            return Some(f64::INFINITY);
        };
        let m = mean(i);
        Some(heads.iter().map(|v| (v.q[i] - m).powi(2)).sum::<f64>() / k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::learner::Step;
    use Action::*;

    fn at(index: usize) -> Seen<'static> {
        const STATE: [f64; 6] = [0.0; 6];
        Seen {
            state: &STATE,
            features: &[],
            index: Some(index),
        }
    }

    fn step(index: usize, action: Action) -> Step<'static> {
        Step {
            at: at(index),
            action,
        }
    }

    #[test]
    fn uncertainty_falls_as_the_heads_agree() {
        let mut e = EnsembleSarsa::new(&AgentConfig::default(), 5, 0.5, 3);
        assert_eq!(e.uncertainty(at(0)), Some(f64::INFINITY), "nothing learned");
        // A state whose Shoot always pays 1: each head learns it on about half
        // of the visits, so early the heads disagree, later they agree.
        let mut seen = Vec::new();
        for visit in 0..400 {
            e.learn((step(0, Shoot), 1.0, None));
            e.end_episode();
            if [2, 400 - 1].contains(&visit) {
                seen.push(e.uncertainty(at(0)).unwrap());
            }
        }
        assert!(seen[0] > 1e-3, "{seen:?}");
        assert!(seen[1] < 1e-9, "{seen:?}");
        let mean = e.values(at(0)).q[Shoot.index()];
        assert!((mean - 1.0).abs() < 1e-6, "{mean}");
    }

    #[test]
    fn a_snapshot_holds_the_mean_and_restores_agreeing_heads() {
        let mut e = EnsembleSarsa::new(&AgentConfig::default(), 4, 0.5, 9);
        for _ in 0..5 {
            e.learn((step(0, Dribble), 1.0, None));
            e.end_episode();
        }
        let mean = e.values(at(0));
        let table = e.table().unwrap();
        assert_eq!(table[0].q, mean.q);
        let mut f = EnsembleSarsa::new(&AgentConfig::default(), 4, 0.5, 1);
        f.restore(table).unwrap();
        assert_eq!(f.values(at(0)).q, mean.q);
        assert_eq!(f.uncertainty(at(0)), Some(0.0));
    }
}
