//! Wire protocol shared by env-server, agents and coordinator.
//!
//! Messages are serde types encoded with postcard ([`codec`]); every message
//! carries a [`Header`] with [`PROTOCOL_VERSION`], the experiment, run,
//! episode and frame, so that stale, duplicate, foreign or malformed
//! messages are recognised and dropped. Key expressions live in [`keys`],
//! message and byte counters in [`counters`]. Joining the zenoh network is
//! the `node` crate's job: this one knows nothing of zenoh.

mod action;
pub mod codec;
mod features;
pub mod keys;
pub mod message;
pub mod parts;
pub mod traffic;

pub use action::{Action, STATE_FEATURES, State};
pub use codec::{
    DecodeError, SettingsError, decode, decode_settings, encode, encode_settings, version_refusal,
};
pub use features::{Features, MAX_FEATURE_TEAM, MAX_FEATURES, hfo_feature_count};
pub use message::*;
pub use traffic::{Direction, DropReason, MessageCounters, MessageKind};
