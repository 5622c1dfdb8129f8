//! `fluid-solver run CASE [--out DIR]`: runs a fluid-only case standalone;
//! `fluid-solver participant …`: one fluid participant inside a coupled run (started by the coupler).

use clap::{Parser, Subcommand};
use fluid_solver::participant::FluidParticipant;
use schemas::case::fluid::FluidBackend;
use schemas::case::{Case, CaseError};
use schemas::participant::{serve, ParticipantArgs};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

/// 3D E-MPS fluid solver (Saitoh & Akitomo) with particle walls.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the single [fluid.NAME] participant of a fluid-only case to case.end_time.
    Run {
        /// The case file (case.toml).
        case: PathBuf,
        /// Output folder (default: out/<case name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Where the step runs, overriding the case's `backend`: cpu or gpu (E-MPS, fluid-only).
        #[arg(long, value_parser = ["cpu", "gpu"])]
        backend: Option<String>,
    },
    /// Serve one [fluid.NAME] participant of a coupled run (started by `coupler run`).
    Participant(ParticipantArgs),
}

fn participant(args: &ParticipantArgs) -> Result<(), String> {
    let case = Case::load_to(&args.case, args.end_time).map_err(|e| e.to_string())?;
    let mut solver = match &args.resume {
        Some(from) => FluidParticipant::resume(&case, &args.name, args.out.as_deref(), from)?,
        None => FluidParticipant::from_case(&case, &args.name, args.out.as_deref())?,
    };
    serve(args, case.hash, &mut solver).map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Participant(args) => match participant(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        Command::Run { case, out, backend } => {
            let mut case = match Case::load(&case) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Err(e) = set_backend(&mut case, backend.as_deref()) {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            let out = out.unwrap_or_else(|| PathBuf::from("out").join(&case.info.name));
            let terminal = std::io::stderr().is_terminal();
            match fluid_solver::run::run_case(&case, &out, terminal) {
                Ok(s) => {
                    eprintln!("done: {s}; output in {}", out.display());
                    ExitCode::SUCCESS
                }
                Err(e @ fluid_solver::run::RunError::Gpu { .. }) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
    }
}

/// `--backend`: sets every fluid section's backend and checks that the GPU path runs it.
fn set_backend(case: &mut Case, backend: Option<&str>) -> Result<(), CaseError> {
    let backend = match backend {
        None => return Ok(()),
        Some("gpu") => FluidBackend::Gpu,
        Some(_) => FluidBackend::Cpu,
    };
    for (name, cfg) in case.fluid.iter_mut() {
        cfg.backend = backend;
        if backend == FluidBackend::Gpu {
            cfg.gpu_support(&format!("fluid.{name}"))
                .map_err(|e| CaseError::at(&case.path, e))?;
        }
    }
    Ok(())
}
