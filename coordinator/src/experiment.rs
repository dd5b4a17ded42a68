//! A validated experiment, its saved agents loaded once: everything a run
//! needs to build its team.

use std::sync::Arc;

use agent::{AdviceCounters, Agent, PersistError, Snapshot};
use serde::Serialize;

use crate::config::{AgentSpec, ExperimentConfig};
use crate::error::Error;
use crate::seeds::{SeedFor, derive};

/// An experiment ready to run: the configuration checked, every snapshot
/// read, verified and shown to fit its agent.
#[derive(Clone, Debug)]
pub struct Experiment {
    config: ExperimentConfig,
    snapshots: Vec<Option<Arc<Snapshot>>>,
    /// The snapshot each membership event's newcomer starts from, if any.
    newcomer_snapshots: Vec<Option<Arc<Snapshot>>>,
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

/// Reads agent `id`'s snapshot, if `spec` loads one, its counters cleared
/// unless `keep_counters`.
fn load_snapshot(id: usize, spec: &AgentSpec) -> Result<Option<Arc<Snapshot>>, Error> {
    let Some(path) = &spec.load else {
        return Ok(None);
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
    Ok(Some(Arc::new(snapshot)))
}

/// Agent `id` of a team of `n` from `spec`, seeded `seed`, restored from
/// `snapshot` if given.
fn build_agent(
    id: usize,
    n: usize,
    spec: &AgentSpec,
    seed: u64,
    snapshot: Option<&Snapshot>,
) -> Result<Agent, Error> {
    let mut agent = Agent::new(id, n, spec.config.clone(), seed)
        .map_err(|e| crate::error::ConfigError::new(format!("team[{id}].{}", e.key), e.reason))?;
    let failed = |source| Error::Snapshot {
        agent: id,
        path: spec.load.clone().unwrap_or_default(),
        source,
    };
    match (snapshot, &spec.learner) {
        // A learner process restores its own state in its agent's process:
        // here the snapshot only has to hold one.
        (Some(s), Some(_)) if s.learner_state.is_none() => Err(failed(PersistError::Invalid(
            "it holds no learner's own state, which a learner process needs (its `save`)".into(),
        ))),
        (Some(s), None) => agent.restore(s.clone()).map_err(failed),
        _ => Ok(()),
    }?;
    Ok(agent)
}

impl Experiment {
    /// Validates `config` and loads every agent's and newcomer's snapshot.
    /// Writes nothing.
    pub fn prepare(config: ExperimentConfig) -> Result<Self, Error> {
        config.validate()?;
        let snapshots = (config.team.iter().enumerate())
            .map(|(id, spec)| load_snapshot(id, spec))
            .collect::<Result<_, _>>()?;
        let newcomer_snapshots = (config.events.iter())
            .map(|e| load_snapshot(e.slot, &e.newcomer(&config.team[e.slot])))
            .collect::<Result<_, _>>()?;
        let experiment = Self {
            config,
            snapshots,
            newcomer_snapshots,
        };
        // Builds one team and every newcomer to find agents that cannot be
        // built or restored.
        experiment.agents(&experiment.seeds(0))?;
        for k in 0..experiment.config.events.len() {
            experiment.newcomer(0, k)?;
        }
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

    /// The newcomer of membership event `event` in run `run`: its settings,
    /// its seed and the snapshot it starts from, if any.
    pub fn newcomer_of(&self, run: u64, event: usize) -> (AgentSpec, u64, Option<&Snapshot>) {
        let e = &self.config.events[event];
        (
            e.newcomer(&self.config.team[e.slot]),
            derive(self.config.seed, run, SeedFor::Newcomer(event)),
            self.newcomer_snapshots[event].as_deref(),
        )
    }

    /// The newcomer of membership event `event` in run `run`, built and
    /// restored from its snapshot if it has one.
    pub fn newcomer(&self, run: u64, event: usize) -> Result<Agent, Error> {
        let (spec, seed, snapshot) = self.newcomer_of(run, event);
        let slot = self.config.events[event].slot;
        build_agent(slot, self.config.team.len(), &spec, seed, snapshot)
    }

    /// The seed of the simulator of evaluation point `point` of run `run`.
    pub fn evaluation_seed(&self, run: u64, point: u64) -> u64 {
        derive(self.config.seed, run, SeedFor::Evaluation(point))
    }

    /// The agents of a run at its start, each restored from its snapshot if
    /// it has one.
    pub fn agents(&self, seeds: &RunSeeds) -> Result<Vec<Agent>, Error> {
        let n = self.config.team.len();
        (self.config.team.iter().zip(&self.snapshots).enumerate())
            .map(|(id, (spec, snapshot))| {
                build_agent(id, n, spec, seeds.agents[id], snapshot.as_deref())
            })
            .collect()
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
