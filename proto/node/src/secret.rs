//! The experiment's shared secret: one `user:password` line in a file only
//! its owner can read, handed to zenoh's user/password authentication so
//! that a peer without it cannot open a session with the experiment's
//! processes. The secret never appears on a command line: processes get the
//! file's path.

use std::fmt;
use std::fs::{self, OpenOptions};
use std::io::Write;
use std::os::unix::fs::{OpenOptionsExt, PermissionsExt};
use std::path::{Path, PathBuf};

/// The user name of a secret the coordinator creates.
pub const SECRET_USER: &str = "adv";

/// The largest secret file read (bytes).
const MAX_SECRET_FILE: u64 = 4096;

/// Random bytes in a new secret.
const SECRET_BYTES: usize = 32;

/// A secret file that cannot be used; displays as one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("secret file {path}: {problem}")]
pub struct SecretError {
    path: String,
    problem: String,
}

impl SecretError {
    fn new(path: &Path, problem: impl Into<String>) -> Self {
        Self {
            path: path.display().to_string(),
            problem: problem.into(),
        }
    }
}

/// An experiment's credentials and the file they came from. Its `Debug`
/// form leaves the password out.
#[derive(Clone, PartialEq, Eq)]
pub struct Secret {
    path: PathBuf,
    user: String,
    password: String,
}

impl fmt::Debug for Secret {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Secret")
            .field("path", &self.path)
            .field("user", &self.user)
            .finish_non_exhaustive()
    }
}

impl Secret {
    /// Writes a new random secret to `path`, readable by its owner only;
    /// fails if `path` exists.
    pub fn create(path: &Path) -> Result<Self, SecretError> {
        let mut random = [0u8; SECRET_BYTES];
        getrandom::fill(&mut random).map_err(|e| {
            SecretError::new(
                path,
                format!("cannot draw random bytes from the system: {e}"),
            )
        })?;
        let password = hex::encode(random);
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .mode(0o600)
            .open(path)
            .map_err(|e| SecretError::new(path, format!("cannot create: {e}")))?;
        writeln!(file, "{SECRET_USER}:{password}")
            .and_then(|()| file.sync_all())
            .map_err(|e| SecretError::new(path, format!("cannot write: {e}")))?;
        Ok(Self {
            path: path.to_owned(),
            user: SECRET_USER.to_owned(),
            password,
        })
    }

    /// A new random secret in a new directory that only its owner may
    /// enter, both removed when the returned directory is dropped.
    pub fn generate() -> Result<(Self, tempfile::TempDir), SecretError> {
        let dir = tempfile::Builder::new()
            .prefix("adv-secret-")
            .permissions(fs::Permissions::from_mode(0o700))
            .tempdir()
            .map_err(|e| {
                let at = std::env::temp_dir();
                SecretError::new(&at, format!("cannot create a private directory here: {e}"))
            })?;
        let secret = Self::create(&dir.path().join("secret"))?;
        Ok((secret, dir))
    }

    /// Reads the secret at `path`: a regular file of at most 4 KiB that no
    /// one but its owner may read or write, holding one `user:password` line
    /// (no spaces; the user may not contain ':').
    pub fn load(path: &Path) -> Result<Self, SecretError> {
        let fail = |problem: String| SecretError::new(path, problem);
        let meta = fs::metadata(path).map_err(|e| fail(format!("cannot read: {e}")))?;
        if !meta.is_file() {
            return Err(fail("is not a regular file".into()));
        }
        let mode = meta.permissions().mode() & 0o777;
        if mode & 0o077 != 0 {
            return Err(fail(format!(
                "others may read or write it (mode {mode:03o}); expected 600 (chmod 600)"
            )));
        }
        if meta.len() > MAX_SECRET_FILE {
            return Err(fail(format!(
                "{} bytes, expected one line of at most {MAX_SECRET_FILE}",
                meta.len()
            )));
        }
        let text = fs::read_to_string(path).map_err(|e| fail(format!("cannot read: {e}")))?;
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let (Some(line), None) = (lines.next(), lines.next()) else {
            return Err(fail("expected exactly one line 'user:password'".into()));
        };
        match line.trim().split_once(':') {
            Some((user, password))
                if !user.is_empty()
                    && !password.is_empty()
                    && !line.trim().contains(char::is_whitespace) =>
            {
                Ok(Self {
                    path: path.to_owned(),
                    user: user.to_owned(),
                    password: password.to_owned(),
                })
            }
            _ => Err(fail(
                "expected one line 'user:password' with neither part empty and no spaces".into(),
            )),
        }
    }

    /// The file the secret is in.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// zenoh's `transport/auth/usrpwd` setting: present these credentials,
    /// accept only peers that present them.
    #[cfg(feature = "zenoh")]
    pub(crate) fn usrpwd_setting(&self) -> serde_json::Value {
        serde_json::json!({
            "user": self.user,
            "password": self.password,
            "dictionary_file": self.path.display().to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_generated_secret_lives_in_a_private_directory_until_dropped() {
        let (secret, dir) = Secret::generate().unwrap();
        let mode = fs::metadata(dir.path()).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o700);
        assert_eq!(Secret::load(secret.path()).unwrap(), secret);
        let path = dir.path().to_owned();
        drop(dir);
        assert!(!path.exists());
    }

    #[test]
    fn a_created_secret_loads_back_and_is_private() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("secret");
        let made = Secret::create(&path).unwrap();
        assert_eq!(Secret::load(&path).unwrap(), made);
        assert_eq!(made.password.len(), 2 * SECRET_BYTES);
        let mode = fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o600);
        assert!(
            Secret::create(&path)
                .unwrap_err()
                .to_string()
                .contains("cannot create")
        );
        let other = Secret::create(&dir.path().join("other")).unwrap();
        assert_ne!(other.password, made.password, "every secret is new");
        assert!(!format!("{made:?}").contains(&made.password));
    }

    #[test]
    fn unsafe_or_malformed_files_are_refused_with_the_reason() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, text: &str, mode: u32| {
            let path = dir.path().join(name);
            fs::write(&path, text).unwrap();
            fs::set_permissions(&path, fs::Permissions::from_mode(mode)).unwrap();
            path
        };
        let error = |path: &Path| Secret::load(path).unwrap_err().to_string();
        assert!(error(&write("open", "a:b\n", 0o644)).contains("mode 644"));
        assert!(error(&write("empty", "", 0o600)).contains("exactly one line"));
        assert!(error(&write("two", "a:b\nc:d\n", 0o600)).contains("exactly one line"));
        assert!(error(&write("nocolon", "ab\n", 0o600)).contains("user:password"));
        assert!(error(&write("nopass", "a:\n", 0o600)).contains("user:password"));
        assert!(error(&write("space", "a:b c\n", 0o600)).contains("no spaces"));
        let big = "a:".to_owned() + &"b".repeat(5000);
        assert!(error(&write("big", &big, 0o600)).contains("at most 4096"));
        assert!(error(dir.path()).contains("not a regular file"));
        assert!(error(&dir.path().join("missing")).contains("cannot read"));
        let ok = write("ok", "\nuser:pass\n\n", 0o400);
        let secret = Secret::load(&ok).unwrap();
        assert_eq!(
            (secret.user.as_str(), secret.password.as_str()),
            ("user", "pass")
        );
    }
}
