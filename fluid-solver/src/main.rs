//! `fluid-solver run CASE [--out DIR]`: runs a fluid-only case standalone (on MPI ranks when
//! started by `mpirun -np N` and built with the `mpi` feature);
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
    if let Some(served) = ranks::participant_if_launched(&case, args) {
        return served;
    }
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
                // an empty message: another rank reports it
                if !e.is_empty() {
                    eprintln!("error: {e}");
                }
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
            if let Some(code) = ranks::run_if_launched(&case, &out) {
                return code;
            }
            for (name, cfg) in case.fluid.iter().filter(|(_, cfg)| cfg.rank_count() > 1) {
                eprintln!(
                    "note: fluid.{name}.ranks = {}, but no MPI launcher started this process: the fluid runs in one process (`coupler run` starts the ranks)",
                    cfg.rank_count()
                );
            }
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

/// A standalone run started by an MPI launcher (`mpirun`, `srun`): on the ranks with the `mpi`
/// feature, refused without it (each process would run the whole case into the same files).
mod ranks {
    use schemas::case::Case;
    use schemas::participant::ParticipantArgs;
    use std::path::Path;
    use std::process::ExitCode;

    /// The ranks' run and its exit code, or `None` when no launcher started this process.
    #[cfg(feature = "mpi")]
    pub fn run_if_launched(case: &Case, out: &Path) -> Option<ExitCode> {
        use fluid_solver::ranks::launcher::launched_by_mpi;
        use fluid_solver::ranks::mpi_link::RankLink;
        use fluid_solver::ranks::rank_run::{run_on_ranks, RankRunError};
        use fluid_solver::run::RunError;
        if !launched_by_mpi() {
            return None;
        }
        let link = match RankLink::initialize() {
            Ok(link) => link,
            Err(e) => {
                eprintln!("error: {e}");
                return Some(ExitCode::FAILURE);
            }
        };
        let rank = link.rank();
        let counted = case.fluid.iter().try_for_each(|(name, cfg)| {
            fluid_solver::ranks::launcher::check_rank_count(cfg.ranks, link.size(), name)
        });
        if let Err(e) = counted {
            if rank == 0 {
                eprintln!("error: {}: {e}", case.path.display());
            }
            return Some(ExitCode::from(2));
        }
        if link.size() == 1 {
            return None;
        }
        threads_per_rank();
        Some(match run_on_ranks(case, out, &link) {
            Ok(s) => {
                if rank == 0 {
                    eprintln!("done: {s}; output in {}", out.display());
                }
                ExitCode::SUCCESS
            }
            Err(RankRunError::Setup(e)) => {
                if rank == 0 {
                    eprintln!("error: {e}");
                }
                ExitCode::from(2)
            }
            Err(RankRunError::Here(e @ RunError::Unstable(_))) => {
                eprintln!("error: rank {rank}: {e}");
                ExitCode::FAILURE
            }
            Err(e @ RankRunError::Here(_)) => {
                // the other ranks do not know: stop them rather than leave them waiting
                eprintln!("error: rank {rank}: {e}; stopping every rank");
                link.abort(1)
            }
            Err(RankRunError::Elsewhere { .. }) => ExitCode::FAILURE,
        })
    }

    /// A participant on the ranks a launcher started (the coupler, for a fluid section with
    /// `ranks` > 1): rank 0 serves the coupler, the others follow it; `None` when no launcher
    /// started this process or it started one rank.
    #[cfg(feature = "mpi")]
    pub fn participant_if_launched(case: &Case, args: &ParticipantArgs) -> Option<Result<(), String>> {
        use fluid_solver::ranks::launcher::{check_rank_count, launched_by_mpi};
        use fluid_solver::ranks::mpi_link::RankLink;
        use fluid_solver::ranks::rank_participant::{follow, Leader, RankParticipant};
        use schemas::participant::serve;
        if !launched_by_mpi() {
            return None;
        }
        let link = match RankLink::initialize() {
            Ok(link) => link,
            Err(e) => return Some(Err(e)),
        };
        let ranks = case.fluid.get(&args.name).and_then(|cfg| cfg.ranks);
        if let Err(e) = check_rank_count(ranks, link.size(), &args.name) {
            return Some(Err(format!("{}: {e}", case.path.display())));
        }
        if link.size() == 1 {
            return None;
        }
        threads_per_rank();
        let out = args.out.as_deref();
        let ranks = match &args.resume {
            Some(from) => RankParticipant::resume(case, &args.name, out, from, &link),
            None => RankParticipant::from_case(case, &args.name, out, &link),
        };
        Some(match (link.rank(), ranks) {
            (0, Ok(ranks)) => {
                schemas::signals::install();
                let mut leader = Leader::new(ranks);
                let served = serve(args, case.hash, &mut leader).map_err(|e| e.to_string());
                leader.stop_the_others();
                served
            }
            (_, Ok(ranks)) => {
                schemas::signals::install();
                follow(ranks)
            }
            (0, Err(e)) => Err(e),
            // rank 0 reports what every rank found
            (_, Err(_)) => Err(String::new()),
        })
    }

    /// Without the `mpi` feature: an error when a launcher started more than one process.
    #[cfg(not(feature = "mpi"))]
    pub fn run_if_launched(_case: &Case, _out: &Path) -> Option<ExitCode> {
        let size = fluid_solver::ranks::launcher::launched_ranks()?;
        (size > 1).then(|| {
            eprintln!("error: {}", without_mpi(size));
            ExitCode::from(2)
        })
    }

    /// Without the `mpi` feature: an error when a launcher started more than one process.
    #[cfg(not(feature = "mpi"))]
    pub fn participant_if_launched(_case: &Case, _args: &ParticipantArgs) -> Option<Result<(), String>> {
        let size = fluid_solver::ranks::launcher::launched_ranks()?;
        (size > 1).then(|| Err(without_mpi(size)))
    }

    #[cfg(not(feature = "mpi"))]
    fn without_mpi(size: usize) -> String {
        format!(
            "started as {size} MPI ranks, but this fluid-solver was built without MPI: build it with `cargo build --release --features fluid-solver/mpi` (needs OpenMPI and libclang), or set the case's ranks = 1 (or run it without mpirun)"
        )
    }

    /// Shares the machine's cores among the ranks on it (unless `RAYON_NUM_THREADS` says how
    /// many threads each takes): each rank's threads are its cores divided by the ranks the
    /// launcher put on this node.
    #[cfg(feature = "mpi")]
    fn threads_per_rank() {
        if std::env::var_os("RAYON_NUM_THREADS").is_some() {
            return;
        }
        let on_node = fluid_solver::ranks::launcher::ranks_on_node();
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads((cores / on_node).max(1))
            .build_global();
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
