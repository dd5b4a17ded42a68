//! EF-OnTL's sars-RND (Castagna & Dusparic, arXiv 2303.01170): random
//! network distillation over whole transitions, whose error is an agent's
//! uncertainty about a (state, action, reward, next state) tuple. Facts from
//! the authors' library, github:acastagn/EF-OnTL at `4b3e42a`
//! (`SARSrnd.py`; research-57 §3.1):
//!
//! - its input concat(s, a, r, s'), the action as one scalar (here the
//!   kick's slot in the DQN's order, 0 to 3) and the reward as one, neither
//!   encoded nor normalised (l.18, 64-69);
//! - a target network fixed at its random initialisation and a predictor
//!   of the same layers (Linear, ReLU between), by default one Linear layer
//!   to 1024 outputs (`n_latent_var=[]`, `s_encode_size=1024`, l.14-25,
//!   36), both initialised as PyTorch's `nn.Linear`, the target first
//!   (l.138-141);
//! - the uncertainty: the mean over the outputs of the squared difference
//!   (l.57-62, 86-87);
//! - the predictor trained online, one tuple per step (`minibatch_size` 1),
//!   on that mean, by PyTorch's RMSprop at lr 1e-3 with its defaults (alpha
//!   0.99, epsilon 1e-8 added to the root, no momentum, not centred);
//!   `learn` returns the tuple's uncertainty before its step (l.64-80,
//!   142).
//!
//! Its only draws are its initial weights, from a generator seeded at
//! construction; products run on one thread. The method ef-ontl keeps one
//! per agent (not in its snapshot).

use candle_core::{DType, Device, Tensor, Var};
use rand::SeedableRng;

use crate::net::{self, single_threaded_products};
use crate::selection::AgentRng;

/// PyTorch's RMSprop defaults.
const ALPHA: f64 = 0.99;
const RMS_EPSILON: f64 = 1e-8;

/// Rows per batched evaluation (the library's `estimate_uncertainty`
/// batches by 32). 16 rows of 1024 outputs keep each tensor at 64 KiB,
/// under glibc's 128 KiB `mmap` threshold: larger ones are mapped and
/// unmapped around every candle op, whose page faults cost several times
/// the arithmetic (10,000 rows of 14 inputs: about 60 ms in chunks of 16,
/// 300 ms in chunks of 256, on a loaded machine).
const CHUNK: usize = 16;

/// A sars-RND's settings; the library's defaults.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RndSettings {
    /// Hidden layers' widths (ReLU) of both networks: none.
    pub(crate) hidden: Vec<u32>,
    /// Outputs of both networks: 1024.
    pub(crate) outputs: u32,
    /// RMSprop's learning rate: 1e-3.
    pub(crate) lr: f64,
}

impl Default for RndSettings {
    fn default() -> Self {
        Self {
            hidden: Vec::new(),
            outputs: 1024,
            lr: 1e-3,
        }
    }
}

/// One transition as a sars-RND reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sars<'a> {
    pub(crate) state: &'a [f32],
    /// The kick's slot in the DQN's order.
    pub(crate) slot: usize,
    pub(crate) reward: f32,
    /// The next state (the DQN stores zeros at an episode's end).
    pub(crate) next: &'a [f32],
}

impl<'a> Sars<'a> {
    /// The network's input: concat(s, a, r, s').
    pub(crate) fn row(&self) -> Vec<f32> {
        let mut row = Vec::with_capacity(2 * self.state.len() + 2);
        row.extend_from_slice(self.state);
        row.extend([self.slot as f32, self.reward]);
        row.extend_from_slice(self.next);
        row
    }

    /// The transition an input `row` holds.
    pub(crate) fn of(row: &'a [f32]) -> Self {
        let n = (row.len() - 2) / 2;
        Self {
            state: &row[..n],
            slot: row[n] as usize,
            reward: row[n + 1],
            next: &row[n + 2..],
        }
    }
}

/// Any candle failure: only a shape this module got wrong can cause one.
fn fault(e: candle_core::Error) -> String {
    format!("sars-rnd: {e}")
}

/// The target and the predictor, and RMSprop's mean square of each of the
/// predictor's parameters, laid end to end.
#[derive(Debug)]
pub(crate) struct Rnd {
    settings: RndSettings,
    /// Its input width: 2 x the state's + 2.
    width: usize,
    target: Vec<Tensor>,
    predictor: Vec<Var>,
    square: Tensor,
}

impl Rnd {
    /// A sars-RND of `settings` over transitions of states `state_width`
    /// numbers wide, its weights drawn from a generator seeded by `seed`.
    pub(crate) fn new(settings: &RndSettings, state_width: usize, seed: u64) -> Self {
        single_threaded_products();
        let mut rng = AgentRng::seed_from_u64(seed);
        let width = 2 * state_width + 2;
        let sizes = sizes(settings, width);
        let target: Vec<Tensor> = (net::layers(&sizes, &mut rng).iter())
            .map(Var::as_detached_tensor)
            .collect();
        let predictor = net::layers(&sizes, &mut rng);
        let n = predictor.iter().map(|p| p.elem_count()).sum::<usize>();
        Self {
            target,
            predictor,
            square: Tensor::zeros(n, DType::F32, &Device::Cpu).expect("zeros"),
            settings: settings.clone(),
            width,
        }
    }

    /// Its input width: 2 x the state's + 2.
    pub(crate) fn width(&self) -> usize {
        self.width
    }

    /// Both networks' outputs' squared differences for the rows of `x`.
    fn squared_error(&self, x: &Tensor) -> candle_core::Result<Tensor> {
        let target = net::forward(self.target.iter(), x, &[])?;
        let predicted = net::forward(self.predictor.iter().map(Var::as_tensor), x, &[])?;
        (predicted - target)?.sqr()
    }

    /// One RMSprop step of the predictor towards the target at input `x`
    /// (a [`Sars::row`]); the uncertainty there before the step.
    pub(crate) fn learn(&mut self, x: &[f32]) -> f64 {
        self.step(x).unwrap_or_else(|e| panic!("{}", fault(e)))
    }

    fn step(&mut self, x: &[f32]) -> candle_core::Result<f64> {
        let x = Tensor::from_slice(x, (1, self.width), &Device::Cpu)?;
        let loss = self.squared_error(&x)?.mean_all()?;
        let before = f64::from(loss.to_scalar::<f32>()?);
        let grads = loss.backward()?;
        let g = net::gradient(&self.predictor, &grads)?;
        self.square = ((&self.square * ALPHA)? + (g.sqr()? * (1.0 - ALPHA))?)?;
        let step = ((g / (self.square.sqrt()? + RMS_EPSILON)?)? * self.settings.lr)?;
        net::descend(&self.predictor, &step)?;
        Ok(before)
    }

    /// Its uncertainty at input `x` (a [`Sars::row`]): the mean over the
    /// outputs of the squared difference.
    #[cfg(test)]
    pub(crate) fn uncertainty(&self, x: &[f32]) -> f64 {
        self.uncertainties(x)[0]
    }

    /// The uncertainty of each row of `rows`, inputs laid end to end.
    pub(crate) fn uncertainties(&self, rows: &[f32]) -> Vec<f64> {
        assert_eq!(rows.len() % self.width, 0, "rows of the network's width");
        let each = |chunk: &[f32]| -> candle_core::Result<Vec<f32>> {
            let x =
                Tensor::from_slice(chunk, (chunk.len() / self.width, self.width), &Device::Cpu)?;
            self.squared_error(&x)?.mean(1)?.to_vec1::<f32>()
        };
        (rows.chunks(CHUNK * self.width))
            .map(|chunk| each(chunk).unwrap_or_else(|e| panic!("{}", fault(e))))
            .flat_map(|u| u.into_iter().map(f64::from))
            .collect()
    }
}

/// The layer sizes: inputs, hidden, outputs.
fn sizes(settings: &RndSettings, width: usize) -> Vec<usize> {
    let mut sizes = vec![width];
    sizes.extend(settings.hidden.iter().map(|&w| w as usize));
    sizes.push(settings.outputs as usize);
    sizes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A transition of 6-number states, its numbers from `v`.
    fn row(v: f32, slot: usize) -> Vec<f32> {
        let state: Vec<f32> = (0..6).map(|i| v * (i as f32 - 2.5) / 3.0).collect();
        let next: Vec<f32> = state.iter().map(|s| s * 0.9 + 0.05).collect();
        Sars {
            state: &state,
            slot,
            reward: v,
            next: &next,
        }
        .row()
    }

    #[test]
    fn a_row_is_concat_of_state_action_reward_next() {
        let (state, next) = ([1.0, 2.0], [3.0, 4.0]);
        let sars = Sars {
            state: &state,
            slot: 3,
            reward: -0.5,
            next: &next,
        };
        let row = sars.row();
        assert_eq!(row, [1.0, 2.0, 3.0, -0.5, 3.0, 4.0]);
        assert_eq!(Sars::of(&row), sars);
        assert_eq!(Rnd::new(&RndSettings::default(), 2, 1).width(), 6);
    }

    #[test]
    fn one_seed_gives_the_same_bits_and_another_seed_others() {
        let run = |seed| {
            let mut rnd = Rnd::new(&RndSettings::default(), 6, seed);
            let learned: Vec<u64> = (0..20)
                .map(|i| rnd.learn(&row(i as f32 / 10.0, i % 4)).to_bits())
                .collect();
            let probes: Vec<f32> = (0..4).flat_map(|k| row(0.05 * k as f32, k)).collect();
            let after: Vec<u64> = rnd
                .uncertainties(&probes)
                .iter()
                .map(|u| u.to_bits())
                .collect();
            (learned, after)
        };
        assert_eq!(run(3), run(3));
        let (a, b) = (run(3), run(4));
        assert_ne!(a.0, b.0);
        assert_ne!(a.1, b.1);
    }

    #[test]
    fn learn_returns_the_uncertainty_before_its_step_as_a_batch_does() {
        let mut rnd = Rnd::new(&RndSettings::default(), 6, 2);
        let (x, y) = (row(0.5, 1), row(-0.8, 2));
        let before = rnd.uncertainty(&x);
        assert!(before > 0.0);
        assert_eq!(rnd.learn(&x).to_bits(), before.to_bits());
        assert!(rnd.uncertainty(&x) < before);
        let both = rnd.uncertainties(&[x.clone(), y.clone()].concat());
        for (batched, single) in both.iter().zip([rnd.uncertainty(&x), rnd.uncertainty(&y)]) {
            assert!(
                (batched - single).abs() <= 1e-6 * single,
                "{batched} {single}"
            );
        }
    }

    #[test]
    fn it_grows_sure_of_a_learned_tuple_and_not_of_an_unseen_one() {
        let mut rnd = Rnd::new(&RndSettings::default(), 6, 5);
        let (seen, unseen) = (row(0.5, 1), row(-0.7, 3));
        let (seen_before, unseen_before) = (rnd.uncertainty(&seen), rnd.uncertainty(&unseen));
        for _ in 0..100 {
            rnd.learn(&seen);
        }
        let (seen_after, unseen_after) = (rnd.uncertainty(&seen), rnd.uncertainty(&unseen));
        assert!(
            seen_after < seen_before / 10.0 && unseen_after > unseen_before / 2.0,
            "seen {seen_before} -> {seen_after}, unseen {unseen_before} -> {unseen_after}"
        );
    }

    /// Times one learn step and one uncertainty at the default sizes, and a
    /// batched evaluation of 10,000 tuples, all of random numbers in
    /// [-1, 1): `cargo test --release -p agent --lib -- --ignored
    /// --nocapture --test-threads=1 time_`.
    #[test]
    #[ignore = "a measurement"]
    fn time_the_default_rnd() {
        use rand::Rng;
        for state in [6, 27] {
            let mut rnd = Rnd::new(&RndSettings::default(), state, 1);
            let mut rng = AgentRng::seed_from_u64(2);
            let n = 2000;
            let rows: Vec<f32> = (0..10_000 * rnd.width())
                .map(|_| rng.random::<f32>() * 2.0 - 1.0)
                .collect();
            let xs: Vec<&[f32]> = rows.chunks(rnd.width()).take(n).collect();
            let start = std::time::Instant::now();
            let mut sum: f64 = xs.iter().map(|x| rnd.learn(x)).sum();
            let learn = start.elapsed() / n as u32;
            let start = std::time::Instant::now();
            sum += xs.iter().map(|x| rnd.uncertainty(x)).sum::<f64>();
            let one = start.elapsed() / n as u32;
            let start = std::time::Instant::now();
            sum += rnd.uncertainties(&rows).iter().sum::<f64>();
            let batch = start.elapsed();
            println!(
                "sars-RND, {state}-number states ({} inputs, 1024 outputs): one learn step \
                 {learn:?}, one uncertainty {one:?}, 10,000 batched {batch:?} ({sum})",
                rnd.width()
            );
        }
    }
}
