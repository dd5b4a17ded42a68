//! What an environment is made of: the simulator's settings, the
//! observation set and what a kick action of an agent without the ball
//! does, checked once when Python makes a `Settings` ([`TaskSettings`]).

use crate::observation::{ObservationSet, UnknownName, state_size};
use env_server::EnvConfig;
use numpy::{PyArray1, ndarray::Array1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// What a kick action (SHOOT, DRIBBLE, PASS) of an agent that cannot kick does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MaskedAction {
    /// What HFO does: the action runs and issues no body command.
    Hfo,
    /// The agent MOVEs instead, as the paper's agents do without the ball.
    Move,
    /// The step is refused with an error.
    Raise,
}

impl MaskedAction {
    /// The rule named `name`.
    pub(crate) fn parse(name: &str) -> Result<Self, UnknownName> {
        match name {
            "hfo" => Ok(MaskedAction::Hfo),
            "move" => Ok(MaskedAction::Move),
            "raise" => Ok(MaskedAction::Raise),
            _ => Err(UnknownName {
                what: "masked_action",
                got: name.to_owned(),
                choices: "hfo, move, raise",
            }),
        }
    }

    /// The rule's name.
    fn name(self) -> &'static str {
        match self {
            MaskedAction::Hfo => "hfo",
            MaskedAction::Move => "move",
            MaskedAction::Raise => "raise",
        }
    }
}

/// Everything an environment is made of, validated: shared by every
/// simulator made from it.
#[pyclass(frozen, module = "halffield._halffield")]
#[derive(Clone, Debug)]
pub(crate) struct TaskSettings {
    /// The simulator's settings.
    pub(crate) config: EnvConfig,
    /// The observation set.
    pub(crate) observation: ObservationSet,
    /// What a masked action does.
    pub(crate) masked: MaskedAction,
}

#[pymethods]
impl TaskSettings {
    /// Checks every setting, naming the first bad one.
    #[new]
    #[pyo3(signature = (
        *,
        offense = 3,
        observation = "hfo",
        masked_action = "hfo",
        frames_per_trial = 200,
        untouched_time = 100,
        pass_to_named_receiver = false,
    ))]
    fn new(
        offense: usize,
        observation: &str,
        masked_action: &str,
        frames_per_trial: u32,
        untouched_time: u32,
        pass_to_named_receiver: bool,
    ) -> PyResult<Self> {
        let config = EnvConfig {
            offense,
            frames_per_trial,
            untouched_time,
            pass_to_named_receiver,
            ..EnvConfig::default()
        };
        config
            .validate()
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let invalid = |e: UnknownName| PyValueError::new_err(e.to_string());
        Ok(TaskSettings {
            config,
            observation: ObservationSet::parse(observation).map_err(invalid)?,
            masked: MaskedAction::parse(masked_action).map_err(invalid)?,
        })
    }

    /// Offense agents.
    #[getter]
    fn offense(&self) -> usize {
        self.config.offense
    }

    /// The observation set's name.
    #[getter]
    fn observation(&self) -> &'static str {
        self.observation.name()
    }

    /// What a masked action does: "hfo", "move" or "raise".
    #[getter]
    fn masked_action(&self) -> &'static str {
        self.masked.name()
    }

    /// Cycles after which an episode ends out of time.
    #[getter]
    fn frames_per_trial(&self) -> u32 {
        self.config.frames_per_trial
    }

    /// Cycles without a touch after which an episode ends out of time.
    #[getter]
    fn untouched_time(&self) -> u32 {
        self.config.untouched_time
    }

    /// Whether PASS goes to the named teammate instead of HFO's best pass.
    #[getter]
    fn pass_to_named_receiver(&self) -> bool {
        self.config.pass_to_named_receiver
    }

    /// The agents' names, in agent order.
    #[getter]
    fn agents(&self) -> Vec<String> {
        (0..self.config.offense).map(agent_name).collect()
    }

    /// Features of one agent's observation.
    #[getter]
    pub(crate) fn observation_size(&self) -> usize {
        self.observation.size(self.config.offense)
    }

    /// Discrete actions of one agent: MOVE, SHOOT, DRIBBLE, then PASS to
    /// each teammate.
    #[getter]
    pub(crate) fn action_count(&self) -> usize {
        3 + self.config.offense - 1
    }

    /// Length of the global state.
    #[getter]
    fn state_size(&self) -> usize {
        state_size(self.config.offense)
    }

    /// Lowest and highest value of every observation feature: [-1, 1], but
    /// [1, 11] for the raw uniform numbers.
    fn observation_bounds<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f32>>, Bound<'py, PyArray1<f32>>) {
        let n = self.observation_size();
        let (mut low, mut high) = (Array1::from_elem(n, -1.0f32), Array1::from_elem(n, 1.0f32));
        for i in self.observation.unum_indices(self.config.offense) {
            (low[i], high[i]) = (1.0, 11.0);
        }
        (
            PyArray1::from_owned_array(py, low),
            PyArray1::from_owned_array(py, high),
        )
    }
}

/// The name of agent `agent`, as PettingZoo users know them.
pub(crate) fn agent_name(agent: usize) -> String {
    format!("offense_{agent}")
}
