//! A validated experiment, its saved agents loaded once: everything a run
//! needs to build its team.

use std::sync::Arc;

use agent::{AdviceCounters, Agent, Snapshot};
use serde::Serialize;

use crate::config::ExperimentConfig;
use crate::error::Error;
use crate::seeds::{SeedFor, derive};

/// An experiment ready to run: the configuration checked, every snapshot
/// read, verified and shown to fit its agent.
#[derive(Clone, Debug)]
pub struct Experiment {
    config: ExperimentConfig,
    snapshots: Vec<Option<Arc<Snapshot>>>,
}

/// The seeds of one run (see [`crate::seeds`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunSeeds {
    /// The training simulator's seed.
    pub simulator: u64,
    /// One seed per agent, by id.
    pub agents: Vec<u64>,
}

/// What `config.json` holds: the configuration and the digest of every
/// loaded snapshot, so that a changed file counts as another configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Record<'a> {
    /// Version of the output formats.
    pub format: u32,
    /// The configuration.
    pub config: &'a ExperimentConfig,
    /// Per agent, the digest of the snapshot it starts from (hex), or null.
    pub snapshot_digests: Vec<Option<String>>,
}

/// Version of the results' formats: `config.json`, the run CSVs, the run
/// JSONs and `summary.json`. 2: the run JSONs name each agent's counters
/// as the run CSV's columns do (`give_spent`, `ask_spent`,
/// `advice_requests`, `advice_replies_received`, `messages_dropped`).
/// 3: the advising traffic (`advising_messages`, `advising_bytes`) in the
/// runs, and per training episode in the summary's points; agents' network
/// conditions (`network`) in the configuration.
pub const RESULTS_FORMAT_VERSION: u32 = 3;

impl Experiment {
    /// Validates `config` and loads every agent's snapshot. Writes nothing.
    pub fn prepare(config: ExperimentConfig) -> Result<Self, Error> {
        config.validate()?;
        let mut snapshots = Vec::with_capacity(config.team.len());
        for (id, spec) in config.team.iter().enumerate() {
            let Some(path) = &spec.load else {
                snapshots.push(None);
                continue;
            };
            let bytes = std::fs::read(path).map_err(|e| Error::io("read", path, e))?;
            let mut snapshot = Snapshot::decode(&bytes).map_err(|source| Error::Snapshot {
                agent: id,
                path: path.clone(),
                source,
            })?;
            if !spec.keep_counters {
                snapshot.counters = AdviceCounters::default();
            }
            snapshots.push(Some(Arc::new(snapshot)));
        }
        let experiment = Self { config, snapshots };
        // Builds one team to find agents that cannot be built or restored.
        experiment.agents(&experiment.seeds(0))?;
        Ok(experiment)
    }

    /// The configuration.
    pub fn config(&self) -> &ExperimentConfig {
        &self.config
    }

    /// The snapshot agent `agent` starts every run from, if any, as
    /// prepared (its counters cleared unless `keep_counters`).
    pub fn snapshot(&self, agent: usize) -> Option<&Snapshot> {
        self.snapshots.get(agent)?.as_deref()
    }

    /// The seeds of run `run`.
    pub fn seeds(&self, run: u64) -> RunSeeds {
        let seed = self.config.seed;
        RunSeeds {
            simulator: derive(seed, run, SeedFor::Simulator),
            agents: (0..self.config.team.len())
                .map(|i| derive(seed, run, SeedFor::Agent(i)))
                .collect(),
        }
    }

    /// The seed of the simulator of evaluation point `point` of run `run`.
    pub fn evaluation_seed(&self, run: u64, point: u64) -> u64 {
        derive(self.config.seed, run, SeedFor::Evaluation(point))
    }

    /// The agents of a run at its start, each restored from its snapshot if
    /// it has one.
    pub fn agents(&self, seeds: &RunSeeds) -> Result<Vec<Agent>, Error> {
        let n = self.config.team.len();
        let mut agents = Vec::with_capacity(n);
        for (id, (spec, snapshot)) in self.config.team.iter().zip(&self.snapshots).enumerate() {
            let mut a = Agent::new(id, n, spec.config.clone(), seeds.agents[id]).map_err(|e| {
                crate::error::ConfigError::new(format!("team[{id}].{}", e.key), e.reason)
            })?;
            if let Some(s) = snapshot {
                a.restore(Snapshot::clone(s))
                    .map_err(|source| Error::Snapshot {
                        agent: id,
                        path: spec.load.clone().unwrap_or_default(),
                        source,
                    })?;
            }
            agents.push(a);
        }
        Ok(agents)
    }

    /// What `config.json` holds.
    pub fn record(&self) -> Record<'_> {
        Record {
            format: RESULTS_FORMAT_VERSION,
            config: &self.config,
            snapshot_digests: self
                .snapshots
                .iter()
                .map(|s| s.as_ref().map(|s| format!("{:016x}", s.digest())))
                .collect(),
        }
    }
}
