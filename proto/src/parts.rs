//! Snapshots in parts: a snapshot travels as messages of at most
//! [`PART_BYTES`] each (`Control::Load`, `ControlReply::Snapshot`), so that
//! no message is large (zenoh can close a link on one that fills its send
//! queue) and a receiver bounds what it gathers.

/// The most snapshot bytes one message carries.
pub const PART_BYTES: usize = 32 * 1024;

/// The most parts of one snapshot (1 GiB).
pub const MAX_PARTS: u32 = 32 * 1024;

/// `bytes` cut into parts of at most [`PART_BYTES`]: at least one, empty
/// for no bytes.
pub fn split(bytes: &[u8]) -> Vec<&[u8]> {
    if bytes.is_empty() {
        return vec![bytes];
    }
    bytes.chunks(PART_BYTES).collect()
}

/// A snapshot gathered part by part, in order.
#[derive(Debug, Default)]
pub struct Gathering {
    parts: u32,
    bytes: Vec<u8>,
    next: u32,
}

impl Gathering {
    /// Takes part `part` of `parts`: the whole snapshot once this was its
    /// last part, `None` while parts are to come; an error for a part out
    /// of order, a count that changes or is out of bounds, or a part larger
    /// than [`PART_BYTES`] (and the gathering starts over).
    pub fn take(&mut self, part: u32, parts: u32, bytes: &[u8]) -> Result<Option<Vec<u8>>, String> {
        if part == 0 {
            *self = Self::default();
        }
        let check = || {
            if !(1..=MAX_PARTS).contains(&parts) {
                return Err(format!("a snapshot of 1 to {MAX_PARTS} parts, got {parts}"));
            }
            if part != self.next || (part > 0 && parts != self.parts) {
                return Err(format!(
                    "snapshot part {part} of {parts}, expected part {} of {}",
                    self.next,
                    if self.next == 0 { parts } else { self.parts }
                ));
            }
            if bytes.len() > PART_BYTES {
                return Err(format!(
                    "a snapshot part of at most {PART_BYTES} bytes, got {}",
                    bytes.len()
                ));
            }
            Ok(())
        };
        if let Err(e) = check() {
            *self = Self::default();
            return Err(e);
        }
        self.parts = parts;
        self.bytes.extend_from_slice(bytes);
        self.next += 1;
        if self.next < parts {
            return Ok(None);
        }
        let whole = std::mem::take(&mut self.bytes);
        *self = Self::default();
        Ok(Some(whole))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gather(parts: &[&[u8]]) -> Result<Option<Vec<u8>>, String> {
        let mut g = Gathering::default();
        let n = parts.len() as u32;
        let mut last = Ok(None);
        for (i, p) in parts.iter().enumerate() {
            last = g.take(i as u32, n, p);
        }
        last
    }

    #[test]
    fn parts_put_together_give_the_bytes_back() {
        for len in [0, 1, PART_BYTES, PART_BYTES + 1, 3 * PART_BYTES + 7] {
            let bytes: Vec<u8> = (0..len).map(|i| i as u8).collect();
            let parts = split(&bytes);
            assert_eq!(parts.len(), len.div_ceil(PART_BYTES).max(1));
            assert!(parts.iter().all(|p| p.len() <= PART_BYTES));
            assert_eq!(gather(&parts), Ok(Some(bytes)));
        }
    }

    #[test]
    fn parts_out_of_order_oversized_or_miscounted_are_refused() {
        let mut g = Gathering::default();
        assert_eq!(g.take(0, 3, b"a"), Ok(None));
        assert!(
            g.take(2, 3, b"c")
                .unwrap_err()
                .contains("expected part 1 of 3")
        );
        // Refused: it starts over at part 0.
        assert!(g.take(1, 3, b"b").is_err());
        assert_eq!(g.take(0, 2, b"a"), Ok(None));
        assert!(
            g.take(1, 3, b"b")
                .unwrap_err()
                .contains("expected part 1 of 2")
        );
        assert!(g.take(0, 0, b"").unwrap_err().contains("1 to"));
        assert!(g.take(0, MAX_PARTS + 1, b"").is_err());
        let big = vec![0; PART_BYTES + 1];
        assert!(g.take(0, 1, &big).unwrap_err().contains("at most"));
        assert_eq!(g.take(0, 2, b"a"), Ok(None));
        assert_eq!(g.take(1, 2, b"b"), Ok(Some(b"ab".to_vec())));
    }
}
