//! The simulator's baseline policies for Python, drawing from the same
//! random stream as `env-server rollout`.

use crate::actions::encode;
use crate::game::Game;
use env_server::tools::policy::policy_rng;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A baseline policy (random, shoot, dribble, pass, uniform) with its own
/// random stream: `BaselinePolicy(name, seed)` in Python chooses as `env-server
/// rollout --policy name --seed seed` does, one agent after the other.
#[pyclass(name = "BaselinePolicy", module = "halffield._halffield")]
pub(crate) struct SeededPolicy {
    policy: env_server::BaselinePolicy,
    rng: Xoshiro256PlusPlus,
}

#[pymethods]
impl SeededPolicy {
    /// The policy `name` drawing from `seed`.
    #[new]
    fn new(name: &str, seed: u64) -> PyResult<Self> {
        let policy = name
            .parse()
            .map_err(|e: env_server::tools::policy::UnknownPolicy| {
                PyValueError::new_err(e.to_string())
            })?;
        Ok(SeededPolicy {
            policy,
            rng: policy_rng(seed),
        })
    }

    /// The policy's name.
    #[getter]
    fn name(&self) -> &'static str {
        self.policy.name()
    }
}

impl SeededPolicy {
    /// Every agent's action index in `game` as it stands, drawn in agent order.
    pub(crate) fn actions(&mut self, game: &Game) -> PyResult<Vec<usize>> {
        let env = game.env();
        (0..env.offense())
            .map(|agent| {
                let action = self.policy.choose(env.can_kick(agent), &mut self.rng);
                encode(env, game.observation(), agent, action).ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "baseline policy {:?} passed, which a lone attacker cannot do: \
                         use offense >= 2 or the policy shoot or dribble",
                        self.policy.name()
                    ))
                })
            })
            .collect()
    }
}
