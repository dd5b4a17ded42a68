//! A Double DQN over the agent's observation (van Hasselt et al., AAAI
//! 2016): an MLP of candle tensors, a target network, experience replay,
//! an epsilon schedule, Huber loss and Adam; with `heads` of 2 or more, K
//! heads on one torso, each trained on its bootstrap mask (Osband et al.,
//! NeurIPS 2016), whose variance is its uncertainty (docs/learners.md).
//!
//! It learns where the agent decides, from one kick to the next: the frames
//! it moves without the ball are folded into the kick's discounted reward
//! (an SMDP step, as HFO's own agents and `numpy_learner.py` learn), so one
//! stored transition is one decision. Everything it draws (initial weights,
//! bootstrap masks, replay samples) comes from its own generator, seeded
//! from the agent's; its arithmetic runs on one thread (candle's CPU
//! backend with the matrix product's threading turned off), so a seed gives
//! the same bits whatever the study's threads.

use candle_core::{D, DType, Device, Tensor, Var};
use proto::{Action, Features};
use rand::{Rng, SeedableRng};
use serde::{Deserialize, Serialize};

use crate::learner::{ActionValues, Experience, Learner, Seen};
use crate::learner_settings::{DqnSettings, ObservationSet};
use crate::net::{self, flat, single_threaded_products};
use crate::selection::{AgentRng, epsilon_greedy};

/// The kick actions the network values, in its output order.
pub(crate) const KICKS: [Action; 4] = [
    Action::Shoot,
    Action::Dribble,
    Action::PassNear,
    Action::PassFar,
];

/// Bits of [`ActionValues::learned`] for every kick action.
const ALL_KICKS: u8 = 0b1_1110;

/// Adam's constants (Kingma & Ba's, PyTorch's defaults).
const BETA1: f64 = 0.9;
const BETA2: f64 = 0.999;
const ADAM_EPSILON: f64 = 1e-8;

/// What a saved state starts with, and its layout's version (2: the
/// observation set it reads).
const STATE_TAG: &str = "adhoc-advising dqn";
const STATE_VERSION: u16 = 2;

/// Whether `state`, a learner's own saved bytes, is a DQN's.
pub(crate) fn holds_dqn_state(state: &[u8]) -> bool {
    matches!(postcard::take_from_bytes::<String>(state), Ok((tag, _)) if tag == STATE_TAG)
}

/// The network's output position of a kick action.
pub(crate) fn kick_slot(action: Action) -> Option<usize> {
    KICKS.iter().position(|&a| a == action)
}

/// Whether `a` and `b` hold the same bits.
fn same_bits(a: &Features, b: &Features) -> bool {
    let (a, b) = (a.as_slice(), b.as_slice());
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Any candle failure: only a shape this module got wrong can cause one.
fn fault(e: candle_core::Error) -> String {
    format!("dqn: {e}")
}

/// The experience replay: a ring of decisions.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
struct Replay {
    capacity: usize,
    /// Where the next transition goes once it is full.
    next: usize,
    /// `features` per transition.
    state: Vec<f32>,
    /// The kick's output slot.
    action: Vec<u8>,
    /// The discounted reward to the next decision.
    reward: Vec<f32>,
    /// gamma^k to the next decision, 0 at the episode's end.
    discount: Vec<f32>,
    /// `features` per transition (zeros at the episode's end).
    next_state: Vec<f32>,
    /// Which heads learn it, a bit each.
    mask: Vec<u16>,
}

/// Decisions laid out for one gradient step: their states, next states,
/// kick slots (one per head), rewards, discounts and heads' masks.
struct Batch {
    heads: usize,
    n: usize,
    s: Vec<f32>,
    s2: Vec<f32>,
    a: Vec<u32>,
    rew: Vec<f32>,
    disc: Vec<f32>,
    mask: Vec<f32>,
}

impl Batch {
    /// Room for `n` decisions of `width` inputs learned by `heads` heads.
    fn with_capacity(n: usize, width: usize, heads: usize) -> Self {
        Self {
            heads,
            n: 0,
            s: Vec::with_capacity(n * width),
            s2: Vec::with_capacity(n * width),
            a: Vec::new(),
            rew: Vec::new(),
            disc: Vec::new(),
            mask: Vec::with_capacity(n * heads),
        }
    }

    /// Adds one decision: its state, next state, kick slot, reward and
    /// discount, and which heads learn it (a bit each).
    fn push(&mut self, s: &[f32], s2: &[f32], slot: u8, (rew, disc): (f32, f32), mask: u16) {
        let k = self.heads;
        self.n += 1;
        self.s.extend_from_slice(s);
        self.s2.extend_from_slice(s2);
        self.a.extend(std::iter::repeat_n(u32::from(slot), k));
        self.rew.push(rew);
        self.disc.push(disc);
        (self.mask).extend((0..k).map(|h| f32::from(u8::from(mask >> h & 1 == 1))));
    }
}

/// One decision, closed.
struct Decision<'a> {
    state: &'a [f32],
    slot: usize,
    reward: f64,
    discount: f64,
    next: Option<&'a [f32]>,
    mask: u16,
}

impl Replay {
    fn new(capacity: usize) -> Self {
        Self {
            capacity,
            ..Self::default()
        }
    }

    fn len(&self) -> usize {
        self.action.len()
    }

    fn push(&mut self, d: &Decision<'_>) {
        let width = d.state.len();
        let zeros = vec![0.0; width];
        let next = d.next.unwrap_or(&zeros);
        if self.len() < self.capacity {
            self.state.extend_from_slice(d.state);
            self.next_state.extend_from_slice(next);
            self.action.push(d.slot as u8);
            self.reward.push(d.reward as f32);
            self.discount.push(d.discount as f32);
            self.mask.push(d.mask);
        } else {
            let i = self.next;
            self.state[i * width..(i + 1) * width].copy_from_slice(d.state);
            self.next_state[i * width..(i + 1) * width].copy_from_slice(next);
            self.action[i] = d.slot as u8;
            self.reward[i] = d.reward as f32;
            self.discount[i] = d.discount as f32;
            self.mask[i] = d.mask;
            self.next = (i + 1) % self.capacity;
        }
    }

    /// Whether its columns agree with one another, `width` and `heads`.
    fn consistent(&self, width: usize, heads: usize) -> bool {
        let n = self.len();
        n <= self.capacity
            && (self.next < self.capacity.max(1))
            && [self.reward.len(), self.discount.len(), self.mask.len()] == [n; 3]
            && self.state.len() == n * width
            && self.next_state.len() == n * width
            && self.action.iter().all(|&a| usize::from(a) < KICKS.len())
            && self
                .mask
                .iter()
                .all(|&m| m != 0 && u32::from(m) >> heads == 0)
    }
}

/// The kick being learned: its state and slot, the discounted reward since
/// and the discount of what follows.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Open {
    state: Vec<f32>,
    slot: usize,
    reward: f64,
    discount: f64,
}

impl Open {
    /// Folds one frame's `reward` in.
    fn fold(&mut self, reward: f64, gamma: f64) {
        self.reward += self.discount * reward;
        self.discount *= gamma;
    }
}

/// Adam's moments, every parameter's laid end to end in one tensor (one
/// candle op per update for all of them), and its step count.
#[derive(Debug)]
struct Adam {
    lr: f64,
    m: Tensor,
    v: Tensor,
    t: u64,
}

impl Adam {
    fn new(lr: f64, params: &[Var]) -> candle_core::Result<Self> {
        let n = params.iter().map(|p| p.elem_count()).sum::<usize>();
        let zeros = Tensor::zeros(n, DType::F32, &Device::Cpu)?;
        Ok(Self {
            lr,
            m: zeros.clone(),
            v: zeros,
            t: 0,
        })
    }

    /// One step of every parameter, each with its gradient in `grads`.
    fn step(
        &mut self,
        params: &[Var],
        grads: &candle_core::backprop::GradStore,
    ) -> candle_core::Result<()> {
        self.t += 1;
        let t = self.t as i32;
        let (c1, c2) = (1.0 - BETA1.powi(t), 1.0 - BETA2.powi(t));
        let g = net::gradient(params, grads)?;
        self.m = ((&self.m * BETA1)? + (&g * (1.0 - BETA1))?)?;
        self.v = ((&self.v * BETA2)? + (g.sqr()? * (1.0 - BETA2))?)?;
        let m_hat = (&self.m / c1)?;
        let v_hat = (&self.v / c2)?;
        let step = ((m_hat / (v_hat.sqrt()? + ADAM_EPSILON)?)? * self.lr)?;
        net::descend(params, &step)
    }
}

/// The layers' parameters: weight (in x out) then bias, layer by layer.
fn forward<'a>(
    params: impl ExactSizeIterator<Item = &'a Tensor>,
    x: &Tensor,
) -> candle_core::Result<Tensor> {
    let layers = params.len() / 2;
    let mut h = x.clone();
    let mut params = params;
    for l in 0..layers {
        let (w, b) = (params.next(), params.next());
        let (Some(w), Some(b)) = (w, b) else {
            unreachable!("a weight and a bias per layer");
        };
        let hw = h.matmul(w)?;
        // The bias copied to every row: adding two contiguous tensors is
        // several times faster in candle than `broadcast_add`, same sums.
        h = (&hw + b.broadcast_as(hw.shape())?.contiguous()?)?;
        if l + 1 < layers {
            h = h.relu()?;
        }
    }
    Ok(h)
}

/// The agent's Double DQN (or ensemble of heads on one torso).
#[derive(Debug)]
pub struct Dqn {
    settings: DqnSettings,
    gamma: f64,
    width: usize,
    heads: usize,
    params: Vec<Var>,
    target: Vec<Tensor>,
    adam: Adam,
    replay: Replay,
    rng: AgentRng,
    /// The own kick being learned, and a shared episode's.
    open: Option<Open>,
    /// Own decisions learned: the epsilon schedule's clock.
    decisions: u64,
    /// Transitions stored, own and shared: the training clock.
    stored: u64,
    /// Gradient steps taken.
    updates: u64,
    /// The last input valued and every head's outputs there.
    cache: Option<(Features, Vec<f32>)>,
}

impl Dqn {
    /// A DQN of `settings` over `inputs` numbers of its observation set
    /// (its [`width`](ObservationSet::width) in the agent's team),
    /// discounting by `gamma` per frame, its weights and draws seeded by
    /// `seed`.
    pub fn new(settings: &DqnSettings, gamma: f64, inputs: usize, seed: u64) -> Self {
        single_threaded_products();
        let mut rng = AgentRng::seed_from_u64(seed);
        let width = inputs;
        let heads = settings.heads.max(1) as usize;
        let params = Self::initial(settings, width, heads, &mut rng);
        let target: candle_core::Result<Vec<Tensor>> =
            params.iter().map(|p| p.as_tensor().copy()).collect();
        Self {
            adam: Adam::new(settings.lr, &params).expect("zeros of its parameters' shapes"),
            target: target.unwrap_or_else(|e| panic!("{}", fault(e))),
            params,
            replay: Replay::new(settings.replay as usize),
            rng,
            settings: settings.clone(),
            gamma,
            width,
            heads,
            open: None,
            decisions: 0,
            stored: 0,
            updates: 0,
            cache: None,
        }
    }

    /// Its network's parameters, drawn from `rng` ([`net::layers`]).
    fn initial(settings: &DqnSettings, width: usize, heads: usize, rng: &mut AgentRng) -> Vec<Var> {
        let mut sizes = vec![width];
        sizes.extend(settings.hidden.iter().map(|&w| w as usize));
        sizes.push(heads * KICKS.len());
        net::layers(&sizes, rng)
    }

    /// The online network's parameters.
    fn online(&self) -> impl ExactSizeIterator<Item = &Tensor> {
        self.params.iter().map(Var::as_tensor)
    }

    /// Whether it has taken a gradient step: its values mean something.
    fn trained(&self) -> bool {
        self.updates > 0
    }

    /// What the network reads of `at`: the paper's six features, or HFO's;
    /// none where it reads HFO's and `at` has not as many (the state of an
    /// asker whose observations do not carry them).
    fn input(&self, at: Seen<'_>) -> Option<Features> {
        match self.settings.observation {
            ObservationSet::Paper => Features::from_f64(at.state),
            ObservationSet::Hfo => {
                Features::new(at.features).filter(|_| at.features.len() == self.width)
            }
        }
    }

    /// Every head's four kick values for input `x`, head by head.
    fn outputs(&mut self, x: &Features) -> Vec<f32> {
        if let Some((_, out)) = self.cache.as_ref().filter(|(k, _)| same_bits(k, x)) {
            return out.clone();
        }
        let x_tensor = Tensor::from_slice(x.as_slice(), (1, self.width), &Device::Cpu);
        let out = x_tensor
            .and_then(|x| forward(self.online(), &x))
            .and_then(|y| y.flatten_all()?.to_vec1::<f32>())
            .unwrap_or_else(|e| panic!("{}", fault(e)));
        self.cache = Some((*x, out.clone()));
        out
    }

    /// The exploration probability of its next decision.
    fn epsilon(&self) -> f64 {
        let s = &self.settings;
        if self.decisions >= s.epsilon_decay {
            return s.epsilon_end;
        }
        let f = self.decisions as f64 / s.epsilon_decay as f64;
        s.epsilon_start + f * (s.epsilon_end - s.epsilon_start)
    }

    /// Which heads learn the next transition (at least one).
    fn mask(&mut self) -> u16 {
        if self.heads == 1 {
            return 1;
        }
        let p = self.settings.mask_probability;
        let mut mask = (0..self.heads).fold(0u16, |m, k| {
            let learns = p >= 1.0 || self.rng.random::<f64>() < p;
            m | u16::from(learns) << k
        });
        if mask == 0 {
            mask = 1 << self.rng.random_range(0..self.heads);
        }
        mask
    }

    /// Folds one frame of an episode into `open`, storing the decision it
    /// closes; whether it closed one.
    fn fold(&mut self, open: &mut Option<Open>, experience: Experience<'_>) -> bool {
        let Some((kick, next)) = self.close(open, experience) else {
            return false;
        };
        let mask = self.mask();
        self.replay.push(&Decision {
            state: &kick.state,
            slot: kick.slot,
            reward: kick.reward,
            discount: if next.is_some() { kick.discount } else { 0.0 },
            next: next.as_ref().map(Features::as_slice),
            mask,
        });
        self.stored += 1;
        let s = &self.settings;
        let ready = self.replay.len() as u64 >= s.warmup.max(u64::from(s.batch));
        if ready && self.stored.is_multiple_of(s.train_every) {
            let batch = self.sample();
            self.train(batch).unwrap_or_else(|e| panic!("{}", fault(e)));
        }
        true
    }

    /// Folds one frame of an episode into `open`: the decision it closes,
    /// with the next decision's input (none at the episode's end), if it
    /// closes one. A kick whose input it cannot read (a shared state
    /// without HFO's features) is not learned.
    fn close(
        &self,
        open: &mut Option<Open>,
        experience: Experience<'_>,
    ) -> Option<(Open, Option<Features>)> {
        let (from, reward, next) = experience;
        if let Some(slot) = kick_slot(from.action) {
            *open = self.input(from.at).map(|x| Open {
                state: x.as_slice().to_vec(),
                slot,
                reward: 0.0,
                discount: 1.0,
            });
        }
        let Some(kick) = open.as_mut() else {
            return None; // moving before its first kick of the episode
        };
        kick.fold(reward, self.gamma);
        let next = match next {
            None => None,
            Some(n) if n.action.is_kick() => match self.input(n.at) {
                Some(x) => Some(x),
                None => {
                    *open = None;
                    return None;
                }
            },
            Some(_) => return None,
        };
        open.take().map(|kick| (kick, next))
    }

    /// A batch drawn from the replay.
    fn sample(&mut self) -> Batch {
        let mut batch = Batch::with_capacity(self.settings.batch as usize, self.width, self.heads);
        let (w, r) = (self.width, &self.replay);
        for _ in 0..self.settings.batch {
            let i = self.rng.random_range(0..r.len());
            batch.push(
                &r.state[i * w..(i + 1) * w],
                &r.next_state[i * w..(i + 1) * w],
                r.action[i],
                (r.reward[i], r.discount[i]),
                r.mask[i],
            );
        }
        batch
    }

    /// One gradient step on `batch`, then the target's copy when it is due.
    fn train(&mut self, batch: Batch) -> candle_core::Result<()> {
        let w = self.width;
        let Batch {
            heads: k,
            n,
            s,
            s2,
            a,
            rew,
            disc,
            mask,
        } = batch;
        let cpu = &Device::Cpu;
        let s = Tensor::from_vec(s, (n, w), cpu)?;
        let s2 = Tensor::from_vec(s2, (n, w), cpu)?;
        let a = Tensor::from_vec(a, (n, k, 1), cpu)?;
        let rew = Tensor::from_vec(rew, (n, 1), cpu)?;
        let disc = Tensor::from_vec(disc, (n, 1), cpu)?;
        let mask = Tensor::from_vec(mask, (n, k), cpu)?;
        let kicks = KICKS.len();
        // Double DQN: the online network picks the next action, the target values it.
        let best = forward(self.online(), &s2)?
            .detach()
            .reshape((n, k, kicks))?
            .argmax_keepdim(D::Minus1)?;
        let ahead = forward(self.target.iter(), &s2)?
            .reshape((n, k, kicks))?
            .gather(&best, D::Minus1)?
            .squeeze(D::Minus1)?;
        let y = ahead.broadcast_mul(&disc)?.broadcast_add(&rew)?.detach();
        let q = forward(self.online(), &s)?
            .reshape((n, k, kicks))?
            .gather(&a, D::Minus1)?
            .squeeze(D::Minus1)?;
        // Huber (delta 1): c^2 / 2 + (|d| - c), c = min(|d|, 1).
        let d = (q - y)?.abs()?;
        let c = d.clamp(0f32, 1f32)?;
        let huber = ((c.sqr()? * 0.5)? + (d - &c)?)?;
        let loss = ((huber * mask)?.sum_all()? / (n * k) as f64)?;
        let grads = loss.backward()?;
        self.adam.step(&self.params, &grads)?;
        self.updates += 1;
        self.cache = None;
        if self.updates.is_multiple_of(self.settings.target_every) {
            self.target = (self.params.iter())
                .map(|p| p.as_tensor().copy())
                .collect::<candle_core::Result<_>>()?;
        }
        Ok(())
    }

    /// Its state for a snapshot.
    fn saved(&self) -> candle_core::Result<Saved> {
        Ok(Saved {
            tag: STATE_TAG.into(),
            version: STATE_VERSION,
            observation: self.settings.observation,
            shape: self.shape(),
            params: net::lists(self.online())?,
            target: net::lists(self.target.iter())?,
            adam_m: net::flat_lists(&self.adam.m, &self.params)?,
            adam_v: net::flat_lists(&self.adam.v, &self.params)?,
            adam_t: self.adam.t,
            decisions: self.decisions,
            stored: self.stored,
            updates: self.updates,
            replay: self.replay.clone(),
            rng: self.rng.clone(),
        })
    }

    /// What a saved state must match: the layer sizes.
    fn shape(&self) -> Vec<u32> {
        let mut sizes = vec![self.width as u32];
        sizes.extend(&self.settings.hidden);
        sizes.push((self.heads * KICKS.len()) as u32);
        sizes
    }

    /// Takes `saved` as its state once it checked it fits.
    fn load(&mut self, saved: Saved) -> Result<(), String> {
        let (theirs, ours) = (saved.observation, self.settings.observation);
        if theirs != ours {
            return Err(format!(
                "the snapshot's DQN reads observation `{}` ({} inputs), this agent's reads `{}` \
                 ({} inputs): load it into an agent of observation = \"{}\"",
                theirs.name(),
                saved.shape.first().copied().unwrap_or_default(),
                ours.name(),
                self.width,
                theirs.name()
            ));
        }
        if saved.shape != self.shape() {
            return Err(format!(
                "the snapshot's network has layers {:?} (inputs, hidden, heads x 4 kicks), \
                 this agent's {:?}",
                saved.shape,
                self.shape()
            ));
        }
        if saved.replay.capacity != self.replay.capacity {
            return Err(format!(
                "the snapshot's replay holds {} transitions, this agent's `replay` is {}",
                saved.replay.capacity, self.replay.capacity
            ));
        }
        if !saved.replay.consistent(self.width, self.heads) {
            return Err("the snapshot's replay buffer is inconsistent".into());
        }
        let tensors = |lists, what| net::tensors(lists, &self.params, what);
        let params = tensors(saved.params, "network")?;
        let target = tensors(saved.target, "target network")?;
        let m = tensors(saved.adam_m, "optimiser state")?;
        let v = tensors(saved.adam_v, "optimiser state")?;
        for (var, value) in self.params.iter().zip(&params) {
            var.set(value).map_err(fault)?;
        }
        self.target = target;
        self.adam.m = flat(&m).map_err(fault)?;
        self.adam.v = flat(&v).map_err(fault)?;
        self.adam.t = saved.adam_t;
        self.decisions = saved.decisions;
        self.stored = saved.stored;
        self.updates = saved.updates;
        self.replay = saved.replay;
        self.rng = saved.rng;
        self.open = None;
        self.cache = None;
        Ok(())
    }
}

/// A DQN's snapshot bytes (postcard): everything it learns and draws from,
/// so that a restored agent goes on as the saved one would have.
#[derive(Serialize, Deserialize)]
struct Saved {
    tag: String,
    version: u16,
    observation: ObservationSet,
    shape: Vec<u32>,
    params: Vec<Vec<f32>>,
    target: Vec<Vec<f32>>,
    adam_m: Vec<Vec<f32>>,
    adam_v: Vec<Vec<f32>>,
    adam_t: u64,
    decisions: u64,
    stored: u64,
    updates: u64,
    replay: Replay,
    rng: AgentRng,
}

impl Learner for Dqn {
    /// The heads' mean of each kick action, every kick learned once it has
    /// taken a gradient step; nothing learned before (Move never is).
    /// None where it cannot read `at` (see [`Dqn::input`]).
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        let Some(x) = self.input(at).filter(|_| self.trained()) else {
            return ActionValues::default();
        };
        let out = self.outputs(&x);
        let mut values = ActionValues {
            learned: ALL_KICKS,
            ..ActionValues::default()
        };
        for (slot, action) in KICKS.iter().enumerate() {
            let sum: f64 = (0..self.heads)
                .map(|h| f64::from(out[h * KICKS.len() + slot]))
                .sum();
            values.q[action.index()] = sum / self.heads as f64;
        }
        values
    }

    /// Epsilon-greedy on its values with the schedule's epsilon (the
    /// exploration draw and greedy ties as SARSA's).
    fn choose(&mut self, at: Seen<'_>, rng: &mut AgentRng) -> Action {
        let q = self.values(at).q;
        epsilon_greedy(&q, self.epsilon(), rng)
    }

    fn learn(&mut self, experience: Experience<'_>) {
        let mut open = self.open.take();
        if self.fold(&mut open, experience) {
            self.decisions += 1;
        }
        self.open = open;
    }

    fn end_episode(&mut self) {
        self.open = None;
    }

    /// A teammate's goal episode, folded from kick to kick as its own and
    /// stored in its replay (not counted as its decisions).
    fn replay(&mut self, episode: &[Experience<'_>]) {
        let mut open = None;
        for &experience in episode {
            self.fold(&mut open, experience);
        }
    }

    /// A teammate's experience, folded from kick to kick as a shared
    /// episode is (its transitions read in order as steps of the sender's
    /// episodes), learned by one gradient step on exactly the decisions it
    /// closes, every head on each; nothing stored in its replay, no draw
    /// made. False if it closes none it can read.
    fn learn_batch(&mut self, batch: &[Experience<'_>]) -> bool {
        let mut open = None;
        let decisions: Vec<(Open, Option<Features>)> = (batch.iter())
            .filter_map(|&experience| self.close(&mut open, experience))
            .collect();
        if decisions.is_empty() {
            return false;
        }
        let (w, heads) = (self.width, self.heads);
        let every_head = u16::MAX >> (16 - heads);
        let zeros = vec![0.0; w];
        let mut laid = Batch::with_capacity(decisions.len(), w, heads);
        for (kick, next) in &decisions {
            let discount = if next.is_some() { kick.discount } else { 0.0 };
            let s2 = next.as_ref().map_or(&zeros[..], Features::as_slice);
            let (reward, discount) = (kick.reward as f32, discount as f32);
            laid.push(
                &kick.state,
                s2,
                kick.slot as u8,
                (reward, discount),
                every_head,
            );
        }
        self.train(laid).unwrap_or_else(|e| panic!("{}", fault(e)));
        true
    }

    /// None: it keeps its network itself ([`save_state`](Learner::save_state)).
    fn table(&self) -> Option<Vec<ActionValues>> {
        None
    }

    fn restore(&mut self, _values: Vec<ActionValues>) -> Result<(), String> {
        Err(
            "the snapshot holds a Q-table (learner sarsa or ensemble), not a DQN's network: \
             load a snapshot saved by a dqn agent"
                .into(),
        )
    }

    fn save_state(&self) -> Option<Vec<u8>> {
        let saved = self.saved().unwrap_or_else(|e| panic!("{}", fault(e)));
        Some(postcard::to_allocvec(&saved).expect("a DQN's state serialises"))
    }

    fn load_state(&mut self, state: &[u8]) -> Result<(), String> {
        if !holds_dqn_state(state) {
            return Err("the snapshot holds another learner's state, not a DQN's: \
                        load a snapshot saved by a dqn agent"
                .into());
        }
        if let Ok(((_, version), _)) = postcard::take_from_bytes::<(String, u16)>(state)
            && version != STATE_VERSION
        {
            return Err(format!(
                "the DQN's saved state is of version {version}, this build reads {STATE_VERSION}"
            ));
        }
        let saved: Saved =
            postcard::from_bytes(state).map_err(|e| format!("the DQN's saved state: {e}"))?;
        self.load(saved)
    }

    /// The mean over the kick actions of the heads' variance there;
    /// infinite before it trained; none for a single head or where it
    /// cannot read `at`.
    fn uncertainty(&mut self, at: Seen<'_>) -> Option<f64> {
        let x = self.input(at).filter(|_| self.heads >= 2)?;
        if !self.trained() {
            return Some(f64::INFINITY);
        }
        let out = self.outputs(&x);
        let k = self.heads as f64;
        let variance = |slot: usize| {
            let each = (0..self.heads).map(|h| f64::from(out[h * KICKS.len() + slot]));
            let mean = each.clone().sum::<f64>() / k;
            each.map(|q| (q - mean).powi(2)).sum::<f64>() / k
        };
        Some((0..KICKS.len()).map(variance).sum::<f64>() / KICKS.len() as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::learner::Step;
    use Action::*;
    use proto::State;

    /// Small and quick to train.
    fn small() -> DqnSettings {
        DqnSettings {
            hidden: vec![16],
            lr: 1e-2,
            batch: 8,
            replay: 500,
            warmup: 16,
            target_every: 10,
            epsilon_decay: 0,
            epsilon_end: 0.2,
            ..DqnSettings::default()
        }
    }

    fn step(state: &State, action: Action) -> Step<'_> {
        Step {
            at: Seen {
                state,
                features: &[],
                index: None,
            },
            action,
        }
    }

    const A: State = [0.5, -0.5, 0.0, 0.2, 0.1, -0.3];
    const B: State = [-0.5, 0.5, 0.3, -0.2, 0.0, 0.6];

    /// A one-step bandit: in A Shoot pays 1, in B PassFar does; every other
    /// kick pays 0. Episodes of one decision, the learner's own choices.
    fn bandit(dqn: &mut Dqn, episodes: usize, rng: &mut AgentRng) {
        for e in 0..episodes {
            let (state, best) = if e % 2 == 0 {
                (&A, Shoot)
            } else {
                (&B, PassFar)
            };
            let at = Seen {
                state,
                features: &[],
                index: None,
            };
            let action = dqn.choose(at, rng);
            let reward = if action == best { 1.0 } else { 0.0 };
            dqn.learn((step(state, action), reward, None));
            dqn.end_episode();
        }
    }

    fn bits(values: ActionValues) -> [u64; 5] {
        values.q.map(f64::to_bits)
    }

    #[test]
    fn it_learns_a_one_step_bandit_and_knows_nothing_before() {
        let mut dqn = Dqn::new(&small(), 0.9, 6, 7);
        let at = |state| Seen {
            state,
            features: &[],
            index: None,
        };
        assert_eq!(dqn.values(at(&A)), ActionValues::default());
        let mut rng = AgentRng::seed_from_u64(1);
        bandit(&mut dqn, 600, &mut rng);
        let (a, b) = (dqn.values(at(&A)), dqn.values(at(&B)));
        assert_eq!(a.learned, ALL_KICKS);
        assert_eq!(crate::selection::greedy_first(&a.q), Shoot, "{a:?}");
        assert_eq!(crate::selection::greedy_first(&b.q), PassFar, "{b:?}");
        assert!((a.q[Shoot.index()] - 1.0).abs() < 0.2, "{a:?}");
        assert!(a.kick_spread() > 0.5, "{a:?}");
    }

    #[test]
    fn moves_fold_into_the_kick_before_them() {
        let settings = DqnSettings {
            warmup: 1000,
            ..small()
        };
        let mut dqn = Dqn::new(&settings, 0.5, 6, 1);
        // Kick, two moves, a kick, a move, the end.
        dqn.learn((step(&A, Dribble), 1.0, Some(step(&B, Move))));
        dqn.learn((step(&B, Move), 2.0, Some(step(&B, Move))));
        dqn.learn((step(&B, Move), 4.0, Some(step(&A, PassNear))));
        dqn.learn((step(&A, PassNear), 8.0, Some(step(&A, Move))));
        dqn.learn((step(&A, Move), 16.0, None));
        let r = &dqn.replay;
        assert_eq!(r.len(), 2);
        assert_eq!(r.action, [1, 2]);
        // 1 + 0.5 * 2 + 0.25 * 4 = 3, then 0.125 to the next kick.
        assert_eq!(r.reward, [3.0, 16.0]);
        assert_eq!(r.discount, [0.125, 0.0]);
        assert_eq!(r.state[..6], A.map(|x| x as f32));
        assert_eq!(r.next_state[..6], A.map(|x| x as f32));
        assert_eq!(r.next_state[6..], [0.0; 6]);
        assert_eq!(dqn.decisions, 2);
        // Moves before any kick teach nothing.
        dqn.learn((step(&A, Move), 1.0, None));
        assert_eq!(dqn.replay.len(), 2);
    }

    #[test]
    fn a_batch_is_one_gradient_step_kept_out_of_the_replay() {
        let mut dqn = Dqn::new(&small(), 0.9, 6, 5);
        bandit(&mut dqn, 100, &mut AgentRng::seed_from_u64(4));
        let at = Seen {
            state: &A,
            features: &[],
            index: None,
        };
        let before = dqn.values(at);
        let (stored, updates, length, rng) =
            (dqn.stored, dqn.updates, dqn.replay.len(), dqn.rng.clone());
        // In A, PassNear pays 5 (a kick, two moves folded in, the end).
        let batch = [
            (step(&A, PassNear), 1.0, Some(step(&B, Move))),
            (step(&B, Move), 4.0, None),
        ];
        assert!(dqn.learn_batch(&batch));
        let after = dqn.values(at);
        assert!(
            after.q[PassNear.index()] > before.q[PassNear.index()],
            "{before:?} -> {after:?}"
        );
        assert_eq!((dqn.stored, dqn.updates), (stored, updates + 1));
        assert_eq!(dqn.replay.len(), length);
        assert_eq!(dqn.rng, rng, "no draw");
        // Moves alone close no decision: nothing to learn.
        assert!(!dqn.learn_batch(&[(step(&B, Move), 1.0, None)]));
        assert_eq!(dqn.updates, updates + 1);
    }

    #[test]
    fn adams_moments_keep_no_step_graph() {
        let mut dqn = Dqn::new(&small(), 0.9, 6, 3);
        bandit(&mut dqn, 50, &mut AgentRng::seed_from_u64(2));
        assert!(dqn.trained());
        // A graph in a moment would chain every gradient step's to it.
        assert!(!dqn.adam.m.track_op() && !dqn.adam.v.track_op());
    }

    #[test]
    fn a_seed_gives_the_same_bits_and_another_seed_others() {
        let run = |seed| {
            let mut dqn = Dqn::new(&small(), 0.9, 6, seed);
            bandit(&mut dqn, 200, &mut AgentRng::seed_from_u64(3));
            (
                bits(dqn.values(Seen {
                    state: &A,
                    features: &[],
                    index: None,
                })),
                dqn.save_state(),
            )
        };
        assert_eq!(run(5), run(5));
        assert_ne!(run(5).0, run(6).0);
    }

    #[test]
    fn a_snapshot_goes_on_as_the_saved_learner_would() {
        let settings = DqnSettings {
            heads: 3,
            ..small()
        };
        let mut saved = Dqn::new(&settings, 0.9, 6, 11);
        bandit(&mut saved, 100, &mut AgentRng::seed_from_u64(4));
        let bytes = saved.save_state().unwrap();
        let mut loaded = Dqn::new(&settings, 0.9, 6, 99);
        loaded.load_state(&bytes).unwrap();
        assert_eq!(loaded.save_state().unwrap(), bytes);
        for dqn in [&mut saved, &mut loaded] {
            bandit(dqn, 50, &mut AgentRng::seed_from_u64(8));
        }
        let at = Seen {
            state: &B,
            features: &[],
            index: None,
        };
        assert_eq!(bits(saved.values(at)), bits(loaded.values(at)));
        assert_eq!(saved.uncertainty(at), loaded.uncertainty(at));
        assert_eq!(saved.save_state(), loaded.save_state());
    }

    #[test]
    fn another_learners_snapshot_is_refused() {
        let mut dqn = Dqn::new(&small(), 0.9, 6, 1);
        let table = dqn.restore(vec![ActionValues::default()]).unwrap_err();
        assert!(table.contains("Q-table"), "{table}");
        let other = dqn.load_state(b"\x93NUMPY weights").unwrap_err();
        assert!(other.contains("another learner's state"), "{other}");
        let wider = Dqn::new(
            &DqnSettings {
                hidden: vec![32],
                ..small()
            },
            0.9,
            6,
            1,
        );
        let shape = dqn.load_state(&wider.save_state().unwrap()).unwrap_err();
        assert!(shape.contains("layers [6, 32, 4]"), "{shape}");
        let mut cut = wider.save_state().unwrap();
        cut.truncate(cut.len() / 2);
        assert!(dqn.load_state(&cut).is_err());
    }

    #[test]
    fn an_ensembles_uncertainty_shrinks_where_it_learned() {
        let settings = DqnSettings {
            heads: 5,
            ..small()
        };
        let mut dqn = Dqn::new(&settings, 0.9, 6, 2);
        let at = Seen {
            state: &A,
            features: &[],
            index: None,
        };
        assert_eq!(dqn.uncertainty(at), Some(f64::INFINITY));
        assert_eq!(Dqn::new(&small(), 0.9, 6, 2).uncertainty(at), None);
        let mut seen = Vec::new();
        for e in 0..400 {
            let action = KICKS[e % 4];
            let reward = if action == Shoot { 1.0 } else { -1.0 };
            dqn.learn((step(&A, action), reward, None));
            if [20, 399].contains(&e) {
                seen.push(dqn.uncertainty(at).unwrap());
            }
        }
        assert!(seen[1] < seen[0] / 10.0, "{seen:?}");
    }

    /// HFO's features of three attackers, scaled by `v`.
    fn hfo_features(v: f32) -> Vec<f32> {
        (0..27).map(|i| v * (i as f32 + 1.0) / 27.0).collect()
    }

    fn hfo_small() -> DqnSettings {
        DqnSettings {
            observation: ObservationSet::Hfo,
            ..small()
        }
    }

    #[test]
    fn an_hfo_network_reads_hfos_features_and_not_the_papers() {
        let width = ObservationSet::Hfo.width(3);
        let mut dqn = Dqn::new(&hfo_small(), 0.9, width, 7);
        assert_eq!((width, dqn.shape()[0]), (27, 27), "its first layer");
        // One paper state, two feature vectors: Shoot pays in the first,
        // PassFar in the second.
        let (fa, fb) = (hfo_features(0.5), hfo_features(-0.5));
        let at = |features| Seen {
            state: &A,
            features,
            index: None,
        };
        // A paper network of the same seed learns the same experience.
        let mut paper = Dqn::new(&small(), 0.9, 6, 7);
        let mut rng = AgentRng::seed_from_u64(1);
        for e in 0..600 {
            let (features, best) = if e % 2 == 0 {
                (&fa[..], Shoot)
            } else {
                (&fb[..], PassFar)
            };
            let action = dqn.choose(at(features), &mut rng);
            let reward = if action == best { 1.0 } else { 0.0 };
            for learner in [&mut dqn, &mut paper] {
                let step = Step {
                    at: at(features),
                    action,
                };
                learner.learn((step, reward, None));
                learner.end_episode();
            }
        }
        let (a, b) = (dqn.values(at(&fa)), dqn.values(at(&fb)));
        assert_eq!(crate::selection::greedy_first(&a.q), Shoot, "{a:?}");
        assert_eq!(crate::selection::greedy_first(&b.q), PassFar, "{b:?}");
        // The paper's state changes nothing; without features it knows nothing.
        let elsewhere = Seen {
            state: &B,
            ..at(&fa)
        };
        assert_eq!(bits(dqn.values(elsewhere)), bits(a));
        // The paper network cannot tell the two apart.
        assert_eq!(bits(paper.values(at(&fa))), bits(paper.values(at(&fb))));
        assert_ne!(bits(paper.values(at(&fa))), bits(a));
        assert_eq!(dqn.values(at(&[])), ActionValues::default());
        assert_eq!(dqn.values(at(&fa[..26])), ActionValues::default());
        // A kick without features is not learned.
        let stored = dqn.replay.len();
        dqn.learn((step(&A, Shoot), 1.0, None));
        assert_eq!(dqn.replay.len(), stored);
    }

    #[test]
    fn a_snapshot_of_another_observation_or_version_is_refused() {
        let hfo = Dqn::new(&hfo_small(), 0.9, 27, 1).save_state().unwrap();
        let mut paper = Dqn::new(&small(), 0.9, 6, 1);
        assert_eq!(
            paper.load_state(&hfo).unwrap_err(),
            "the snapshot's DQN reads observation `hfo` (27 inputs), this agent's reads `paper` \
             (6 inputs): load it into an agent of observation = \"hfo\""
        );
        let mut back = Dqn::new(&hfo_small(), 0.9, 27, 2);
        let e = back.load_state(&paper.save_state().unwrap()).unwrap_err();
        assert!(e.starts_with("the snapshot's DQN reads observation `paper` (6 inputs), this agent's reads `hfo` (27 inputs)"), "{e}");
        back.load_state(&hfo).unwrap();
        // Version 1 (before the observation was recorded) says so.
        let tag = STATE_TAG.len() + 1;
        let mut old = hfo.clone();
        assert_eq!(old[tag], 2);
        old[tag] = 1;
        assert_eq!(
            back.load_state(&old).unwrap_err(),
            "the DQN's saved state is of version 1, this build reads 2"
        );
    }
}
