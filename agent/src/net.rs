//! What the networks share: the DQN's ([`crate::dqn`]), advice
//! imitation's behavioural cloning ([`crate::cloning`]) and EF-OnTL's
//! sars-RND ([`crate::rnd`]). MLPs of candle tensors whose products run on
//! one thread (the DQN has its own forward pass, with a cache).

use std::sync::Once;

use candle_core::backprop::GradStore;
use candle_core::{Device, Tensor, Var};
use rand::Rng;

use crate::selection::AgentRng;

/// Turns off the threading of the matrix products candle's CPU backend
/// runs (the `gemm` crate's, above a size): a DQN's products are small, a
/// study already runs its runs on its threads, and one thread per product
/// keeps every sum in one order.
pub(crate) fn single_threaded_products() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| gemm_common::gemm::set_threading_threshold(usize::MAX));
}

/// `tensors` flattened and laid end to end.
pub(crate) fn flat(tensors: &[Tensor]) -> candle_core::Result<Tensor> {
    let each = tensors.iter().map(Tensor::flatten_all);
    Tensor::cat(&each.collect::<candle_core::Result<Vec<_>>>()?, 0)
}

/// The parts of `flat` in the shapes of `params`, in their order.
pub(crate) fn parts(flat: &Tensor, params: &[Var]) -> candle_core::Result<Vec<Tensor>> {
    let mut at = 0;
    let mut parts = Vec::with_capacity(params.len());
    for p in params {
        parts.push(flat.narrow(0, at, p.elem_count())?.reshape(p.shape())?);
        at += p.elem_count();
    }
    Ok(parts)
}

/// The layers from `sizes[0]` inputs through `sizes[1..]`, each a weight
/// (in x out) then a bias, drawn from `rng` as PyTorch's `nn.Linear`
/// initialises them (uniform in +-1/sqrt(fan_in)), in the DQN's order.
pub(crate) fn layers(sizes: &[usize], rng: &mut AgentRng) -> Vec<Var> {
    let mut params = Vec::with_capacity(2 * sizes.len().saturating_sub(1));
    for pair in sizes.windows(2) {
        let (fan_in, out) = (pair[0], pair[1]);
        let bound = 1.0 / (fan_in as f32).sqrt();
        let mut draw = |n: usize| -> Vec<f32> {
            (0..n)
                .map(|_| (rng.random::<f32>() * 2.0 - 1.0) * bound)
                .collect()
        };
        let w = Var::from_vec(draw(fan_in * out), (fan_in, out), &Device::Cpu);
        let b = Var::from_vec(draw(out), out, &Device::Cpu);
        params.push(w.expect("a weight of its own shape"));
        params.push(b.expect("a bias of its own shape"));
    }
    params
}

/// The MLP of `params` (weight then bias per layer, ReLU between layers)
/// on the rows of `x`; with `masks`, one per hidden layer, each hidden
/// layer's output multiplied by its mask (dropout); without, none.
pub(crate) fn forward<'a>(
    params: impl ExactSizeIterator<Item = &'a Tensor>,
    x: &Tensor,
    masks: &[Tensor],
) -> candle_core::Result<Tensor> {
    let layers = params.len() / 2;
    let mut h = x.clone();
    let mut params = params;
    for l in 0..layers {
        let (Some(w), Some(b)) = (params.next(), params.next()) else {
            unreachable!("a weight and a bias per layer");
        };
        let hw = h.matmul(w)?;
        // As the DQN adds its biases: faster in candle than broadcast_add.
        h = (&hw + b.broadcast_as(hw.shape())?.contiguous()?)?;
        if l + 1 < layers {
            h = h.relu()?;
            if let Some(mask) = masks.get(l) {
                h = (h * mask)?;
            }
        }
    }
    Ok(h)
}

/// Every parameter's gradient in `grads`, laid end to end and detached (a
/// gradient holds its step's graph, which an optimiser's moments would
/// otherwise chain from step to step).
pub(crate) fn gradient(params: &[Var], grads: &GradStore) -> candle_core::Result<Tensor> {
    let g = (params.iter())
        .map(|p| grads.get(p.as_tensor()).cloned())
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| candle_core::Error::msg("a parameter without a gradient"))?;
    Ok(flat(&g)?.detach())
}

/// Subtracts `step`, every parameter's laid end to end, from `params`.
pub(crate) fn descend(params: &[Var], step: &Tensor) -> candle_core::Result<()> {
    for (p, step) in params.iter().zip(parts(step, params)?) {
        p.set(&(p.as_tensor() - step)?)?;
    }
    Ok(())
}

/// `tensors`' numbers, one list each, for a snapshot.
pub(crate) fn lists<'a>(
    tensors: impl Iterator<Item = &'a Tensor>,
) -> candle_core::Result<Vec<Vec<f32>>> {
    tensors.map(|t| t.flatten_all()?.to_vec1::<f32>()).collect()
}

/// A flat tensor (an optimiser's moments) as lists in the shapes of `params`.
pub(crate) fn flat_lists(flat: &Tensor, params: &[Var]) -> candle_core::Result<Vec<Vec<f32>>> {
    lists(parts(flat, params)?.iter())
}

/// `lists` as tensors of the shapes of `params`, refused unless there are
/// as many, each of its size and finite; `what` names them in the error.
pub(crate) fn tensors(
    lists: Vec<Vec<f32>>,
    params: &[Var],
    what: &str,
) -> Result<Vec<Tensor>, String> {
    if lists.len() != params.len() {
        return Err(format!("the snapshot's {what} has {} tensors", lists.len()));
    }
    (lists.into_iter().zip(params))
        .map(|(values, p)| {
            if values.iter().any(|x| !x.is_finite()) {
                return Err(format!("the snapshot's {what} holds a non-finite number"));
            }
            Tensor::from_vec(values, p.shape(), &Device::Cpu)
                .map_err(|e| format!("the snapshot's {what}: {e}"))
        })
        .collect()
}

/// Whether `state` starts with `tag` and `version`, as every snapshot of
/// these networks does; why not if not.
pub(crate) fn check_header(state: &[u8], tag: &str, version: u16) -> Result<(), String> {
    match postcard::take_from_bytes::<(String, u16)>(state) {
        Ok(((t, _), _)) if t != tag => Err(format!("not a {tag} state (it is a {t} state)")),
        Ok(((_, v), _)) if v != version => Err(format!(
            "the {tag} state is of version {v}, this build reads {version}"
        )),
        Ok(_) => Ok(()),
        Err(_) => Err(format!("not a {tag} state")),
    }
}
