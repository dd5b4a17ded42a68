//! `analyse`: re-analyse a study directory from its files alone, or
//! publish it.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

/// Writes a study directory's REPORT.md, significance.json and figures anew
/// from its files (study.json, each entry's config.json and run-<k>.json, or
/// run-<k>.json.gz in a published study): nothing is played.
#[derive(Parser)]
#[command(version)]
struct Cli {
    /// The study directory (`coordinator study --out DIR`).
    dir: PathBuf,
    /// Instead of analysing DIR, publish it into DEST: its study.json,
    /// REPORT.md, significance.json, figures, and each entry's config.json,
    /// summary.json and finished runs gzipped (run-<k>.json.gz,
    /// run-<k>.csv.gz); no pretraining, snapshots or logs. DEST is refused
    /// when it holds another study.
    #[arg(long, value_name = "DEST")]
    publish: Option<PathBuf>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let done = match &cli.publish {
        Some(dest) => analysis::publish::publish(&cli.dir, dest)
            .map(|p| format!("{}: {} files, {} bytes", dest.display(), p.files, p.bytes)),
        None => analysis::files::read_study(&cli.dir)
            .and_then(|(study, entries)| analysis::report::write_report(&cli.dir, &study, &entries))
            .map(|report| report.display().to_string()),
    };
    match done {
        Ok(line) => {
            println!("{line}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
