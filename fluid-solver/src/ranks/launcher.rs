//! What an MPI launcher (`mpirun`, `srun`) tells the processes it starts, through their
//! environment: read with or without the `mpi` feature, so that a build without it can refuse
//! to run once per rank.

/// The environment variables a launcher sets in every rank it starts (OpenMPI, MPICH's Hydra,
/// Slurm's PMI and PMIx).
const LAUNCHER_VARIABLES: [&str; 4] = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "PMI_RANK"];

/// Whether this process was started by an MPI launcher.
pub fn launched_by_mpi() -> bool {
    LAUNCHER_VARIABLES.iter().any(|v| std::env::var_os(v).is_some())
}

/// How many ranks the launcher started, where it says (OpenMPI, MPICH's Hydra).
pub fn launched_ranks() -> Option<usize> {
    first_number(&["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"])
}

/// How many ranks the launcher put on this node (1 where it does not say).
pub fn ranks_on_node() -> usize {
    first_number(&[
        "OMPI_COMM_WORLD_LOCAL_SIZE",
        "MPI_LOCALNRANKS",
        "SLURM_NTASKS_PER_NODE",
    ])
    .unwrap_or(1)
    .max(1)
}

/// The first of `variables` set to a number.
fn first_number(variables: &[&str]) -> Option<usize> {
    variables
        .iter()
        .find_map(|v| std::env::var(v).ok()?.parse::<usize>().ok())
}

/// An error when the launcher started `started` ranks for fluid `name` of a case that sets
/// another number (`ranks`, `None` when the case does not say).
pub fn check_rank_count(ranks: Option<usize>, started: usize, name: &str) -> Result<(), String> {
    match ranks {
        Some(n) if n != started => Err(format!(
            "started as {started} MPI ranks, but fluid.{name}.ranks = {n}: start {n} (`coupler run` starts them through the section's launcher)"
        )),
        _ => Ok(()),
    }
}
