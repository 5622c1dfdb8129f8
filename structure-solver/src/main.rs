//! `structure-solver`: `run CASE [--out DIR]` for a structure-only case, `participant …` inside a
//! coupled run started by the coupler.

use clap::{Parser, Subcommand};
use schemas::case::Case;
use schemas::participant::{serve, ParticipantArgs};
use std::path::PathBuf;
use std::process::ExitCode;
use structure_solver::participant::StructureParticipant;
use structure_solver::standalone;

/// Point masses, springs, rigid bodies with washout supports and ASI-Gauss frames.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a structure-only case under its prescribed loads to case.end_time.
    Run {
        /// The case file (one [structure.NAME] section, no fluid).
        case: PathBuf,
        /// Output folder (default: out/<case name>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Take part in a coupled run (started by the coupler).
    Participant(ParticipantArgs),
}

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Run { case, out } => standalone::run(&case, out.as_deref()).map(|s| {
            for w in &s.warnings {
                eprintln!("warning: {w}");
            }
            println!(
                "done: t = {} s in {} substeps; releases: {}; output in {}",
                s.end_time,
                s.substeps,
                if s.releases.is_empty() {
                    "none".to_string()
                } else {
                    format!("{:?}", s.releases)
                },
                s.out_dir.display()
            );
        }),
        Command::Participant(args) => participant(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn participant(args: &ParticipantArgs) -> Result<(), String> {
    let case = Case::load_to(&args.case, args.end_time).map_err(|e| e.to_string())?;
    let mut solver = match &args.resume {
        Some(from) => StructureParticipant::resume(&case, &args.name, args.out.as_deref(), from)?,
        None => StructureParticipant::from_case(&case, &args.name, args.out.as_deref())?,
    };
    serve(args, case.hash, &mut solver).map_err(|e| e.to_string())
}
