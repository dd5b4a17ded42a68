//! The simulator's scripted policies for Python, drawing from the same
//! random stream as `env-server rollout`.

use crate::actions::encode;
use crate::checked_env::CheckedEnv;
use env_server::tools::scripted::policy_rng;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A scripted policy (random, shoot, dribble, pass, uniform) with its own
/// random stream: `ScriptedPolicy(name, seed)` in Python chooses as `env-server
/// rollout --policy name --seed seed` does, one agent after the other.
#[pyclass(module = "halffield._halffield")]
pub(crate) struct ScriptedPolicy {
    policy: env_server::ScriptedPolicy,
    rng: Xoshiro256PlusPlus,
}

#[pymethods]
impl ScriptedPolicy {
    /// The policy `name` drawing from `seed`.
    #[new]
    fn new(name: &str, seed: u64) -> PyResult<Self> {
        let policy = name
            .parse()
            .map_err(|e: env_server::tools::scripted::UnknownPolicy| {
                PyValueError::new_err(e.to_string())
            })?;
        Ok(ScriptedPolicy {
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

impl ScriptedPolicy {
    /// Every agent's action index in `game` as it stands, drawn in agent order.
    pub(crate) fn actions(&mut self, game: &CheckedEnv) -> PyResult<Vec<usize>> {
        let env = game.env();
        (0..env.offense())
            .map(|agent| {
                let action = self.policy.choose(env.can_kick(agent), &mut self.rng);
                encode(env, game.observation(), agent, action).ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "scripted policy {:?} passed, which a lone attacker cannot do: \
                         use offense >= 2 or the policy shoot or dribble",
                        self.policy.name()
                    ))
                })
            })
            .collect()
    }
}
