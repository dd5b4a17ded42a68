//! EF-OnTL's transfer buffer (Castagna & Dusparic; github:acastagn/EF-OnTL
//! at `4b3e42a`, `transferBuffer.py` and `transferCoreEngine.py`;
//! research-57 §3.2-3.4): the last N transitions of an agent's own, each
//! with the uncertainty its sars-RND had of it when it learned it (stale
//! since), and the choice of the B a receiver is sent by the gap between
//! the sender's stored uncertainty and the receiver's now. The method
//! ef-ontl keeps one per agent (not in its snapshot).

use serde::{Deserialize, Serialize};

use crate::rnd::{Rnd, Sars};

/// A ring of the last `capacity` transitions, column by column.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct TransferBuffer {
    capacity: usize,
    /// A row's width: a [`Sars::row`]'s.
    width: usize,
    /// The oldest transition's place once it is full (where the next goes).
    next: usize,
    /// [`Sars::row`]s laid end to end.
    rows: Vec<f32>,
    /// gamma^k to the next decision, 0 at the episode's end (as the DQN's
    /// replay stores it).
    discount: Vec<f32>,
    /// The owner's sars-RND uncertainty when it learned the row.
    uncertainty: Vec<f64>,
}

impl TransferBuffer {
    /// An empty buffer of the last `capacity` (at least 1) transitions of
    /// states `state_width` numbers wide.
    pub(crate) fn new(capacity: usize, state_width: usize) -> Self {
        assert!(
            capacity > 0,
            "a transfer buffer holds at least one transition"
        );
        Self {
            capacity,
            width: 2 * state_width + 2,
            next: 0,
            rows: Vec::new(),
            discount: Vec::new(),
            uncertainty: Vec::new(),
        }
    }

    /// How many transitions it holds.
    pub(crate) fn len(&self) -> usize {
        self.uncertainty.len()
    }

    /// Stores a transition, its input `row` (a [`Sars::row`]), its
    /// `discount` and `uncertainty` (what [`Rnd::learn`] returned for it),
    /// dropping the oldest when full.
    pub(crate) fn push(&mut self, row: &[f32], discount: f32, uncertainty: f64) {
        assert_eq!(row.len(), self.width, "a row of the buffer's width");
        if self.len() < self.capacity {
            self.rows.extend_from_slice(row);
            self.discount.push(discount);
            self.uncertainty.push(uncertainty);
        } else {
            let i = self.next;
            self.rows[i * self.width..(i + 1) * self.width].copy_from_slice(row);
            self.discount[i] = discount;
            self.uncertainty[i] = uncertainty;
            self.next = (i + 1) % self.capacity;
        }
    }

    /// The place of the `i`th oldest transition.
    fn place(&self, i: usize) -> usize {
        (self.next + i) % self.len()
    }

    /// The `i`th oldest transition (0 the oldest) and its discount.
    pub(crate) fn get(&self, i: usize) -> (Sars<'_>, f32) {
        let at = self.place(i);
        let row = &self.rows[at * self.width..(at + 1) * self.width];
        (Sars::of(row), self.discount[at])
    }

    /// The stored uncertainty of the `i`th oldest transition.
    pub(crate) fn uncertainty(&self, i: usize) -> f64 {
        self.uncertainty[self.place(i)]
    }

    /// The mean of the stored uncertainties (the teacher choice
    /// `avg_uncertainty`, `transferBuffer.py` l.31-32); none when empty.
    pub(crate) fn mean_uncertainty(&self) -> Option<f64> {
        let n = self.len();
        (n > 0).then(|| self.uncertainty.iter().sum::<f64>() / n as f64)
    }

    /// The transitions to send `receiver`, as `get`'s indices: the first
    /// `b` in ascending order of delta = the stored uncertainty - the
    /// receiver's now, the oldest first among equals (Python's stable
    /// `sorted`); none if it holds fewer than `b`
    /// (`transfer_higher_delta_confidence`, `transferCoreEngine.py`
    /// l.68-72, 91-96). No filter on the sign of delta.
    pub(crate) fn select_by_delta(&self, receiver: &Rnd, b: usize) -> Vec<usize> {
        let n = self.len();
        if n < b || b == 0 {
            return Vec::new();
        }
        assert_eq!(
            receiver.width(),
            self.width,
            "a receiver of the same inputs"
        );
        let mut rows = Vec::with_capacity(self.rows.len());
        for i in 0..n {
            let at = self.place(i);
            rows.extend_from_slice(&self.rows[at * self.width..(at + 1) * self.width]);
        }
        let theirs = receiver.uncertainties(&rows);
        let delta: Vec<f64> = (0..n)
            .map(|i| self.uncertainty[self.place(i)] - theirs[i])
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| delta[i].total_cmp(&delta[j]));
        order.truncate(b);
        order
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rnd::RndSettings;

    fn row(v: f32) -> Vec<f32> {
        let (state, next) = ([v, -v], [v / 2.0, 0.1]);
        Sars {
            state: &state,
            slot: 2,
            reward: v,
            next: &next,
        }
        .row()
    }

    #[test]
    fn it_keeps_the_last_n_oldest_first() {
        let mut buffer = TransferBuffer::new(3, 2);
        assert!(buffer.len() == 0 && buffer.mean_uncertainty().is_none());
        for i in 1..=5 {
            buffer.push(&row(i as f32), 0.5 * i as f32, f64::from(i));
        }
        assert_eq!(buffer.len(), 3);
        let rewards: Vec<(f32, f32)> = (0..3)
            .map(|i| buffer.get(i))
            .map(|(sars, discount)| (sars.reward, discount))
            .collect();
        assert_eq!(rewards, [(3.0, 1.5), (4.0, 2.0), (5.0, 2.5)]);
        assert_eq!(buffer.get(1).0.row(), row(4.0));
        assert_eq!(buffer.mean_uncertainty(), Some(4.0));
    }

    #[test]
    fn it_selects_the_b_smallest_gaps_to_the_receivers_uncertainty() {
        let receiver = Rnd::new(&RndSettings::default(), 2, 3);
        let mut buffer = TransferBuffer::new(5, 2);
        // Two pushed first and dropped: they would have been chosen.
        for v in [0.9, 0.8] {
            buffer.push(&row(v), 1.0, -10.0);
        }
        // Stored uncertainty = the receiver's + delta.
        let delta = [0.3, -0.2, 0.0, -0.5, 0.1];
        for (i, d) in delta.iter().enumerate() {
            let x = row(i as f32 / 10.0);
            buffer.push(&x, 1.0, receiver.uncertainty(&x) + d);
        }
        assert_eq!(buffer.select_by_delta(&receiver, 2), [3, 1]);
        assert_eq!(buffer.select_by_delta(&receiver, 4), [3, 1, 2, 4]);
        assert_eq!(buffer.select_by_delta(&receiver, 5), [3, 1, 2, 4, 0]);
        assert_eq!(buffer.get(3).0.row(), row(0.3));
        assert!(buffer.select_by_delta(&receiver, 6).is_empty());
    }

    #[test]
    fn it_round_trips_through_serde() {
        let mut buffer = TransferBuffer::new(2, 2);
        for i in 0..3 {
            buffer.push(&row(i as f32), 0.9, 0.1 * f64::from(i));
        }
        let bytes = postcard::to_allocvec(&buffer).unwrap();
        assert_eq!(
            postcard::from_bytes::<TransferBuffer>(&bytes).unwrap(),
            buffer
        );
    }
}
