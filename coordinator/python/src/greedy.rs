//! A learner of ours frozen from its snapshot file, for playing a trained
//! team anywhere the paper's 6-feature state can be computed (our
//! simulator, or the real HFO through its features).

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard, PoisonError};

use agent::{Agent, AgentConfig, Decision, Features, Mode, Observation, Snapshot};
use proto::{Action, STATE_FEATURES};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

/// A frozen agent: `GreedyAgent(path)` loads a snapshot file (`coordinator
/// run --save-agents`) and `act(state, can_kick)` plays as our evaluations
/// do: Move without the ball, else the greedy action of its table (ties in
/// the order Shoot, Dribble, PassFar, PassNear; Shoot in a state it never
/// saw).
#[pyclass(module = "adhoc_advising._adhoc_advising")]
pub(crate) struct GreedyAgent {
    /// Behind a lock only so Python threads may share it.
    agent: Mutex<Agent>,
}

#[pymethods]
impl GreedyAgent {
    /// The agent saved in the snapshot file at `path`.
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        let bytes = std::fs::read(&path)
            .map_err(|e| PyOSError::new_err(format!("cannot read {}: {e}", path.display())))?;
        let invalid = |e: &dyn std::fmt::Display| {
            PyValueError::new_err(format!("{} is not a usable snapshot: {e}", path.display()))
        };
        let snapshot = Snapshot::decode(&bytes).map_err(|e| invalid(&e))?;
        let config = AgentConfig {
            tiles_per_feature: snapshot.tiling.tiles_per_feature,
            tile_width: snapshot.tiling.tile_width,
            tile_step: snapshot.tiling.tile_step,
            ..AgentConfig::default()
        };
        let mut agent = Agent::new(0, 1, config, 0).map_err(|e| invalid(&e))?;
        agent.restore(snapshot).map_err(|e| invalid(&e))?;
        agent.begin_episode(Mode::Evaluation);
        Ok(GreedyAgent {
            agent: Mutex::new(agent),
        })
    }

    /// The index (`adhoc_advising.PAPER_ACTIONS`) of its action in `state`, the
    /// paper's 6 features, when it can kick (`can_kick`) or not.
    fn act(&mut self, state: Vec<f64>, can_kick: bool) -> PyResult<usize> {
        let state: [f64; STATE_FEATURES] = state.try_into().map_err(|s: Vec<f64>| {
            PyValueError::new_err(format!(
                "a state has {STATE_FEATURES} features, got {}",
                s.len()
            ))
        })?;
        if let Some(bad) = state.iter().find(|x| !x.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "the state's features must be finite numbers, got {bad}"
            )));
        }
        let obs = Observation {
            state,
            features: Features::NONE,
            can_kick,
            position: [0.0, 0.0],
        };
        match self.agent().act_begin(&obs, 0.0, &[], &|_| false) {
            Decision::Act(action) => Ok(action.index()),
            Decision::Ask { .. } => unreachable!("a frozen agent never asks"),
        }
    }

    /// The digest of its learned state (as in `run-<k>.json`'s reports).
    #[getter]
    fn digest(&self) -> u64 {
        self.agent().digest()
    }
}

impl GreedyAgent {
    /// The agent; a panic elsewhere cannot leave a frozen table half-written.
    fn agent(&self) -> MutexGuard<'_, Agent> {
        self.agent.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// The paper's actions by index, as [`GreedyAgent::act`] returns them.
pub(crate) fn paper_action_names() -> Vec<&'static str> {
    Action::ALL.iter().map(|a| a.name()).collect()
}
