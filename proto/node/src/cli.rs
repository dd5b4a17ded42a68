//! The command line every process shares: the connection arguments, the
//! one-line errors with exit code 2, and quiet-by-default logging.

use std::fmt::Display;
use std::path::PathBuf;

use clap::Parser;
use proto::keys::{InvalidExperiment, Keys};

use crate::net::NetConfig;
use crate::secret::{Secret, SecretError};

/// How a process started for an experiment joins it; flattened into the
/// `agent` and `env-server serve` command lines (the coordinator starts
/// them with these flags).
#[derive(Clone, Debug, PartialEq, Eq, clap::Args)]
pub struct ConnectionArgs {
    /// Experiment name (letters, digits, '-', '_'), shared by all its
    /// processes; every key lives under adv/NAME.
    #[arg(long, value_name = "NAME")]
    pub experiment: String,
    /// zenoh endpoint to listen on (port 0: any free port).
    #[arg(long, value_name = "ENDPOINT", default_value = "tcp/127.0.0.1:0")]
    pub listen: String,
    /// zenoh endpoint to connect to: the coordinator's, or a router's (repeatable).
    #[arg(long, value_name = "ENDPOINT")]
    pub connect: Vec<String>,
    /// Exit when the coordinator that was seen leaves (for processes a
    /// coordinator starts itself; services keep running).
    #[arg(long)]
    pub exit_with_coordinator: bool,
    /// The experiment's secret: a file, readable by its owner only, holding
    /// one `user:password` line; every process of the experiment uses the
    /// same one, and peers without it are refused.
    #[arg(long, value_name = "FILE", required_unless_present = "no_auth")]
    pub secret_file: Option<PathBuf>,
    /// Join without authentication: anyone who can reach the endpoints can
    /// then read and send every message.
    #[arg(long, conflicts_with = "secret_file")]
    pub no_auth: bool,
    /// A zenoh configuration file (JSON5) to start from, e.g. TLS
    /// certificates and access control (deploy/tls/); the flags above are
    /// set on top of it.
    #[arg(long, value_name = "FILE")]
    pub zenoh_config: Option<PathBuf>,
}

impl ConnectionArgs {
    /// The experiment's keys; fails on a bad experiment name.
    pub fn keys(&self) -> Result<Keys, InvalidExperiment> {
        Keys::new(&self.experiment)
    }

    /// The zenoh settings: a peer on these endpoints, with the secret
    /// unless `--no-auth`; fails on a secret file that cannot be used.
    pub fn net(&self) -> Result<NetConfig, SecretError> {
        let secret = self.secret_file.as_deref().map(Secret::load).transpose()?;
        Ok(
            NetConfig::peer(vec![self.listen.clone()], self.connect.clone())
                .with_secret(secret)
                .with_base(self.zenoh_config.clone()),
        )
    }
}

/// Folds a multi-line message into one line, without clap's usage hints.
fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with("For more information") && !l.starts_with("Usage:")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Parses the command line: `--help` and `--version` print and exit 0; a
/// bad command line prints clap's message on one line and exits 2.
pub fn parse_or_exit<P: Parser>() -> P {
    match P::try_parse() {
        Ok(parsed) => parsed,
        Err(e) if !e.use_stderr() => {
            // Nothing more to do if stdout is gone.
            let _ = e.print();
            std::process::exit(0)
        }
        Err(e) => {
            eprintln!("{}", one_line(&e.to_string()));
            std::process::exit(2)
        }
    }
}

/// Prints `error: <message>` on one line to standard error and exits 2.
pub fn exit_with_error(message: impl Display) -> ! {
    eprintln!("error: {}", one_line(&message.to_string()));
    std::process::exit(2)
}

/// Logs to standard error, filtered by `RUST_LOG`, or by `default_filter`
/// (e.g. `"off"`, `"error"`) when it is unset or invalid. The default also
/// silences zenoh's "sending on a closed channel": a sample that reaches a
/// subscriber while the process drops it on its way out.
pub fn init_tracing(default_filter: &str) {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env().unwrap_or_else(|_| {
        tracing_subscriber::EnvFilter::new(format!("{default_filter},zenoh::api::handlers=off"))
    });
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .init();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Parser)]
    struct TestCli {
        #[command(flatten)]
        connection: ConnectionArgs,
    }

    #[test]
    fn connection_flags_keep_their_names() {
        let cli = TestCli::try_parse_from([
            "x",
            "--experiment",
            "e1",
            "--connect",
            "tcp/127.0.0.1:1",
            "--connect",
            "tcp/127.0.0.1:2",
            "--exit-with-coordinator",
            "--no-auth",
        ])
        .unwrap();
        let c = cli.connection;
        assert!(c.exit_with_coordinator);
        assert_eq!(c.keys().unwrap(), Keys::new("e1").unwrap());
        assert_eq!(
            c.net().unwrap(),
            NetConfig::peer(
                vec!["tcp/127.0.0.1:0".into()],
                vec!["tcp/127.0.0.1:1".into(), "tcp/127.0.0.1:2".into()]
            )
        );
        let bad = TestCli::try_parse_from(["x", "--experiment", "a/b", "--no-auth"]).unwrap();
        assert!(bad.connection.keys().is_err());
        assert!(TestCli::try_parse_from(["x"]).is_err());
    }

    #[test]
    fn a_secret_is_required_unless_refused_explicitly() {
        let error = |args: &[&str]| TestCli::try_parse_from(args).err().map(|e| e.to_string());
        let missing = error(&["x", "--experiment", "e"]).unwrap();
        assert!(missing.contains("--secret-file"), "{missing}");
        assert!(error(&["x", "--experiment", "e", "--secret-file", "s", "--no-auth"]).is_some());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("secret");
        let secret = Secret::create(&path).unwrap();
        let cli = TestCli::try_parse_from(
            ["x", "--experiment", "e", "--secret-file"]
                .map(str::to_owned)
                .into_iter()
                .chain([path.display().to_string()]),
        )
        .unwrap();
        assert_eq!(cli.connection.net().unwrap().secret, Some(secret));
        let missing_file =
            TestCli::try_parse_from(["x", "--experiment", "e", "--secret-file", "/nonexistent/s"])
                .unwrap();
        assert!(
            missing_file
                .connection
                .net()
                .unwrap_err()
                .to_string()
                .contains("/nonexistent/s")
        );
    }

    #[test]
    fn clap_messages_fold_to_one_line() {
        let text = "error: unexpected argument '--x' found\n\n  tip: to pass '--x' as a value, use '-- --x'\n\nUsage: agent [OPTIONS]\n\nFor more information, try '--help'.\n";
        assert_eq!(
            one_line(text),
            "error: unexpected argument '--x' found tip: to pass '--x' as a value, use '-- --x'"
        );
    }
}
