//! Many environments stepped in one call: the GIL released and the
//! environments spread over rayon's threads, numpy arrays in and out.
//! An environment whose episode ends starts the next one in the same step
//! (Gymnasium's same-step autoreset, and what HFO itself does: the state
//! after a terminal step belongs to the next episode).

use crate::arrays::array;
use crate::checked_env::CheckedEnv;
use crate::errors::{batch_step_error, not_started, value_error};
use crate::settings::TaskSettings;
use crate::status;
use env_server::Outcome;
use numpy::{PyArray1, PyArray3, PyReadonlyArrayDyn};
use proto::Action;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};

/// Observations (envs x agents x features) and action masks (envs x agents x actions).
type BatchViews<'py> = (Bound<'py, PyArray3<f32>>, Bound<'py, PyArray3<i8>>);

/// What a step returns: the views, then per environment the team's reward,
/// HFO's status number and the frame, then the last observations of the
/// episodes that ended (zeros elsewhere).
type BatchStep<'py> = (
    Bound<'py, PyArray3<f32>>,
    Bound<'py, PyArray3<i8>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i8>>,
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray3<f32>>,
);

/// The most environments one batch holds (each takes a few kilobytes,
/// its buffers a few hundred bytes).
pub(crate) const MAX_ENVS: usize = 1 << 20;

/// The most threads a batch starts.
const MAX_THREADS: usize = 1024;

/// `n` simulated HFO tasks of the same settings: `BatchEnv(settings,
/// n, threads)`, then `reset(seed)`; environment `i` draws from `seed + i`.
#[pyclass(module = "halffield._halffield")]
pub(crate) struct BatchEnv {
    settings: TaskSettings,
    n: usize,
    games: Vec<CheckedEnv>,
    /// A pool of its own when the batch was given a thread count, else
    /// rayon's global pool (one thread per core, or `RAYON_NUM_THREADS`).
    pool: Option<ThreadPool>,
}

#[pymethods]
impl BatchEnv {
    /// `n` environments of `settings`, none started, stepped on `threads`
    /// threads of their own (rayon's global pool without).
    #[new]
    #[pyo3(signature = (settings, n, threads = None))]
    fn new(settings: PyRef<'_, TaskSettings>, n: usize, threads: Option<usize>) -> PyResult<Self> {
        if !(1..=MAX_ENVS).contains(&n) {
            return Err(PyValueError::new_err(format!(
                "a batch holds 1 to {MAX_ENVS} environments, got n={n}"
            )));
        }
        let pool = match threads {
            Some(t) if !(1..=MAX_THREADS).contains(&t) => {
                return Err(PyValueError::new_err(format!(
                    "threads must be 1 to {MAX_THREADS}, got {t}"
                )));
            }
            Some(t) => Some(
                ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .map_err(|e| {
                        PyRuntimeError::new_err(format!("cannot start {t} threads: {e}"))
                    })?,
            ),
            None => None,
        };
        Ok(BatchEnv {
            settings: settings.clone(),
            n,
            games: Vec::new(),
            pool,
        })
    }

    /// Environments in the batch.
    #[getter]
    fn n(&self) -> usize {
        self.n
    }

    /// New simulators, environment `i` drawing from `seed + i` (wrapping),
    /// each at the start of its first episode.
    fn reset<'py>(&mut self, py: Python<'py>, seed: u64) -> PyResult<BatchViews<'py>> {
        self.games = (0..self.n as u64)
            .map(|i| CheckedEnv::new(&self.settings, seed.wrapping_add(i)))
            .collect::<Result<_, _>>()
            .map_err(value_error)?;
        let mut out = Buffers::new(&self.settings, self.n);
        let slots = out.slots(&self.settings);
        let (games, pool) = (&mut self.games, &self.pool);
        py.detach(|| {
            on(pool, || {
                games.par_iter_mut().zip(slots).for_each(|(game, slot)| {
                    game.reset();
                    game.write_observations(slot.obs);
                    game.write_masks(slot.masks);
                });
            })
        });
        let Buffers { obs, masks, .. } = out;
        Ok((
            array(py, self.shape(Per::Feature), obs)?,
            array(py, self.shape(Per::Action), masks)?,
        ))
    }

    /// Plays one step of every environment: `actions` holds one action
    /// index per environment and agent (shape envs x agents). Every action
    /// is checked before any environment steps.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: PyReadonlyArrayDyn<'py, i64>,
    ) -> PyResult<BatchStep<'py>> {
        if self.games.is_empty() {
            return Err(not_started());
        }
        let actions = actions.as_array();
        let agents = self.settings.config.offense;
        if actions.shape() != [self.n, agents] {
            return Err(PyValueError::new_err(format!(
                "actions must have shape (envs, agents) = ({}, {agents}), got {:?}",
                self.n,
                actions.shape()
            )));
        }
        let decoded = (self.games.iter().zip(actions.outer_iter()).enumerate())
            .map(|(i, (game, row))| {
                let row: Vec<i64> = row.iter().copied().collect();
                game.decode(&row).map_err(|e| batch_step_error(i, e))
            })
            .collect::<PyResult<Vec<Vec<Action>>>>()?;
        let mut out = Buffers::new(&self.settings, self.n);
        let slots = out.slots(&self.settings);
        let (games, pool) = (&mut self.games, &self.pool);
        let ends: Vec<(Outcome, u32)> = py.detach(|| {
            on(pool, || {
                (games.par_iter_mut().zip(decoded).zip(slots))
                    .map(|((game, actions), slot)| advance(game, &actions, slot))
                    .collect()
            })
        });
        let Buffers { obs, masks, last } = out;
        Ok((
            array(py, self.shape(Per::Feature), obs)?,
            array(py, self.shape(Per::Action), masks)?,
            PyArray1::from_vec(py, ends.iter().map(|(o, _)| o.reward()).collect()),
            PyArray1::from_vec(py, ends.iter().map(|&(o, _)| status::code(o)).collect()),
            PyArray1::from_vec(py, ends.iter().map(|&(_, f)| f).collect()),
            array(py, self.shape(Per::Feature), last)?,
        ))
    }
}

/// What the innermost axis of an output holds.
enum Per {
    Feature,
    Action,
}

impl BatchEnv {
    /// The shape of an output: envs x agents x `per`.
    fn shape(&self, per: Per) -> (usize, usize, usize) {
        let inner = match per {
            Per::Feature => self.settings.observation_size(),
            Per::Action => self.settings.action_count(),
        };
        (self.n, self.settings.config.offense, inner)
    }
}

/// Runs `work` on `pool`, or on rayon's global pool.
fn on<T: Send>(pool: &Option<ThreadPool>, work: impl FnOnce() -> T + Send) -> T {
    match pool {
        Some(pool) => pool.install(work),
        None => work(),
    }
}

/// Plays `actions` in `game`, then writes its views into `slot`; an episode
/// that ended leaves its last observations in `slot.last` and starts the
/// next. Returns how the step ended and at which frame.
fn advance(game: &mut CheckedEnv, actions: &[Action], slot: Slot<'_>) -> (Outcome, u32) {
    let outcome = game.step(actions);
    let frame = game.env().frame();
    if outcome.is_terminal() {
        game.write_observations(slot.last);
        game.reset();
    }
    game.write_observations(slot.obs);
    game.write_masks(slot.masks);
    (outcome, frame)
}

/// The output buffers of a step, environment after environment.
struct Buffers {
    obs: Vec<f32>,
    masks: Vec<i8>,
    last: Vec<f32>,
}

/// One environment's share of the [`Buffers`].
struct Slot<'a> {
    obs: &'a mut [f32],
    masks: &'a mut [i8],
    last: &'a mut [f32],
}

impl Buffers {
    /// Zeroed buffers for `n` environments of `settings`.
    fn new(settings: &TaskSettings, n: usize) -> Self {
        let agents = settings.config.offense;
        let features = n * agents * settings.observation_size();
        Buffers {
            obs: vec![0.0; features],
            masks: vec![0; n * agents * settings.action_count()],
            last: vec![0.0; features],
        }
    }

    /// Every environment's share, in order.
    fn slots(&mut self, settings: &TaskSettings) -> Vec<Slot<'_>> {
        let agents = settings.config.offense;
        let features = agents * settings.observation_size();
        let actions = agents * settings.action_count();
        (self.obs.chunks_exact_mut(features))
            .zip(self.masks.chunks_exact_mut(actions))
            .zip(self.last.chunks_exact_mut(features))
            .map(|((obs, masks), last)| Slot { obs, masks, last })
            .collect()
    }
}
