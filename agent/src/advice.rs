//! The formulas of the advising strategies (docs/algorithms.md 2-3): asking and
//! giving probabilities, confidence functions, the reachable set and the
//! EpisodeSharing budget split.

use serde::{Deserialize, Serialize};

use crate::config_error::{AgentConfigError, require_non_negative};

/// The reachable set G(s): whom an ad hoc advisee asks.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reachable {
    /// Every other agent of the team, in id order.
    #[default]
    Everyone,
    /// These agent ids, in the given order (the asking agent itself is skipped).
    Agents(Vec<usize>),
    /// Teammates whose field position is within this distance (metres):
    /// a radio range.
    WithinDistance(f64),
    /// Its two neighbours on a ring of the ids: `me - 1` and `me + 1`
    /// (modulo the team size).
    Ring,
    /// A star around the hub of this id: the hub asks everyone, the others
    /// only the hub.
    Star(usize),
}

/// The paper's budget of every advising and sharing side.
pub(crate) const PAPER_BUDGET: u64 = 1000;

impl Reachable {
    /// A radio range must be finite and >= 0.
    pub(crate) fn validate(&self) -> Result<(), AgentConfigError> {
        match *self {
            Reachable::WithinDistance(d) => require_non_negative("reachable", d),
            _ => Ok(()),
        }
    }
}

/// P_ask(s) = (1 + v_a)^(-sqrt(n(s))); 1 for an unvisited state.
pub fn p_ask(visits: u64, v_a: f64) -> f64 {
    (1.0 + v_a).powf(-(visits as f64).sqrt())
}

/// P_give(s) = 1 - (1 + v_g)^(-Psi(s)).
pub fn p_give(psi: f64, v_g: f64) -> f64 {
    1.0 - (1.0 + v_g).powf(-psi)
}

/// AdHocVisit's confidence Psi(s) = log2 n(s) (for n(s) > 0).
pub fn psi_visit(visits: u64) -> f64 {
    (visits as f64).log2()
}

/// AdHocTD's confidence Psi(s) = sqrt(n(s)) * |max_a Q - min_a Q|, the spread
/// taken over the tried kick actions.
pub fn psi_td(visits: u64, spread: f64) -> f64 {
    (visits as f64).sqrt() * spread.abs()
}

/// Fills `out` with G(s) of agent `me` in a team of `team_size`: never `me`
/// itself; with [`Reachable::WithinDistance`], only agents whose position (by
/// id in `positions`) is known and close enough.
pub fn reachable_set(
    rule: &Reachable,
    me: usize,
    team_size: usize,
    positions: &[[f64; 2]],
    out: &mut Vec<usize>,
) {
    out.clear();
    match rule {
        Reachable::Everyone => out.extend((0..team_size).filter(|&j| j != me)),
        Reachable::Agents(ids) => {
            out.extend(ids.iter().copied().filter(|&j| j != me && j < team_size))
        }
        Reachable::WithinDistance(d) => {
            let Some(&[x, y]) = positions.get(me) else {
                return;
            };
            let near = |j: usize| {
                positions
                    .get(j)
                    .is_some_and(|&[u, v]| (u - x).hypot(v - y) <= *d)
            };
            out.extend((0..team_size).filter(|&j| j != me && near(j)));
        }
        Reachable::Ring => {
            let (before, after) = ((me + team_size - 1) % team_size, (me + 1) % team_size);
            out.extend([before, after].into_iter().filter(|&j| j != me));
            out.dedup();
        }
        Reachable::Star(hub) if *hub == me => out.extend((0..team_size).filter(|&j| j != me)),
        Reachable::Star(hub) => out.extend((*hub < team_size).then_some(*hub)),
    }
}

/// How many leading transitions of an episode of `len` transitions the
/// `receiver`-th of `receivers` receivers gets from a remaining budget.
///
/// Budget units go transition by transition, to each receiver in turn, so
/// transition `t` reaches receiver `k` when `t * receivers + k < budget`.
pub fn shared_prefix(len: usize, receivers: usize, receiver: usize, budget: u64) -> usize {
    let (m, k) = (receivers as u64, receiver as u64);
    if k >= budget || m == 0 {
        return 0;
    }
    let reach = (budget - k).div_ceil(m);
    usize::try_from(reach).map_or(len, |r| r.min(len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn asking_probability() {
        // v_a = 0.5: 1.5^(-sqrt n).
        assert_eq!(p_ask(0, 0.5), 1.0); // 1.5^0
        assert!(close(p_ask(1, 0.5), 2.0 / 3.0)); // 1.5^-1
        assert!(close(p_ask(4, 0.5), 1.0 / 2.25)); // 1.5^-2 = 0.444..
        assert!(close(p_ask(9, 0.5), 1.0 / 3.375)); // 1.5^-3 = 0.296..
    }

    #[test]
    fn giving_probability_visit_based() {
        // v_g = 0.5, Psi = log2 n.
        assert_eq!(p_give(psi_visit(1), 0.5), 0.0); // log2 1 = 0 -> 1 - 1
        assert!(close(p_give(psi_visit(4), 0.5), 1.0 - 1.0 / 2.25)); // Psi 2 -> 0.555..
        assert!(close(p_give(psi_visit(8), 0.5), 1.0 - 1.0 / 3.375)); // Psi 3 -> 0.7037..
    }

    #[test]
    fn giving_probability_td_based() {
        // v_g = 1.5, Psi = sqrt n * spread.
        assert!(close(p_give(psi_td(4, 0.5), 1.5), 0.6)); // Psi 2 * 0.5 = 1 -> 1 - 1/2.5
        assert!(close(p_give(psi_td(4, 1.0), 1.5), 0.84)); // Psi 2 -> 1 - 1/6.25
        assert!(close(p_give(psi_td(16, 0.25), 1.5), 0.6)); // Psi 4 * 0.25 = 1
        assert_eq!(p_give(psi_td(100, 0.0), 1.5), 0.0); // no spread, no advice
    }

    #[test]
    fn reachable_sets() {
        let mut g = Vec::new();
        reachable_set(&Reachable::Everyone, 1, 3, &[], &mut g);
        assert_eq!(g, vec![0, 2]);
        reachable_set(&Reachable::Agents(vec![2, 1, 0]), 1, 3, &[], &mut g);
        assert_eq!(g, vec![2, 0]);
        // Agent 0 at the origin: agent 1 at distance 5 (3-4-5), agent 2 at 10.
        let pos = [[0.0, 0.0], [3.0, 4.0], [10.0, 0.0]];
        reachable_set(&Reachable::WithinDistance(5.0), 0, 3, &pos, &mut g);
        assert_eq!(g, vec![1]);
        reachable_set(&Reachable::WithinDistance(5.0), 0, 3, &[], &mut g);
        assert!(g.is_empty());
        // A ring of 4: agent 0's neighbours are 3 and 1; of 2, the other once.
        reachable_set(&Reachable::Ring, 0, 4, &[], &mut g);
        assert_eq!(g, vec![3, 1]);
        reachable_set(&Reachable::Ring, 1, 2, &[], &mut g);
        assert_eq!(g, vec![0]);
        // A star around agent 1: it asks everyone, the others only it.
        reachable_set(&Reachable::Star(1), 1, 3, &[], &mut g);
        assert_eq!(g, vec![0, 2]);
        reachable_set(&Reachable::Star(1), 2, 3, &[], &mut g);
        assert_eq!(g, vec![1]);
    }

    #[test]
    fn topologies_read_as_team_files_write_them() {
        let read = |toml: &str| -> Reachable {
            #[derive(Deserialize)]
            struct Key {
                reachable: Reachable,
            }
            toml::from_str::<Key>(toml).unwrap().reachable
        };
        assert_eq!(read(r#"reachable = "ring""#), Reachable::Ring);
        assert_eq!(read("reachable = { star = 2 }"), Reachable::Star(2));
        assert_eq!(
            read("reachable = { within-distance = 20.0 }"),
            Reachable::WithinDistance(20.0)
        );
    }

    #[test]
    fn sharing_budget_goes_transition_by_transition() {
        // Budget 5, 2 receivers, 4 transitions: units t0->r0, t0->r1, t1->r0,
        // t1->r1, t2->r0: receiver 0 gets 3, receiver 1 gets 2.
        assert_eq!(shared_prefix(4, 2, 0, 5), 3);
        assert_eq!(shared_prefix(4, 2, 1, 5), 2);
        // Plenty of budget: the whole episode; none left: nothing.
        assert_eq!(shared_prefix(4, 2, 1, 1000), 4);
        assert_eq!(shared_prefix(4, 2, 0, 0), 0);
    }

    proptest! {
        #[test]
        fn shared_units_never_exceed_the_budget(len in 0usize..300, m in 1usize..5, budget in 0u64..2000) {
            let total: usize = (0..m).map(|k| shared_prefix(len, m, k, budget)).sum();
            prop_assert_eq!(total as u64, budget.min((len * m) as u64));
        }

        #[test]
        fn probabilities_stay_in_unit_interval(n in 0u64..1_000_000, spread in 0.0f64..10.0) {
            for p in [p_ask(n, 0.5), p_give(psi_td(n, spread), 1.5), p_give(psi_visit(n.max(1)), 0.5)] {
                prop_assert!((0.0..=1.0).contains(&p));
            }
        }
    }
}
