//! One environment for the Python environments (PettingZoo's and
//! Gymnasium's): reset, step, the global state, scripted actions and
//! pictures.

use crate::arrays::array;
use crate::checked_env::CheckedEnv;
use crate::errors::{not_started, step_error, value_error};
use crate::observation::global_state;
use crate::scripted::ScriptedPolicy;
use crate::settings::TaskSettings;
use crate::status;
use env_server::tools::render::frame_svg;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// Every agent's observation (agents x features) and action mask (agents x actions).
type AgentViews<'py> = (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<i8>>);

/// What a step returns: the views, the team's reward, HFO's status and the frame.
type SingleStep<'py> = (
    Bound<'py, PyArray2<f32>>,
    Bound<'py, PyArray2<i8>>,
    f64,
    &'static str,
    u32,
);

/// One simulated HFO task: `Env(settings)`, then `reset(seed)`.
#[pyclass(module = "halffield._halffield")]
pub(crate) struct Env {
    settings: TaskSettings,
    game: Option<CheckedEnv>,
}

#[pymethods]
impl Env {
    /// A simulator of `settings`; its first `reset` needs a seed.
    #[new]
    fn new(settings: PyRef<'_, TaskSettings>) -> Self {
        Env {
            settings: settings.clone(),
            game: None,
        }
    }

    /// Starts an episode: with `seed`, of a new simulator drawing from it;
    /// without, the next episode of the same random stream.
    #[pyo3(signature = (seed = None))]
    fn reset<'py>(&mut self, py: Python<'py>, seed: Option<u64>) -> PyResult<AgentViews<'py>> {
        if let Some(seed) = seed {
            self.game = Some(CheckedEnv::new(&self.settings, seed).map_err(value_error)?);
        }
        let game = self
            .game
            .as_mut()
            .ok_or_else(|| PyRuntimeError::new_err("the first reset() needs a seed"))?;
        game.reset();
        views(py, game)
    }

    /// Plays one step with one action index per agent, in agent order.
    fn step<'py>(&mut self, py: Python<'py>, actions: Vec<i64>) -> PyResult<SingleStep<'py>> {
        let game = self.game.as_mut().ok_or_else(not_started)?;
        let decoded = game.decode(&actions).map_err(step_error)?;
        let outcome = py.detach(|| game.step(&decoded));
        let (obs, masks) = views(py, game)?;
        Ok((
            obs,
            masks,
            outcome.reward(),
            status::name(outcome),
            game.env().frame(),
        ))
    }

    /// The global state (see `TaskSettings.state_size`).
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f32>>> {
        let game = self.game.as_ref().ok_or_else(not_started)?;
        Ok(PyArray1::from_vec(py, global_state(game.env())))
    }

    /// Every agent's action under `policy` as the simulator stands.
    fn scripted_actions(&self, mut policy: PyRefMut<'_, ScriptedPolicy>) -> PyResult<Vec<usize>> {
        let game = self.game.as_ref().ok_or_else(not_started)?;
        policy.actions(game)
    }

    /// A picture of the field as it stands, as an SVG document.
    fn render_svg(&self) -> PyResult<String> {
        let game = self.game.as_ref().ok_or_else(not_started)?;
        Ok(frame_svg(game.env()))
    }

    /// The same picture as an RGB image (height x width x 3).
    fn render_rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let game = self.game.as_ref().ok_or_else(not_started)?;
        let svg = frame_svg(game.env());
        let image = py
            .detach(|| raster::rgb(&svg))
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        array(py, (image.height, image.width, 3), image.pixels)
    }
}

/// Every agent's observation and action mask in `game` as it stands.
fn views<'py>(py: Python<'py>, game: &CheckedEnv) -> PyResult<AgentViews<'py>> {
    let n = game.env().offense();
    let (features, actions) = (game.observation().size(n), game.action_count());
    let mut obs = vec![0.0; n * features];
    let mut masks = vec![0; n * actions];
    game.write_observations(&mut obs);
    game.write_masks(&mut masks);
    Ok((
        array(py, (n, features), obs)?,
        array(py, (n, actions), masks)?,
    ))
}
