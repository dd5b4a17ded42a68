//! What one `coordinator run` asks for, whoever asks: the command line and
//! Python's `run()` build the same [`ExperimentConfig`] from the same
//! arguments, so they write the same files.

use agent::{Algorithm, Latency, LearnerSettings, NetworkConditions, Profile};
use env_server::EvaluationMemory;

use crate::config::{AgentSpec, ExperimentConfig, TeamSpec};
use crate::error::ConfigError;
use crate::transport::Transport;

/// Who plays.
#[derive(Clone, Debug, PartialEq)]
pub enum Agents {
    /// Every agent runs `algorithm` with `profile`'s constants and fidelity.
    Algorithm {
        /// The algorithm.
        algorithm: Algorithm,
        /// Mistake Correcting (adhoc-visit, adhoc-td and torrey only).
        mistake_correcting: bool,
    },
    /// A team file's agents and events.
    Team(TeamSpec),
}

/// One experiment as `coordinator run`'s arguments describe it.
#[derive(Clone, Debug, PartialEq)]
pub struct RunRequest {
    /// Who plays.
    pub agents: Agents,
    /// Independent runs R.
    pub runs: u64,
    /// Training episodes N per run.
    pub episodes: u64,
    /// An evaluation every K training episodes.
    pub eval_every: u64,
    /// Episodes M of one evaluation.
    pub eval_episodes: u64,
    /// The experiment seed.
    pub seed: u64,
    /// The fidelity profile of [`Agents::Algorithm`], and the default level
    /// of the intervals.
    pub profile: Profile,
    /// The intervals' level (default: the profile's).
    pub ci_level: Option<f64>,
    /// Offense agents (default: 3, or the team's size).
    pub offense: Option<usize>,
    /// What an evaluation's simulator remembers at its start.
    pub evaluation_memory: EvaluationMemory,
    /// Where agents and simulator live.
    pub transport: Transport,
    /// Every agent's advice messages' latency; with `advice_loss`, sets the
    /// network conditions.
    pub advice_latency: Option<Latency>,
    /// The probability that an advice message is lost.
    pub advice_loss: Option<f64>,
    /// With network conditions, how long an agent waits for advice (ms).
    pub advice_timeout_ms: Option<u64>,
    /// The learner of every agent of [`Agents::Algorithm`] by name, with its
    /// defaults for the algorithm (default: the one the algorithm needs); a
    /// team file names each agent's.
    pub learner: Option<String>,
}

impl RunRequest {
    /// `agents` under the command line's defaults: the paper's protocol (50
    /// runs of 5000 episodes, 100 evaluation episodes every 20), seed 1, in
    /// process.
    pub fn new(agents: Agents) -> Self {
        Self {
            agents,
            runs: 50,
            episodes: 5000,
            eval_every: 20,
            eval_episodes: 100,
            seed: 1,
            profile: Profile::Paper,
            ci_level: None,
            offense: None,
            evaluation_memory: EvaluationMemory::default(),
            transport: Transport::InProcess,
            advice_latency: None,
            advice_loss: None,
            advice_timeout_ms: None,
            learner: None,
        }
    }

    /// What plays, as the command line prints it: `adhoc-td`,
    /// `adhoc-td (mistake correcting)`, `adhoc-td (learner dqn)` or `team`.
    pub fn label(&self) -> String {
        match &self.agents {
            Agents::Algorithm {
                algorithm,
                mistake_correcting,
            } => {
                let mut label = algorithm.name().to_string();
                if *mistake_correcting {
                    label.push_str(" (mistake correcting)");
                }
                if let Some(learner) = &self.learner {
                    label.push_str(&format!(" (learner {learner})"));
                }
                label
            }
            Agents::Team(_) => "team".into(),
        }
    }

    /// The experiment's configuration (validated later, by
    /// [`crate::Experiment::prepare`]).
    pub fn config(self) -> Result<ExperimentConfig, ConfigError> {
        let TeamSpec {
            agents: mut team,
            events,
        } = match self.agents {
            Agents::Team(_) if self.learner.is_some() => {
                return Err(ConfigError::new(
                    "learner",
                    "names the learner of a team of one algorithm; a team file names each \
                     agent's (`learner = \"dqn\"` in its table)",
                ));
            }
            Agents::Team(team) => team,
            Agents::Algorithm {
                algorithm,
                mistake_correcting,
            } => {
                let mut spec = AgentSpec::of(algorithm, self.profile);
                if let Some(name) = &self.learner {
                    spec.config.learner =
                        LearnerSettings::named_for(name, algorithm.learner_need())
                            .map_err(|e| ConfigError::new(e.key, e.reason))?;
                }
                if mistake_correcting {
                    (spec.config.algorithm)
                        .set("mistake_correcting", true)
                        .map_err(|e| ConfigError::new(e.key, e.reason))?;
                }
                TeamSpec {
                    agents: vec![spec; self.offense.unwrap_or(3)],
                    events: Vec::new(),
                }
            }
        };
        if self.advice_latency.is_some() || self.advice_loss.is_some() {
            let base = NetworkConditions::default();
            let conditions = NetworkConditions {
                latency: self.advice_latency.unwrap_or(base.latency),
                loss: self.advice_loss.unwrap_or(base.loss),
                timeout_ms: self
                    .advice_timeout_ms
                    .map_or(base.timeout_ms, |ms| ms as f64),
            };
            for spec in &mut team {
                spec.config.network = Some(conditions);
            }
        }
        let mut config = ExperimentConfig {
            runs: self.runs,
            episodes: self.episodes,
            eval_every: self.eval_every,
            eval_episodes: self.eval_episodes,
            seed: self.seed,
            ci_level: self.ci_level.unwrap_or(self.profile.ci_level()),
            transport: self.transport,
            team,
            events,
            ..ExperimentConfig::default()
        };
        config.env.offense = self.offense.unwrap_or(config.team.len());
        config.env.evaluation_memory = self.evaluation_memory;
        Ok(config)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use agent::{DqnSettings, LearnerNeed};

    fn of(algorithm: &str, learner: Option<&str>) -> RunRequest {
        RunRequest {
            learner: learner.map(String::from),
            ..RunRequest::new(Agents::Algorithm {
                algorithm: algorithm.parse().unwrap(),
                mistake_correcting: false,
            })
        }
    }

    #[test]
    fn the_learner_named_reaches_every_agent_with_the_algorithms_defaults() {
        let request = of("adhoc-td", Some("dqn"));
        assert_eq!(request.label(), "adhoc-td (learner dqn)");
        let team = request.config().unwrap().team;
        assert_eq!(team.len(), 3);
        for spec in &team {
            assert_eq!(
                spec.config.learner,
                LearnerSettings::Dqn(DqnSettings::default())
            );
        }
        // rcmp asks by uncertainty: its DQN has heads.
        let rcmp = of("rcmp", Some("dqn")).config().unwrap().team;
        assert!(rcmp[0].config.learner.meets(LearnerNeed::Uncertainty));
        rcmp[0].config.validate().unwrap();
        // Without one, the algorithm's own.
        let sarsa = of("adhoc-td", None).config().unwrap().team;
        assert_eq!(sarsa[0].config.learner, LearnerSettings::Sarsa);
    }

    #[test]
    fn an_unknown_learner_or_one_for_a_team_is_refused() {
        let e = of("adhoc-td", Some("deep")).config().unwrap_err();
        assert_eq!(e.key, "learner");
        assert!(
            e.reason.contains("expected one of: sarsa, ensemble, dqn"),
            "{e}"
        );
        let team = RunRequest {
            learner: Some("dqn".into()),
            ..RunRequest::new(Agents::Team(TeamSpec::default()))
        };
        let e = team.config().unwrap_err();
        assert_eq!(e.key, "learner");
        assert!(e.reason.contains("a team file names each agent's"), "{e}");
    }
}
