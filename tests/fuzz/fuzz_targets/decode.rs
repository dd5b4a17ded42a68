//! Any bytes on the wire: `proto::decode` returns a message or an error,
//! never panics, and what it returns encodes back to a message that decodes
//! to itself. A control message's settings bytes decode to an agent
//! configuration or an error, and a decoded configuration validates or is
//! refused, without a panic.

#![no_main]

use libfuzzer_sys::fuzz_target;
use proto::{Body, Control, Header};

/// The experiment id the decoder expects (any fixed value).
const EXPERIMENT: u64 = 0x0adc_0ffe_e0ad_0c0d;

fuzz_target!(|data: &[u8]| {
    let _ = proto::decode(data, EXPERIMENT);
    // The same bytes after a valid header of this experiment, so that the
    // body decoder sees them too.
    let mut framed = postcard::to_allocvec(&Header::new(EXPERIMENT, 0, 0, 0)).expect("encodes");
    framed.extend_from_slice(data);
    for bytes in [data, &framed[..]] {
        if let Ok(envelope) = proto::decode(bytes, EXPERIMENT) {
            let again = proto::decode(&proto::encode(&envelope), EXPERIMENT)
                .expect("an encoded message decodes");
            // Compared as bytes: a NaN in an observation is not equal to itself.
            assert_eq!(proto::encode(&again), proto::encode(&envelope));
            if let Body::Control(Control::Reset { config, .. }) = &envelope.body {
                settings(config);
            }
        }
    }
    settings(data);
});

fn settings(bytes: &[u8]) {
    if let Ok(config) = proto::decode_settings::<agent::AgentConfig>(bytes) {
        let _ = config.validate();
    }
}
