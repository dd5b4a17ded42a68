//! The simulators of one run of an experiment: one for training, and one
//! for each evaluation block, which starts with the training simulator's
//! agent memories or none (`EnvConfig::evaluation_memory`).

use proto::Mode;

use crate::sim::config::{EnvConfig, EnvConfigError, EvaluationMemory};
use crate::sim::env::Env;

/// A run's training simulator and its current evaluation simulator.
#[derive(Clone, Debug)]
pub struct RunEnvs {
    training: Env,
    evaluation: Option<Env>,
}

impl RunEnvs {
    /// The simulators of a run with settings `config`, the training one
    /// drawing from `seed`.
    pub fn new(config: EnvConfig, seed: u64) -> Result<Self, EnvConfigError> {
        Ok(Self {
            training: Env::new(config, seed)?,
            evaluation: None,
        })
    }

    /// Number of offense agents.
    pub fn offense(&self) -> usize {
        self.training.offense()
    }

    /// Starts an evaluation block on a new simulator drawing from `seed`;
    /// with carried memories its agents remember what the training
    /// simulator's remember.
    pub fn begin_evaluation(&mut self, seed: u64) {
        let config = self.training.config().clone();
        let carried = config.evaluation_memory == EvaluationMemory::Carried;
        let mut env = Env::new(config, seed).expect("the training simulator's settings are valid");
        if carried {
            env.remember_as(&self.training);
        }
        self.evaluation = Some(env);
    }

    /// The simulator of an episode in `mode`: the training one (which, with
    /// carried memories, takes back what the agents remembered at the end
    /// of the last evaluation block), or the current evaluation block's,
    /// if one began.
    pub fn env(&mut self, mode: Mode) -> Option<&mut Env> {
        match mode {
            Mode::Training => {
                if let Some(evaluation) = self.evaluation.take()
                    && evaluation.config().evaluation_memory == EvaluationMemory::Carried
                {
                    self.training.remember_as(&evaluation);
                }
                Some(&mut self.training)
            }
            Mode::Evaluation => self.evaluation.as_mut(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action;

    /// Plays episodes of always-SHOOT on `env` until some agent remembers a course.
    fn until_a_course_is_remembered(env: &mut Env) {
        for _ in 0..200 {
            env.reset();
            while !env.step(&vec![Action::Shoot; env.offense()]).is_terminal() {}
            if env.memories().iter().any(|m| m.last_shot.is_some()) {
                return;
            }
        }
        panic!("no course in 200 episodes");
    }

    #[test]
    fn carried_memories_go_to_the_evaluation_block_and_come_back() {
        let mut sims = RunEnvs::new(EnvConfig::default(), 3).unwrap();
        until_a_course_is_remembered(sims.env(Mode::Training).unwrap());
        let trained = sims.env(Mode::Training).unwrap().memories().to_vec();
        assert!(sims.env(Mode::Evaluation).is_none(), "no block began");
        sims.begin_evaluation(11);
        let evaluation = sims.env(Mode::Evaluation).unwrap();
        assert_eq!(evaluation.memories(), &trained[..]);
        evaluation.reset();
        evaluation.step(&[Action::Move; 3]);
        let after = evaluation.memories().to_vec();
        assert_ne!(after, trained, "the view moved on");
        assert_eq!(sims.env(Mode::Training).unwrap().memories(), &after[..]);
        assert!(sims.env(Mode::Evaluation).is_none(), "the block ended");
    }

    #[test]
    fn fresh_evaluation_blocks_remember_nothing() {
        let config = EnvConfig {
            evaluation_memory: EvaluationMemory::Fresh,
            ..EnvConfig::default()
        };
        let mut sims = RunEnvs::new(config, 3).unwrap();
        until_a_course_is_remembered(sims.env(Mode::Training).unwrap());
        let trained = sims.env(Mode::Training).unwrap().memories().to_vec();
        sims.begin_evaluation(11);
        let fresh = Env::new(EnvConfig::default(), 11).unwrap();
        assert_eq!(
            sims.env(Mode::Evaluation).unwrap().memories(),
            fresh.memories()
        );
        assert_eq!(sims.env(Mode::Training).unwrap().memories(), &trained[..]);
    }
}
