//! Any file given as a snapshot: `Snapshot::decode` returns a snapshot or an
//! error, never panics. The bytes are tried as a whole file and as the body
//! of a file whose header and checksum are right, so the body decoder sees
//! them too; a decoded snapshot checks or is refused, and one that checks
//! encodes back to a file that decodes to itself.

#![no_main]

use agent::Snapshot;
use libfuzzer_sys::fuzz_target;

/// FNV-1a, 64 bits: the snapshot file's checksum.
fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    })
}

/// A file image with `body` between a valid header and its checksum: the
/// header is taken from a real snapshot's file (magic and version), the
/// length and checksum are `body`'s.
fn framed(body: &[u8]) -> Vec<u8> {
    let empty = Snapshot {
        tiling: agent::TilingParams::of(&agent::AgentConfig::default()),
        entries: Vec::new(),
        counters: Default::default(),
        training_episodes: 0,
    };
    let file = empty.encode().expect("an empty snapshot encodes");
    let body_len = postcard::to_allocvec(&empty).expect("encodes").len();
    let magic_and_version = file.len() - body_len - 8 - 8;
    let mut out = file[..magic_and_version].to_vec();
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(body);
    out.extend_from_slice(&fnv(body).to_le_bytes());
    out
}

fuzz_target!(|data: &[u8]| {
    for bytes in [data.to_vec(), framed(data)] {
        if let Ok(snapshot) = Snapshot::decode(&bytes) {
            if snapshot.check().is_ok() {
                let file = snapshot.encode().expect("a checked snapshot encodes");
                assert_eq!(Snapshot::decode(&file).expect("decodes"), snapshot);
            }
        }
    }
});
