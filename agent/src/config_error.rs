//! A configuration value out of its range, and the range checks that name it.

/// A configuration value out of its allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("invalid agent config `{key}`: {reason}")]
pub struct AgentConfigError {
    /// The offending key, as spelled in the configuration.
    pub key: String,
    /// What is wrong with its value.
    pub reason: String,
}

impl AgentConfigError {
    pub(crate) fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

/// `Ok` when `value` is finite and `ok`, else an error saying what `value`
/// must be.
pub(crate) fn require(
    key: &'static str,
    value: f64,
    rule: &str,
    ok: bool,
) -> Result<(), AgentConfigError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(AgentConfigError::new(
            key,
            format!("must be {rule}, got {value}"),
        ))
    }
}

/// A probability-like value in [0, 1].
pub(crate) fn require_unit(key: &'static str, value: f64) -> Result<(), AgentConfigError> {
    require(key, value, "in [0, 1]", (0.0..=1.0).contains(&value))
}

/// A finite value >= 0.
pub(crate) fn require_non_negative(key: &'static str, value: f64) -> Result<(), AgentConfigError> {
    require(key, value, "finite and >= 0", value >= 0.0)
}
