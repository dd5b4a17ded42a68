//! Key expressions, all under the per-experiment prefix `adv/<experiment>`.

use std::fmt;
use thiserror::Error;

/// A process's role in an experiment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// The env-server.
    Server,
    /// Agent `id`.
    Agent(u8),
    /// The coordinator.
    Coordinator,
}

impl fmt::Display for Role {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Role::Server => f.write_str("server"),
            Role::Agent(id) => write!(f, "agent/{id}"),
            Role::Coordinator => f.write_str("coordinator"),
        }
    }
}

/// An experiment name that cannot be a key-expression chunk.
#[derive(Debug, Error, PartialEq, Eq)]
#[error("invalid experiment name '{0}': use 1 to 64 characters among letters, digits, '-' and '_'")]
pub struct InvalidExperiment(String);

/// The key expressions of one experiment.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Keys {
    prefix: String,
}

impl Keys {
    /// Keys of experiment `name` (letters, digits, `-`, `_`).
    pub fn new(name: &str) -> Result<Self, InvalidExperiment> {
        let ok = (1..=64).contains(&name.len())
            && name
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_');
        if !ok {
            return Err(InvalidExperiment(name.to_owned()));
        }
        Ok(Keys {
            prefix: format!("adv/{name}"),
        })
    }

    /// Everything of this experiment.
    pub fn all(&self) -> String {
        format!("{}/**", self.prefix)
    }

    /// Observations for agent `id` (env-server publishes).
    pub fn observation(&self, id: u8) -> String {
        format!("{}/obs/{id}", self.prefix)
    }

    /// Actions of agent `id` (agent publishes).
    pub fn action(&self, id: u8) -> String {
        format!("{}/act/{id}", self.prefix)
    }

    /// Actions of every agent (env-server subscribes).
    pub fn actions(&self) -> String {
        format!("{}/act/*", self.prefix)
    }

    /// Agent `id`'s advice queryable.
    pub fn advice(&self, id: u8) -> String {
        format!("{}/advice/{id}", self.prefix)
    }

    /// What agents send agent `id` unasked: shared episodes, experience
    /// batches, reports of how its advice turned out.
    pub fn share(&self, id: u8) -> String {
        format!("{}/share/{id}", self.prefix)
    }

    /// Announcements of agents whose give budget is spent (each agent
    /// publishes on its own, every agent subscribes to all).
    pub fn exhausted(&self, id: u8) -> String {
        format!("{}/exhausted/{id}", self.prefix)
    }

    /// Every agent's announcements.
    pub fn exhausted_all(&self) -> String {
        format!("{}/exhausted/*", self.prefix)
    }

    /// The control queryable of a process.
    pub fn control(&self, role: Role) -> String {
        format!("{}/ctl/{role}", self.prefix)
    }

    /// The liveliness token of a process.
    pub fn alive(&self, role: Role) -> String {
        format!("{}/alive/{role}", self.prefix)
    }

    /// Every liveliness token of this experiment.
    pub fn alive_all(&self) -> String {
        format!("{}/alive/**", self.prefix)
    }

    /// The role whose liveliness token is `key`, if it is one of ours.
    pub fn role_of_alive(&self, key: &str) -> Option<Role> {
        let rest = key.strip_prefix(&self.prefix)?.strip_prefix("/alive/")?;
        match rest {
            "server" => Some(Role::Server),
            "coordinator" => Some(Role::Coordinator),
            _ => rest.strip_prefix("agent/")?.parse().ok().map(Role::Agent),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_roles() {
        let k = Keys::new("exp-1").unwrap();
        assert_eq!(k.observation(2), "adv/exp-1/obs/2");
        assert_eq!(k.control(Role::Agent(0)), "adv/exp-1/ctl/agent/0");
        for role in [Role::Server, Role::Coordinator, Role::Agent(3)] {
            assert_eq!(k.role_of_alive(&k.alive(role)), Some(role));
        }
        assert_eq!(k.role_of_alive("adv/other/alive/server"), None);
        assert!(Keys::new("a/b").is_err());
        assert!(Keys::new("").is_err());
        assert!(Keys::new("x*").is_err());
    }
}
