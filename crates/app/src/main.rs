//! The `helixhair` binary: parses the command line, runs it, reports errors.

use std::process::ExitCode;

use clap::Parser as _;
use helixhair_app::cli::{Cli, run};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(
        &cli,
        &mut std::io::stdout().lock(),
        &mut std::io::stderr().lock(),
    ) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // `{:#}` prints the whole chain: context, then cause.
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
