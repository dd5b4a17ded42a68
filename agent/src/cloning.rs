//! Advice imitation's behavioural-cloning network (Ilhan, Gow &
//! Perez-Liebana, arXiv 2104.08440 and 2104.08441): it imitates the kick
//! actions an agent was advised, and its Monte Carlo dropout variance says
//! where it may stand in for the advisor. Facts from the authors' code,
//! github:ercumentilhan/advice-imitation-reuse at `0e46155`
//! (`code/behavioural_cloning.py`, `executor.py`, `main.py`; research-57
//! §2.2-2.3):
//!
//! - an MLP over the agent's observation, ReLU between its layers, one
//!   logit per kick action in the DQN's order ([`KICKS`]), softmax
//!   probabilities; dropout on every hidden layer's output, so before every
//!   dense layer but the first. The authors' drops a conv torso's features
//!   before its hidden layer and that layer's output before the logits
//!   (`behavioural_cloning.py` l.105-116); here the first layer stands for
//!   the torso, for a dropout on the observation itself (6 or 27 numbers,
//!   not 3136 features) would blur what it learned: on a toy mapping it
//!   kept the uncertainty of well-imitated inputs at 0.05, five times the
//!   authors' fixed threshold, against 0.002 this way;
//! - its loss the authors': sigmoid cross-entropy between the logits and
//!   the one-hot advised action, meaned over actions and batch (l.134-145),
//!   not softmax's, dropout on; minibatches drawn with replacement
//!   (`replay_buffer_bc.py` l.74), at most `batch`; Adam as TensorFlow 1's
//!   `AdamOptimizer` computes it (epsilon added to sqrt(v), the step scaled
//!   by sqrt(1 - beta2^t) / (1 - beta1^t)), lr 1e-4, epsilon 1.5e-4;
//! - its uncertainty at x: the mean over actions of the population variance
//!   of the softmax probabilities over `passes` dropout passes
//!   (l.254-263); its advice, the argmax with dropout off (l.187-191);
//! - its threshold autoset to a percentile (the 90th) of the uncertainty
//!   over the stored samples it imitates correctly (`executor.py`
//!   l.595-651).
//!
//! Every draw (initial weights, minibatches, dropout masks) comes from its
//! own generator; products run on one thread. The method advice-imitation
//! calls all of its `pub(crate)` items.
#![cfg_attr(not(test), allow(dead_code))]

use candle_core::{DType, Device, Tensor, Var};
use proto::Action;
use rand::{Rng, SeedableRng};
use serde::{Deserialize, Serialize};

use crate::dqn::{KICKS, kick_slot};
use crate::learner_settings::DqnSettings;
use crate::net::{self, flat, single_threaded_products};
use crate::selection::AgentRng;

/// Adam's constants: TensorFlow's beta defaults and the authors' epsilon
/// (`main.py` l.61).
const BETA1: f64 = 0.9;
const BETA2: f64 = 0.999;
const ADAM_EPSILON: f64 = 1.5e-4;

const STATE_TAG: &str = "adhoc-advising cloning";
const STATE_VERSION: u16 = 1;

/// A cloning network's settings; the authors' values by default
/// (`main.py` l.59-64) but the layers, the DQN's.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CloningSettings {
    /// Hidden layers' widths (ReLU): the DQN's `hidden` by default (the
    /// authors' 512 over conv features).
    pub(crate) hidden: Vec<u32>,
    /// Dropout's rate on every hidden layer's output, in [0, 1): 0.35.
    pub(crate) dropout: f64,
    /// Adam's learning rate: 1e-4.
    pub(crate) lr: f64,
    /// Samples per minibatch: 32 (fewer while it holds fewer).
    pub(crate) batch: usize,
    /// Dropout passes per uncertainty: 100 (`bc-uc-ensembles`).
    pub(crate) passes: usize,
    /// The threshold before its first autoset: 0.01, AR's fixed one
    /// (`constants/ale.py` l.126, 133).
    pub(crate) threshold: f64,
}

impl Default for CloningSettings {
    fn default() -> Self {
        Self {
            hidden: DqnSettings::default().hidden,
            dropout: 0.35,
            lr: 1e-4,
            batch: 32,
            passes: 100,
            threshold: 0.01,
        }
    }
}

/// Adam's moments, laid end to end, and its step count.
#[derive(Debug)]
struct Adam {
    m: Tensor,
    v: Tensor,
    t: u64,
}

impl Adam {
    /// One step of `params` at rate `lr` down their gradients in `grads`.
    fn step(
        &mut self,
        lr: f64,
        params: &[Var],
        grads: &candle_core::backprop::GradStore,
    ) -> candle_core::Result<()> {
        self.t += 1;
        let t = self.t as f64;
        let lr_t = lr * (1.0 - BETA2.powf(t)).sqrt() / (1.0 - BETA1.powf(t));
        let g = net::gradient(params, grads)?;
        self.m = ((&self.m * BETA1)? + (&g * (1.0 - BETA1))?)?;
        self.v = ((&self.v * BETA2)? + (g.sqr()? * (1.0 - BETA2))?)?;
        let step = ((&self.m / (self.v.sqrt()? + ADAM_EPSILON)?)? * lr_t)?;
        net::descend(params, &step)
    }
}

/// The (observation, advised kick) pairs it imitates, every one kept (the
/// authors' buffer holds 1e6).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
struct Samples {
    /// `width` numbers per sample.
    obs: Vec<f32>,
    /// The advised kick's slot in [`KICKS`].
    slot: Vec<u8>,
}

/// Any candle failure: only a shape this module got wrong can cause one.
fn fault(e: candle_core::Error) -> String {
    format!("cloning: {e}")
}

/// The behavioural-cloning network, its samples, its threshold and its
/// generator.
#[derive(Debug)]
pub(crate) struct Cloning {
    settings: CloningSettings,
    width: usize,
    params: Vec<Var>,
    adam: Adam,
    samples: Samples,
    threshold: f64,
    rng: AgentRng,
}

impl Cloning {
    /// A network of `settings` over `inputs` numbers of the agent's
    /// observation, its weights and draws seeded by `seed`.
    pub(crate) fn new(settings: &CloningSettings, inputs: usize, seed: u64) -> Self {
        single_threaded_products();
        let mut rng = AgentRng::seed_from_u64(seed);
        let sizes = sizes(settings, inputs);
        let params = net::layers(&sizes, &mut rng);
        let n = params.iter().map(|p| p.elem_count()).sum::<usize>();
        let zeros = Tensor::zeros(n, DType::F32, &Device::Cpu).expect("zeros");
        Self {
            adam: Adam {
                m: zeros.clone(),
                v: zeros,
                t: 0,
            },
            params,
            samples: Samples::default(),
            threshold: settings.threshold,
            rng,
            settings: settings.clone(),
            width: inputs,
        }
    }

    /// Stores observation `x` and the kick action advised there.
    ///
    /// # Panics
    /// If `x` is not `inputs` wide or `action` is not a kick.
    pub(crate) fn add(&mut self, x: &[f32], action: Action) {
        assert_eq!(x.len(), self.width, "an observation of the network's width");
        let slot = kick_slot(action).expect("an advised kick action");
        self.samples.obs.extend_from_slice(x);
        self.samples.slot.push(slot as u8);
    }

    /// How many samples it holds.
    pub(crate) fn samples(&self) -> usize {
        self.samples.slot.len()
    }

    /// `iterations` gradient steps, each on `batch` samples (fewer while it
    /// holds fewer) drawn with replacement; none while it holds none.
    pub(crate) fn train(&mut self, iterations: u64) {
        for _ in 0..iterations {
            if self.samples() == 0 {
                return;
            }
            self.step().unwrap_or_else(|e| panic!("{}", fault(e)));
        }
    }

    fn step(&mut self) -> candle_core::Result<()> {
        let (w, k) = (self.width, KICKS.len());
        let n = self.settings.batch.min(self.samples());
        let mut x = Vec::with_capacity(n * w);
        let mut y = vec![0f32; n * k];
        for row in 0..n {
            let i = self.rng.random_range(0..self.samples());
            x.extend_from_slice(&self.samples.obs[i * w..(i + 1) * w]);
            y[row * k + usize::from(self.samples.slot[i])] = 1.0;
        }
        let x = Tensor::from_vec(x, (n, w), &Device::Cpu)?;
        let y = Tensor::from_vec(y, (n, k), &Device::Cpu)?;
        let masks = self.masks(n)?;
        let z = net::forward(self.params.iter().map(Var::as_tensor), &x, &masks)?;
        // tf.nn.sigmoid_cross_entropy_with_logits: max(z, 0) - z y + ln(1 + e^-|z|).
        let softplus = ((z.abs()?.neg()?.exp()? + 1.0)?.log())?;
        let loss = ((z.relu()? - (&z * &y)?)? + softplus)?.mean_all()?;
        let grads = loss.backward()?;
        self.adam.step(self.settings.lr, &self.params, &grads)
    }

    /// Dropout masks for `rows` rows, one per hidden layer's output: 0 with
    /// probability `dropout`, else 1 / (1 - dropout) (TensorFlow's
    /// `nn.dropout`); none at rate 0.
    fn masks(&mut self, rows: usize) -> candle_core::Result<Vec<Tensor>> {
        let rate = self.settings.dropout;
        if rate == 0.0 {
            return Ok(Vec::new());
        }
        let kept = (1.0 / (1.0 - rate)) as f32;
        (self.settings.hidden.iter())
            .map(|&width| {
                let width = width as usize;
                let mask: Vec<f32> = (0..rows * width)
                    .map(|_| {
                        if self.rng.random::<f32>() < rate as f32 {
                            0.0
                        } else {
                            kept
                        }
                    })
                    .collect();
                Tensor::from_vec(mask, (rows, width), &Device::Cpu)
            })
            .collect()
    }

    /// The logits of `rows` copies of `x`, row after row, with `masks`.
    fn logits(&self, x: &[f32], rows: usize, masks: &[Tensor]) -> Vec<f32> {
        assert_eq!(x.len(), self.width, "an observation of the network's width");
        Tensor::from_vec(x.repeat(rows), (rows, self.width), &Device::Cpu)
            .and_then(|x| net::forward(self.params.iter().map(Var::as_tensor), &x, masks))
            .and_then(|z| z.flatten_all()?.to_vec1::<f32>())
            .unwrap_or_else(|e| panic!("{}", fault(e)))
    }

    /// Its advice at `x`: the kick of the largest probability, dropout off
    /// (the first of equals).
    pub(crate) fn greedy(&self, x: &[f32]) -> Action {
        KICKS[self.greedy_slot(x)]
    }

    fn greedy_slot(&self, x: &[f32]) -> usize {
        let z = self.logits(x, 1, &[]);
        (1..z.len()).fold(0, |best, i| if z[i] > z[best] { i } else { best })
    }

    /// Its uncertainty at `x`: over `passes` dropout passes, each action's
    /// softmax probability's population variance, meaned over the actions.
    pub(crate) fn uncertainty(&mut self, x: &[f32]) -> f64 {
        let (n, k) = (self.settings.passes, KICKS.len());
        let masks = self.masks(n).unwrap_or_else(|e| panic!("{}", fault(e)));
        let z = self.logits(x, n, &masks);
        let mut p = vec![0.0; n * k];
        for (row, out) in z.chunks(k).zip(p.chunks_mut(k)) {
            let top = row.iter().fold(f32::NEG_INFINITY, |a, &b| a.max(b));
            for (o, &zi) in out.iter_mut().zip(row) {
                *o = f64::from(zi - top).exp();
            }
            let sum: f64 = out.iter().sum();
            out.iter_mut().for_each(|o| *o /= sum);
        }
        let variance = |a: usize| {
            let each = p.iter().skip(a).step_by(k);
            let mean = each.clone().sum::<f64>() / n as f64;
            each.map(|q| (q - mean).powi(2)).sum::<f64>() / n as f64
        };
        (0..k).map(variance).sum::<f64>() / k as f64
    }

    /// The threshold: its setting until the first autoset.
    pub(crate) fn threshold(&self) -> f64 {
        self.threshold
    }

    /// Sets the threshold to the `percentile` (numpy's linear
    /// interpolation) of the uncertainty over the stored samples whose
    /// dropout-off advice is their label, evaluated in their order. With
    /// none such it keeps the threshold it had (the authors' code fails
    /// there, on numpy's percentile of nothing; with no samples at all it
    /// sets infinity).
    pub(crate) fn autoset_threshold(&mut self, percentile: f64) {
        let w = self.width;
        let mut correct = Vec::new();
        for i in 0..self.samples() {
            let x = self.samples.obs[i * w..(i + 1) * w].to_vec();
            let u = self.uncertainty(&x);
            if self.greedy_slot(&x) == usize::from(self.samples.slot[i]) {
                correct.push(u);
            }
        }
        if !correct.is_empty() {
            self.threshold = percentile_of(&mut correct, percentile);
        }
    }

    /// Its state: the weights, Adam's moments, the samples, the threshold
    /// and the generator, so that a loaded network goes on as this would.
    pub(crate) fn save(&self) -> Vec<u8> {
        let saved = self.saved().unwrap_or_else(|e| panic!("{}", fault(e)));
        postcard::to_allocvec(&saved).expect("a cloning network's state serialises")
    }

    fn saved(&self) -> candle_core::Result<Saved> {
        Ok(Saved {
            tag: STATE_TAG.into(),
            version: STATE_VERSION,
            shape: self.shape(),
            params: net::lists(self.params.iter().map(Var::as_tensor))?,
            adam_m: net::flat_lists(&self.adam.m, &self.params)?,
            adam_v: net::flat_lists(&self.adam.v, &self.params)?,
            adam_t: self.adam.t,
            samples: self.samples.clone(),
            threshold: self.threshold,
            rng: self.rng.clone(),
        })
    }

    fn shape(&self) -> Vec<u32> {
        sizes(&self.settings, self.width)
            .iter()
            .map(|&s| s as u32)
            .collect()
    }

    /// Takes `state` (from [`save`](Self::save)) as its own, refused with
    /// why if it is not a cloning network's of its layers; its settings
    /// stay its own.
    pub(crate) fn load(&mut self, state: &[u8]) -> Result<(), String> {
        net::check_header(state, STATE_TAG, STATE_VERSION)?;
        let saved: Saved = postcard::from_bytes(state).map_err(|e| format!("{STATE_TAG}: {e}"))?;
        if saved.shape != self.shape() {
            return Err(format!(
                "the snapshot's cloning network has layers {:?}, this one {:?}",
                saved.shape,
                self.shape()
            ));
        }
        let s = &saved.samples;
        if s.obs.len() != s.slot.len() * self.width
            || s.slot.iter().any(|&a| usize::from(a) >= KICKS.len())
            || saved.threshold.is_nan()
        {
            return Err("the snapshot's cloning samples or threshold are inconsistent".into());
        }
        let params = net::tensors(saved.params, &self.params, "cloning network")?;
        let m = net::tensors(saved.adam_m, &self.params, "optimiser state")?;
        let v = net::tensors(saved.adam_v, &self.params, "optimiser state")?;
        for (var, value) in self.params.iter().zip(&params) {
            var.set(value).map_err(fault)?;
        }
        self.adam = Adam {
            m: flat(&m).map_err(fault)?,
            v: flat(&v).map_err(fault)?,
            t: saved.adam_t,
        };
        self.samples = saved.samples;
        self.threshold = saved.threshold;
        self.rng = saved.rng;
        Ok(())
    }
}

/// The layer sizes: inputs, hidden, one logit per kick.
fn sizes(settings: &CloningSettings, inputs: usize) -> Vec<usize> {
    let mut sizes = vec![inputs];
    sizes.extend(settings.hidden.iter().map(|&w| w as usize));
    sizes.push(KICKS.len());
    sizes
}

/// numpy's `percentile(values, p)` (linear interpolation, its `_lerp`) of
/// `values`, not empty; sorts them.
fn percentile_of(values: &mut [f64], p: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    let at = p / 100.0 * (values.len() - 1) as f64;
    let lo = at.floor() as usize;
    let hi = (lo + 1).min(values.len() - 1);
    let (a, b, t) = (values[lo], values[hi], at - lo as f64);
    let d = b - a;
    if t >= 0.5 {
        b - d * (1.0 - t)
    } else {
        a + d * t
    }
}

/// A cloning network's snapshot bytes (postcard).
#[derive(Serialize, Deserialize)]
struct Saved {
    tag: String,
    version: u16,
    shape: Vec<u32>,
    params: Vec<Vec<f32>>,
    adam_m: Vec<Vec<f32>>,
    adam_v: Vec<Vec<f32>>,
    adam_t: u64,
    samples: Samples,
    threshold: f64,
    rng: AgentRng,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> CloningSettings {
        CloningSettings {
            hidden: vec![32, 32],
            lr: 1e-2,
            ..CloningSettings::default()
        }
    }

    /// A separable toy mapping over 6 numbers: the quadrant of the first
    /// two picks the kick; the other four are noise.
    fn toy(n: usize, seed: u64) -> Vec<(Vec<f32>, Action)> {
        let mut rng = AgentRng::seed_from_u64(seed);
        (0..n)
            .map(|i| {
                let slot = i % 4;
                let sign = |bit: usize| if slot >> bit & 1 == 1 { 0.6 } else { -0.6 };
                let mut noise = |scale: f32| (rng.random::<f32>() * 2.0 - 1.0) * scale;
                let x = vec![
                    sign(0) + noise(0.25),
                    sign(1) + noise(0.25),
                    noise(0.2),
                    noise(0.2),
                    noise(0.2),
                    noise(0.2),
                ];
                (x, KICKS[slot])
            })
            .collect()
    }

    fn accuracy(bc: &Cloning, set: &[(Vec<f32>, Action)]) -> f64 {
        let right = set.iter().filter(|(x, a)| bc.greedy(x) == *a).count();
        right as f64 / set.len() as f64
    }

    fn trained(settings: &CloningSettings, seed: u64, iterations: u64) -> Cloning {
        let mut bc = Cloning::new(settings, 6, seed);
        for (x, a) in toy(64, 1) {
            bc.add(&x, a);
        }
        bc.train(iterations);
        bc
    }

    #[test]
    fn one_seed_gives_the_same_bits_and_another_seed_others() {
        let x = &toy(1, 9)[0].0;
        let run = |seed| {
            let mut bc = trained(&small(), seed, 20);
            (bc.save(), bc.uncertainty(x).to_bits(), bc.greedy(x))
        };
        assert_eq!(run(5), run(5));
        assert_ne!(run(5).0, run(6).0);
        assert_ne!(run(5).1, run(6).1);
    }

    #[test]
    fn it_learns_a_separable_mapping_and_grows_sure_where_it_learned() {
        let held_out = toy(200, 2);
        let mut bc = trained(&small(), 3, 0);
        let before = accuracy(&bc, &held_out);
        let inside: Vec<Vec<f32>> = toy(8, 4).into_iter().map(|(x, _)| x).collect();
        let far: Vec<Vec<f32>> = (0..8)
            .map(|i| {
                (0..6)
                    .map(|j| if (i + j) % 2 == 0 { 4.0 } else { -4.0 })
                    .collect()
            })
            .collect();
        let mean = |bc: &mut Cloning, xs: &[Vec<f32>]| {
            xs.iter().map(|x| bc.uncertainty(x)).sum::<f64>() / xs.len() as f64
        };
        bc.train(300);
        let after = accuracy(&bc, &held_out);
        assert!(before < 0.5 && after > 0.9, "{before} -> {after}");
        let (inside_after, far_after) = (mean(&mut bc, &inside), mean(&mut bc, &far));
        assert!(
            inside_after < far_after / 3.0,
            "inside {inside_after}, far {far_after}"
        );
    }

    #[test]
    fn the_percentile_is_numpys_linear_one() {
        let p = |values: &[f64], p| percentile_of(&mut values.to_vec(), p);
        let four = [0.4, 0.1, 0.3, 0.2];
        // Sorted 0.1 0.2 0.3 0.4; the 90th at 2.7: 0.3 + 0.7 x 0.1.
        assert!((p(&four, 90.0) - 0.37).abs() < 1e-15);
        assert!((p(&four, 50.0) - 0.25).abs() < 1e-15);
        assert_eq!((p(&four, 0.0), p(&four, 100.0)), (0.1, 0.4));
        assert_eq!(p(&[0.7], 90.0), 0.7);
    }

    #[test]
    fn the_threshold_is_the_90th_percentile_over_the_correctly_imitated() {
        let settings = CloningSettings {
            hidden: vec![4],
            passes: 10,
            ..CloningSettings::default()
        };
        let mut bc = Cloning::new(&settings, 2, 7);
        let xs: Vec<[f32; 2]> = (0..5).map(|i| [i as f32 * 0.3 - 0.6, 0.5]).collect();
        // Samples 0, 2 and 4 labelled as it answers, 1 and 3 otherwise.
        let wrong = |a: Action| KICKS[(kick_slot(a).unwrap() + 1) % 4];
        for (i, x) in xs.iter().enumerate() {
            let g = bc.greedy(x);
            bc.add(x, if i % 2 == 0 { g } else { wrong(g) });
        }
        // A copy draws the same masks: each sample's uncertainty in order.
        let mut copy = Cloning::new(&settings, 2, 99);
        copy.load(&bc.save()).unwrap();
        let u: Vec<f64> = xs.iter().map(|x| copy.uncertainty(x)).collect();
        let mut s = [u[0], u[2], u[4]];
        s.sort_by(f64::total_cmp);
        // At 0.9 x 2 = 1.8: s[1] + 0.8 (s[2] - s[1]).
        let expected = s[1] + 0.8 * (s[2] - s[1]);
        assert_eq!(bc.threshold(), 0.01);
        bc.autoset_threshold(90.0);
        assert!(
            (bc.threshold() - expected).abs() <= 1e-15,
            "{} {expected}",
            bc.threshold()
        );
        assert!(s[0] < expected && expected <= s[2]);

        // None imitated correctly: the threshold stays.
        let mut none = Cloning::new(&settings, 2, 7);
        for x in &xs {
            let g = none.greedy(x);
            none.add(x, wrong(g));
        }
        none.autoset_threshold(90.0);
        assert_eq!(none.threshold(), 0.01);
    }

    #[test]
    fn a_snapshot_goes_on_as_the_saved_network_would() {
        let mut saved = trained(&small(), 11, 30);
        saved.autoset_threshold(90.0);
        let bytes = saved.save();
        let mut loaded = Cloning::new(&small(), 6, 12);
        loaded.load(&bytes).unwrap();
        assert_eq!(loaded.save(), bytes);
        assert_eq!(loaded.threshold(), saved.threshold());
        let (x, a) = toy(1, 5).remove(0);
        for bc in [&mut saved, &mut loaded] {
            bc.add(&x, a);
            bc.train(10);
        }
        assert_eq!(
            saved.uncertainty(&x).to_bits(),
            loaded.uncertainty(&x).to_bits()
        );
        assert_eq!(saved.save(), loaded.save());
    }

    #[test]
    fn a_snapshot_of_other_layers_or_another_kind_is_refused() {
        let mut bc = Cloning::new(&small(), 6, 1);
        let wider = CloningSettings {
            hidden: vec![8],
            ..small()
        };
        let e = bc.load(&Cloning::new(&wider, 6, 1).save()).unwrap_err();
        assert_eq!(
            e,
            "the snapshot's cloning network has layers [6, 8, 4], this one [6, 32, 32, 4]"
        );
        let other = postcard::to_allocvec(&("adhoc-advising sars-rnd", 1u16)).unwrap();
        let e = bc.load(&other).unwrap_err();
        assert!(e.contains("not a adhoc-advising cloning state"), "{e}");
        let mut cut = bc.save();
        cut.truncate(cut.len() / 2);
        assert!(bc.load(&cut).is_err());
    }

    /// Times one uncertainty (100 passes) and one training iteration at
    /// the default sizes, on 1000 samples of random numbers in [-1, 1):
    /// `cargo test --release -p agent --lib -- --ignored --nocapture
    /// --test-threads=1 time_`.
    #[test]
    #[ignore = "a measurement"]
    fn time_the_default_cloning_network() {
        for width in [6, 27] {
            let mut bc = Cloning::new(&CloningSettings::default(), width, 1);
            let mut rng = AgentRng::seed_from_u64(2);
            let xs: Vec<Vec<f32>> = (0..1000)
                .map(|_| {
                    (0..width)
                        .map(|_| rng.random::<f32>() * 2.0 - 1.0)
                        .collect()
                })
                .collect();
            for (i, x) in xs.iter().enumerate() {
                bc.add(x, KICKS[i % 4]);
            }
            let n = 2000;
            let start = std::time::Instant::now();
            bc.train(n);
            let iteration = start.elapsed() / n as u32;
            let start = std::time::Instant::now();
            let sum: f64 = (xs.iter().cycle().take(n as usize))
                .map(|x| bc.uncertainty(x))
                .sum();
            let uncertainty = start.elapsed() / n as u32;
            let start = std::time::Instant::now();
            bc.autoset_threshold(90.0);
            let autoset = start.elapsed();
            println!(
                "cloning, {width} inputs, hidden {:?}: one uncertainty ({} passes) {uncertainty:?}, \
                 one training iteration (batch 32) {iteration:?}, autoset over 1000 samples \
                 {autoset:?} ({sum})",
                bc.settings.hidden, bc.settings.passes
            );
        }
    }
}
