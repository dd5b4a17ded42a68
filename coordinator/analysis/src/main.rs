//! `analyse`: re-analyse a study directory from its files alone.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

/// Writes a study directory's REPORT.md, significance.json and figures anew
/// from its files (study.json, each entry's config.json and run-<k>.json):
/// nothing is played.
#[derive(Parser)]
#[command(version)]
struct Cli {
    /// The study directory (`coordinator study --out DIR`).
    dir: PathBuf,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let analysed = analysis::files::read_study(&cli.dir)
        .and_then(|(study, entries)| analysis::report::write_report(&cli.dir, &study, &entries));
    match analysed {
        Ok(report) => {
            println!("{}", report.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
