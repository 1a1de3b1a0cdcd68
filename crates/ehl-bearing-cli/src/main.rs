//! `ehl-bearing` command line: thin layer over the `ehl-bearing` library.

mod characterize_cmd;
mod cli_support;
mod coefficients_cmd;
mod contact_cmd;
mod ehl_cmd;
mod equilibrium_cmd;
mod law_map_cmd;
mod law_map_slurm;
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
    /// Map of the dimensionless quasi-static law over the groups: generate (resumable,
    /// shardable), assemble, check against direct characterizations.
    LawMap(law_map_cmd::LawMapArgs),
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
        Command::LawMap(a) => law_map_cmd::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// The fuzzing tests' SplitMix64 generator.
#[cfg(test)]
#[path = "../../ehl-bearing/tests/splitmix/mod.rs"]
mod splitmix;

/// Command-line parsing over many generated argument lists, in process (the runs themselves:
/// `tests/fuzz_cli.rs`): clap must return arguments or an error, never panic. Default: 20 000
/// lists; `FUZZ_ARGS=1000000 cargo test -p ehl-bearing-cli --bin ehl-bearing fuzz_parse --
/// --ignored` for more.
#[cfg(test)]
mod fuzz_parse {

    use super::Cli;
    use clap::Parser;

    const WORDS: [&str; 40] = [
        "equilibrium",
        "characterize",
        "study",
        "merge",
        "ehl",
        "contact",
        "coefficients",
        "case.toml",
        "-o",
        "out",
        "--json",
        "--method",
        "hertz",
        "quasi-static",
        "--threads",
        "--tolerance",
        "--max-iterations",
        "--time-limit",
        "--grid",
        "--moes-m",
        "--moes-l",
        "--ry-over-rx",
        "--viscosity",
        "barus",
        "--shard",
        "2/3",
        "0/0",
        "--speeds",
        "1,2,,x",
        "--points",
        "--fields",
        "--overwrite",
        "--film",
        "nan",
        "-1",
        "1e400",
        "",
        "--",
        "-",
        "--help",
    ];

    fn lists(seed: u64, n: u64) -> usize {
        let mut rng = super::splitmix::Rng(seed);
        let mut next = move || rng.next();
        let mut parsed = 0;
        for _ in 0..n {
            let len = (next() % 8) as usize;
            let mut args = vec!["ehl-bearing".to_string()];
            for _ in 0..len {
                let r = next();
                args.push(if r % 11 == 0 {
                    format!("{}", f64::from_bits(next()))
                } else {
                    WORDS[(r % WORDS.len() as u64) as usize].to_string()
                });
            }
            if Cli::try_parse_from(&args).is_ok() {
                parsed += 1;
            }
        }
        parsed
    }

    #[test]
    fn parsing_never_panics() {
        let parsed = lists(15, 20_000);
        // Some lists are complete commands.
        assert!(parsed > 100, "{parsed}");
    }

    #[test]
    #[ignore]
    fn parsing_never_panics_many() {
        let n = std::env::var("FUZZ_ARGS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(1_000_000);
        let t0 = std::time::Instant::now();
        let parsed = lists(15, n);
        println!(
            "{n} argument lists parsed in {:.1} s: {parsed} accepted, {} refused",
            t0.elapsed().as_secs_f64(),
            n as usize - parsed
        );
    }
}
