//! Liveliness: which agents are reachable, and whether the coordinator is
//! still there (docs/protocol.md, "Liveness").

use std::sync::Arc;

use node::alive::CoordinatorPresence;
use proto::keys::Role;
use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::Subscriber;
use zenoh::sample::{Sample, SampleKind};

use crate::context::{Context, Exit};

/// Follows the experiment's liveliness tokens until the session closes:
/// agents come and go from the live set; with `exit_with_coordinator`,
/// once the coordinator has been seen, its disappearance stops the process
/// (nobody else would stop it).
pub async fn track(
    ctx: Arc<Context>,
    tokens: Subscriber<FifoChannelHandler<Sample>>,
    exit_with_coordinator: bool,
) {
    let coordinator = CoordinatorPresence::default();
    while let Ok(sample) = tokens.recv_async().await {
        let present = sample.kind() == SampleKind::Put;
        let role = ctx.keys.role_of_alive(sample.key_expr().as_str());
        tracing::debug!(?role, present, "liveliness");
        match role {
            Some(Role::Agent(j)) => {
                ctx.set_alive(j, present);
                if present {
                    ctx.learner().peer_joined(j);
                }
            }
            Some(Role::Coordinator) if coordinator.left(present) && exit_with_coordinator => {
                ctx.stop(Exit::CoordinatorGone)
            }
            _ => {}
        }
    }
}
