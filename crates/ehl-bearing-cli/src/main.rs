//! `ehl-bearing` command line: thin layer over the `ehl-bearing` library.

mod characterize_cmd;
mod ehl_cmd;
mod equilibrium_cmd;
mod plot;
mod study_cmd;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Lubricated angular-contact ball bearings: equilibrium, EHL contacts, fitted contact laws.
#[derive(Parser)]
#[command(name = "ehl-bearing", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Quasi-static 5-DOF equilibrium of a bearing case with dry Hertz contacts.
    Equilibrium(equilibrium_cmd::EquilibriumArgs),
    /// Coupled loop: equilibrium and per-contact characterization (K, d, ΔF) until consistent.
    Characterize(characterize_cmd::CharacterizeArgs),
    /// Load × speed study: per-point results, CSV, trend curves and plots (resumable).
    Study(study_cmd::StudyArgs),
}

fn main() -> ExitCode {
    let _ = (ehl_cmd::PLACEHOLDER, plot::PLACEHOLDER);
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Equilibrium(a) => equilibrium_cmd::run(a),
        Command::Characterize(a) => characterize_cmd::run(a),
        Command::Study(a) => study_cmd::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
