//! Network conditions injected at the sender (docs/algorithms.md section 6):
//! the fate each advice message draws, and a delay precise to well under a
//! millisecond (tokio's timers round up to whole milliseconds).

use std::time::Duration;

use agent::{Leg, Link, Message};
use proto::Header;

/// The one-way delay `link` draws for the message from `from` to `to` about
/// the frame of `header` (`Some(0.0)` without conditions), or `None` when it
/// is lost.
pub fn fate(link: Option<Link>, header: &Header, from: u8, to: u8, leg: Leg) -> Option<f64> {
    let message = Message {
        episode: header.episode,
        frame: header.frame,
        from: from.into(),
        to: to.into(),
        leg,
    };
    link.map_or(Some(0.0), |l| l.delay(message))
}

/// Waits `ms` milliseconds on a blocking thread.
pub async fn delay(ms: f64) {
    let wait = Duration::from_secs_f64(ms / 1000.0);
    // Only a panic in `sleep` could fail the join: there is nothing to undo.
    let _ = tokio::task::spawn_blocking(move || std::thread::sleep(wait)).await;
}
