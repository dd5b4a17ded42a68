//! File output: the one atomic write.

use std::io::{self, Write};
use std::path::Path;

/// Prefix of [`write_atomically`]'s temporary files: a leftover one (a
/// crash before its rename) can be recognised and ignored.
pub const TEMP_PREFIX: &str = ".adv-tmp-";

/// Writes `bytes` to `path` atomically and durably: a temporary file in the
/// same directory, written and synced, renamed over `path`, then the
/// directory synced. Readers see the old file or the new one, never a part;
/// on error the temporary file goes.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut file = tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .tempfile_in(dir)?;
    file.write_all(bytes)?;
    file.as_file().sync_all()?;
    file.persist(path).map_err(|e| e.error)?;
    sync_dir(dir)
}

/// Makes a rename in `dir` durable.
fn sync_dir(dir: &Path) -> io::Result<()> {
    std::fs::File::open(dir)?.sync_all()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_replace_the_file_and_leave_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_atomically(&path, b"one").unwrap();
        write_atomically(&path, b"two").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"two");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1);
        let missing = dir.path().join("no-such-dir").join("x");
        assert!(write_atomically(&missing, b"x").is_err());
    }
}
