//! Any file given as a snapshot: `Snapshot::decode` returns a snapshot or an
//! error, never panics. The bytes are tried as a whole file and as the body
//! of a file whose header and checksum are right (`agent::snapshot_file`),
//! so the body decoder sees them too; a decoded snapshot checks or is
//! refused, and one that checks encodes back to a file that decodes to
//! itself.

#![no_main]

use agent::Snapshot;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for bytes in [data.to_vec(), agent::snapshot_file(data)] {
        if let Ok(snapshot) = Snapshot::decode(&bytes) {
            if snapshot.check().is_ok() {
                let file = snapshot.encode().expect("a checked snapshot encodes");
                assert_eq!(Snapshot::decode(&file).expect("decodes"), snapshot);
            }
        }
    }
});
