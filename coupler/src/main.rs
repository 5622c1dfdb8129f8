//! `coupler`: run a case, replay a recording, or check a case file.

use clap::{Parser, Subcommand};
use coupler::error::CouplerError;
use coupler::replay::{replay, ReplayOptions};
use coupler::report::{report, ReportOptions};
use coupler::run::{run, RunOptions};
use schemas::case::Case;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;

/// Tsunami–structure simulations as cooperating processes: a particle fluid solver and a
/// structure solver, coupled through shared memory.
#[derive(Parser)]
#[command(version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a case: starts only the solvers it needs, couples them window by window, and writes
    /// the recording, the action–reaction ledger and each solver's output to the output folder.
    Run {
        /// The case file (e.g. cases/oscillator/case.toml).
        case: PathBuf,
        /// Output folder (default: out/<case name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Use another executable for a participant: --exe NAME=PATH (repeatable).
        #[arg(long, value_name = "NAME=PATH", value_parser = parse_exe)]
        exe: Vec<(String, PathBuf)>,
    },
    /// Drive one solver with its partners' recorded messages and compare its answers with the
    /// recorded ones; exits non-zero when it departs.
    Replay {
        /// A recording written by `coupler run` (out/<case>/recording.rec).
        recording: PathBuf,
        /// The participant to replay.
        #[arg(long)]
        participant: String,
        /// Use this executable instead of the participant's default solver.
        #[arg(long)]
        exe: Option<PathBuf>,
        /// Replay against this case file instead of the recorded one (e.g. a changed parameter).
        #[arg(long)]
        case: Option<PathBuf>,
        /// Largest relative difference per field that still passes.
        #[arg(long, default_value_t = 1e-9)]
        tolerance: f64,
        /// Output folder (default: out/replay-<participant>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Check a case file and list its participants, without starting anything.
    Check { case: PathBuf },
    /// Error against run time (work–precision) of each case's [report] ladders, or with
    /// --stability its families of stiff and extreme runs; --readme puts the latest report into
    /// the README.
    Report {
        /// Case files with [reference] and [report] sections.
        cases: Vec<PathBuf>,
        /// Report folder (default: out/report).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The full ladders and families instead of the CI-sized ones.
        #[arg(long)]
        full: bool,
        /// Run the stability families instead of the ladders.
        #[arg(long)]
        stability: bool,
        /// Timed runs after the warm-up (default: each case's report.repeats).
        #[arg(long)]
        repeats: Option<u32>,
        /// Put the latest report of --out into this README's marked sections; runs nothing.
        #[arg(long, value_name = "README", num_args = 0..=1, default_missing_value = "README.md")]
        readme: Option<PathBuf>,
        /// With --stability: only the family of this name (repeatable).
        #[arg(long)]
        family: Vec<String>,
    },
}

fn parse_exe(s: &str) -> Result<(String, PathBuf), String> {
    match s.split_once('=') {
        Some((name, path)) if !name.is_empty() && !path.is_empty() => {
            Ok((name.to_string(), PathBuf::from(path)))
        }
        _ => Err(format!("expected NAME=PATH, got `{s}`")),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { case, out, exe } => run(&RunOptions {
            case,
            out,
            exe: exe.into_iter().collect::<BTreeMap<_, _>>(),
        }),
        Command::Replay {
            recording,
            participant,
            exe,
            case,
            tolerance,
            out,
        } => replay(&ReplayOptions {
            recording,
            participant,
            exe,
            case,
            tolerance,
            out,
        })
        .map(|_| ()),
        Command::Check { case } => check(&case),
        Command::Report {
            cases,
            out,
            full,
            stability,
            repeats,
            readme,
            family,
        } => report(&ReportOptions {
            cases,
            out,
            full,
            stability,
            repeats,
            readme,
            families: family,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn check(path: &std::path::Path) -> Result<(), CouplerError> {
    let case = Case::load(path)?;
    println!(
        "{}: case `{}`, end time {} s",
        path.display(),
        case.info.name,
        case.info.end_time
    );
    for (name, kind) in case.participants() {
        println!("  participant {name}: {}", kind.binary_name());
    }
    if let Some(c) = &case.coupling {
        println!(
            "  coupling: {:?}, window {} s, {} sample(s) per window",
            c.scheme, c.window, c.samples
        );
    }
    if let Some(r) = &case.reference {
        println!(
            "  reference: {:?}, {:?} error ({})",
            r.against, r.measure, r.source
        );
    }
    if let Some(r) = &case.report {
        println!(
            "  report: {} ladder(s), {} stability family(ies)",
            r.ladder.len(),
            r.stability.len()
        );
    }
    Ok(())
}
