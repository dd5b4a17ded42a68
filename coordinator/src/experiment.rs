//! A validated experiment, its saved agents loaded once: everything a run
//! needs to build its team.

use std::sync::Arc;

use agent::{AdviceCounters, Agent, PersistError, Snapshot};
use serde::Serialize;

use crate::config::{AgentSpec, ExperimentConfig};
use crate::error::{ConfigError, Error};
use crate::plugin::{Plugin, PluginStart};
use crate::seeds::{SeedFor, derive};

/// One agent's objects given in process, if any (see [`crate::plugin`]).
pub type Plugins = Vec<Option<Arc<dyn Plugin>>>;

/// An experiment ready to run: the configuration checked, every snapshot
/// read, verified and shown to fit its agent.
#[derive(Clone, Debug)]
pub struct Experiment {
    config: ExperimentConfig,
    snapshots: Vec<Option<Arc<Snapshot>>>,
    /// The snapshot each membership event's newcomer starts from, if any.
    newcomer_snapshots: Vec<Option<Arc<Snapshot>>>,
    /// Per slot, the objects its agents (and newcomers) are made with.
    plugins: Plugins,
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
/// conditions (`network`) in the configuration. 4: what played each run
/// (`played_with`), and the keys 3 gained without rising (the runs'
/// `advice_matrix`, `joins`, `restarts`, `simulator_restarts`, the
/// summary's `advice_matrix`, the configuration's `events`). 5: what
/// became of the requests (`answered_requests`, `declined_requests`,
/// `futile_requests`, `lost_requests`) in the runs, and the agents'
/// `announce_exhausted`.
pub const RESULTS_FORMAT_VERSION: u32 = 5;

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

/// The agent `start` describes, from `spec`, made with `plugin`'s objects
/// if it has one, restored from `snapshot` if given.
fn build_agent(
    start: PluginStart,
    spec: &AgentSpec,
    plugin: Option<&dyn Plugin>,
    snapshot: Option<&Snapshot>,
) -> Result<Agent, Error> {
    let PluginStart {
        agent: id,
        team_size: n,
        seed,
        ..
    } = start;
    let bad = |key: String, reason: String| ConfigError::new(format!("team[{id}].{key}"), reason);
    let made = |what: &'static str| move |e: String| bad(format!("plugin.{what}"), e);
    let learner = match plugin {
        Some(p) => p.learner(start).map_err(made("learner"))?,
        None => None,
    };
    let agent = match learner {
        Some(learner) => Agent::with_learner(id, n, spec.config.clone(), seed, learner),
        None => Agent::new(id, n, spec.config.clone(), seed),
    };
    let mut agent = agent.map_err(|e| bad(e.key.to_owned(), e.reason))?;
    let strategy = match plugin {
        Some(p) => p.strategy(start).map_err(made("strategy"))?,
        None => None,
    };
    if let Some(strategy) = strategy {
        agent = agent.with_strategy(strategy);
    }
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
        let plugins = vec![None; config.team.len()];
        Self::prepare_with(config, plugins)
    }

    /// [`prepare`](Self::prepare) with objects for some agents, by slot
    /// (see [`crate::plugin`]), which the configuration then records.
    pub fn prepare_with(mut config: ExperimentConfig, plugins: Plugins) -> Result<Self, Error> {
        if plugins.len() != config.team.len() {
            let reason = format!(
                "{} agents, objects for {}",
                config.team.len(),
                plugins.len()
            );
            return Err(ConfigError::new("team", reason).into());
        }
        let from_file = |key: String| {
            let reason = "names an object, which only Python's `run()` can give (docs/python.md)";
            Error::from(ConfigError::new(key, reason))
        };
        for (id, (spec, plugin)) in config.team.iter_mut().zip(&plugins).enumerate() {
            match plugin {
                Some(plugin) => spec.plugin = Some(plugin.spec()),
                None if spec.plugin.is_some() => {
                    return Err(from_file(format!("team[{id}].plugin")));
                }
                None => {}
            }
        }
        for (k, event) in config.events.iter().enumerate() {
            if event.newcomer.as_ref().is_some_and(|n| n.plugin.is_some()) {
                return Err(from_file(format!("events[{k}].newcomer.plugin")));
            }
        }
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
            plugins,
        };
        // Builds one team and every newcomer to find agents that cannot be
        // built or restored.
        experiment.agents(0)?;
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
        let start = self.start(slot, run, seed);
        let plugin = spec.plugin.as_ref().and(self.plugins[slot].as_deref());
        build_agent(start, &spec, plugin, snapshot)
    }

    /// The seed of the simulator of evaluation point `point` of run `run`.
    pub fn evaluation_seed(&self, run: u64, point: u64) -> u64 {
        derive(self.config.seed, run, SeedFor::Evaluation(point))
    }

    /// The agents of run `run` at its start, each restored from its
    /// snapshot if it has one.
    pub fn agents(&self, run: u64) -> Result<Vec<Agent>, Error> {
        let seeds = self.seeds(run);
        (self.config.team.iter().zip(&self.snapshots).enumerate())
            .map(|(id, (spec, snapshot))| {
                let start = self.start(id, run, seeds.agents[id]);
                build_agent(
                    start,
                    spec,
                    self.plugins[id].as_deref(),
                    snapshot.as_deref(),
                )
            })
            .collect()
    }

    /// Who slot `id`'s objects are made for in run `run`.
    fn start(&self, id: usize, run: u64, seed: u64) -> PluginStart {
        PluginStart {
            agent: id,
            team_size: self.config.team.len(),
            run,
            seed,
        }
    }

    /// The objects given in process, of every slot that has them.
    pub fn plugins(&self) -> impl Iterator<Item = &Arc<dyn Plugin>> {
        self.plugins.iter().flatten()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plugin::PluginSpec;

    #[test]
    fn a_file_cannot_name_an_object() {
        let mut config = ExperimentConfig::default();
        config.team[1].plugin = Some(PluginSpec {
            learner: Some("mine".into()),
            strategy: None,
        });
        let Err(Error::Config(e)) = Experiment::prepare(config) else {
            panic!("a recorded object without the object was accepted")
        };
        assert_eq!(e.key, "team[1].plugin");
    }
}
