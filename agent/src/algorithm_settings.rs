//! An algorithm with the values of its settings: what team and study files
//! write as `algorithm` and the algorithm's own keys, handled the same way
//! for every registered method.

use std::fmt;

use serde_json::Value;

use crate::advice::Reachable;
use crate::algorithm::Algorithm;
use crate::config_error::AgentConfigError;
use crate::fidelity::{Fidelity, Profile};
use crate::method::{MethodSettings, Seat, Table};
use crate::strategy::AdvisingStrategy;

/// An algorithm and its settings (e.g. `adhoc-td` with `v_a`, `v_g`,
/// budgets...): its keys are those of its registered method's settings.
pub struct AlgorithmSettings {
    algorithm: Algorithm,
    settings: Box<dyn MethodSettings>,
}

impl AlgorithmSettings {
    /// `algorithm` with the defaults of `profile`.
    pub fn of(algorithm: Algorithm, profile: Profile) -> Self {
        Self {
            algorithm,
            settings: (algorithm.registration().defaults)(profile),
        }
    }

    /// The algorithm `name` with the paper's defaults.
    pub fn named(name: &str) -> Result<Self, crate::UnknownAlgorithm> {
        Ok(Self::of(name.parse()?, Profile::Paper))
    }

    /// Which algorithm.
    pub fn name(&self) -> Algorithm {
        self.algorithm
    }

    /// Its settings as their type (e.g. [`AdHoc`](crate::AdHoc)), if they
    /// are of type `S`.
    pub fn get<S: 'static>(&self) -> Option<&S> {
        self.settings.as_any().downcast_ref()
    }

    /// Its settings as their type, to change them.
    pub fn get_mut<S: 'static>(&mut self) -> Option<&mut S> {
        self.settings.as_any_mut().downcast_mut()
    }

    /// Every key with its value.
    pub fn settings(&self) -> serde_json::Map<String, Value> {
        self.settings.table()
    }

    /// The value of `key`, if the algorithm has it.
    pub fn setting(&self, key: &str) -> Option<Value> {
        self.settings.table().remove(key)
    }

    /// Sets `key` to `value`: an error naming the key when the algorithm
    /// does not have it or the value is not of its type.
    pub fn set(&mut self, key: &str, value: impl Into<Value>) -> Result<(), AgentConfigError> {
        let mut given = Table::new();
        given.insert(key.to_owned(), value.into());
        self.overlay(&mut given)?;
        match given.keys().next() {
            Some(key) => Err(not_a_setting(self.algorithm, key)),
            None => Ok(()),
        }
    }

    /// Whether it runs in Mistake Correcting mode (the advisee sends its
    /// intended action along; docs/algorithms.md section 4).
    pub fn mistake_correcting(&self) -> bool {
        self.setting("mistake_correcting") == Some(Value::Bool(true))
    }

    /// Its reachable set, for the methods that ask a set of advisors.
    pub fn reachable(&self) -> Option<Reachable> {
        serde_json::from_value(self.setting("reachable")?).ok()
    }

    /// The first invalid setting, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        self.settings.validate()
    }

    /// Its decisions for the agent of `seat`, under the fidelity rules
    /// `fidelity`.
    pub fn build_for(&self, fidelity: &Fidelity, seat: &Seat<'_>) -> Box<dyn AdvisingStrategy> {
        self.settings.strategy(fidelity, seat)
    }

    /// Checks the agent ids its reachable set names against the team size.
    pub(crate) fn check_team(&self, team_size: usize) -> Result<(), AgentConfigError> {
        let bad = |j: usize| {
            AgentConfigError::new(
                "reachable",
                format!("agent {j} is out of range or repeated"),
            )
        };
        match self.reachable() {
            Some(Reachable::Agents(ids)) => {
                for (k, &j) in ids.iter().enumerate() {
                    if j >= team_size || ids[..k].contains(&j) {
                        return Err(bad(j));
                    }
                }
                Ok(())
            }
            Some(Reachable::Star(hub)) if hub >= team_size => Err(bad(hub)),
            _ => Ok(()),
        }
    }

    /// `algorithm` under `profile`'s defaults with the keys of `given` that
    /// it has, which are taken out of `given`.
    pub(crate) fn from_table(
        algorithm: Algorithm,
        profile: Profile,
        given: &mut Table,
    ) -> Result<Self, AgentConfigError> {
        let mut settings = Self::of(algorithm, profile);
        settings.overlay(given)?;
        Ok(settings)
    }

    /// Takes the keys it has out of `given` as its values.
    fn overlay(&mut self, given: &mut Table) -> Result<(), AgentConfigError> {
        let mut table = self.settings.table();
        let keys: Vec<String> = table
            .keys()
            .filter(|k| given.contains_key(*k))
            .cloned()
            .collect();
        for key in keys {
            let value = given.remove(&key).expect("a key of `given`");
            let mut one = table.clone();
            one.insert(key.clone(), value.clone());
            if let Err(e) = (self.algorithm.registration().from_table)(one) {
                return Err(AgentConfigError::new(key, e.to_string()));
            }
            table.insert(key, value);
        }
        self.settings = (self.algorithm.registration().from_table)(table)
            .map_err(|e| AgentConfigError::new("algorithm", e.to_string()))?;
        Ok(())
    }

    /// The keys a file writes: every key but those whose value is null and
    /// the method's keys written only when true.
    pub(crate) fn written(&self) -> Table {
        let only_true = self.algorithm.registration().written_when_true;
        let mut table = self.settings.table();
        let unset = |key: &String, value: &Value| {
            value.is_null() || (only_true.contains(&key.as_str()) && *value == Value::Bool(false))
        };
        table.retain(|key, value| !unset(key, value));
        table
    }
}

/// The error for a key `algorithm` does not have, naming the algorithms
/// that have it.
pub(crate) fn not_a_setting(algorithm: Algorithm, key: &str) -> AgentConfigError {
    let owners: Vec<&str> = Algorithm::all()
        .filter(|a| a.has_setting(key))
        .map(Algorithm::name)
        .collect();
    let reason = if owners.is_empty() {
        format!("not a setting of algorithm {algorithm}, nor of any other")
    } else {
        format!(
            "does not apply to algorithm {algorithm}; it belongs to {}",
            owners.join(", ")
        )
    };
    AgentConfigError::new(key, reason)
}

impl Clone for AlgorithmSettings {
    fn clone(&self) -> Self {
        Self {
            algorithm: self.algorithm,
            settings: self.settings.boxed_clone(),
        }
    }
}

impl PartialEq for AlgorithmSettings {
    fn eq(&self, other: &Self) -> bool {
        self.algorithm == other.algorithm && self.settings.table() == other.settings.table()
    }
}

impl Default for AlgorithmSettings {
    /// `no-advice`.
    fn default() -> Self {
        Self::of(Algorithm::default(), Profile::Paper)
    }
}

impl fmt::Debug for AlgorithmSettings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {:?}", self.algorithm, self.settings)
    }
}

impl From<Algorithm> for AlgorithmSettings {
    /// `algorithm` with the paper's defaults.
    fn from(algorithm: Algorithm) -> Self {
        Self::of(algorithm, Profile::Paper)
    }
}
