//! `ehl-bearing` command line: thin layer over the `ehl-bearing` library.

mod characterize_cmd;
mod coefficients_cmd;
mod contact_cmd;
mod ehl_cmd;
mod equilibrium_cmd;
mod plot;
mod progress;
mod slurm_cmd;
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
    /// One steady EHL point contact (contact file or Moes parameters).
    Ehl(ehl_cmd::EhlArgs),
    /// Characterize one lubricated contact: fit Q = K·δ^d + ΔF to EHL solutions.
    Contact(contact_cmd::ContactArgs),
    /// Linearized 5×5 stiffness and damping of the lubricated bearing over speed (JSON, CSV, ROSS table).
    Coefficients(coefficients_cmd::CoefficientsArgs),
}

fn main() -> ExitCode {
    // A closed stdout (e.g. `ehl-bearing study … | head -1`) ends the program quietly, as for
    // other command-line tools, instead of a panic on the failed write. Finished point files are
    // safe: every file is written atomically, and a rerun resumes.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Equilibrium(a) => equilibrium_cmd::run(a),
        Command::Characterize(a) => characterize_cmd::run(a),
        Command::Study(a) => study_cmd::run(a),
        Command::Ehl(a) => ehl_cmd::run(a),
        Command::Contact(a) => contact_cmd::run(a),
        Command::Coefficients(a) => coefficients_cmd::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
