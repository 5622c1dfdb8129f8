//! The participant side of the protocol: a solver implements [`Participant`] and calls [`serve`].
//!
//! The loop: open the link, wait for the coupler, say [`Hello`], get `Welcome` (or `Refused`),
//! send the initial outputs, then answer every `Advance` until `Finish`. The coupler's liveness
//! is checked during every wait; a participant whose coupler is gone stops. While the solver works
//! on a window it reports its steps ([`progress`]), so that a window longer than
//! `coupling.timeout` is not taken for a hang.
//!
//! SIGTERM and SIGINT (the coupler stopping the run, or the kernel when the coupler died) do not
//! kill a participant in the middle of writing an output: they are noted ([`crate::signals`]), the
//! answer being computed is finished, and the participant stops at its next wait, with every row
//! and frame written so far whole. Rows of the last answered window that the coupler had not yet
//! accepted (written at the next window's start or at `Finish`) are not written.

mod progress;

pub use progress::{DiscardProgress, LinkProgress, ProgressSink, ReportingWriter};

use crate::link::{process_alive, Link, LinkError, Side};
use crate::message::{
    Checkpoint, Fields, FromParticipant, Geometry, Header, Hello, InterfaceDecl, Role, ToParticipant,
    Waveform, PROTOCOL_VERSION,
};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A solver that can take part in a coupled run.
pub trait Participant {
    /// Fluid or structure.
    fn role(&self) -> Role;
    /// Simulated time the solver has reached.
    fn time(&self) -> f64;
    /// Names that fix the order of the interface arrays.
    fn interface(&self) -> InterfaceDecl;
    /// Interface outputs at t = 0.
    fn initial_outputs(&mut self) -> Fields;
    /// Member geometry, when it changed since the last call (beam frames only).
    fn geometry_update(&mut self) -> Option<Geometry> {
        None
    }
    /// Keeps the current state (the window start) in memory.
    fn save_checkpoint(&mut self);
    /// Goes back to the state kept by the last [`Participant::save_checkpoint`].
    fn restore_checkpoint(&mut self) -> Result<(), String>;
    /// Advances from `inputs.start()` to exactly `inputs.end()`, reading inputs with
    /// `inputs.at(t)`; returns the outputs at each of `inputs.times` (the first is the window start).
    fn advance(&mut self, inputs: &Waveform) -> Result<Vec<Fields>, String>;
    /// [`Participant::advance`], telling `progress` of every solver step it finishes, so that the
    /// coupler does not take a window longer than `coupling.timeout` for a hang. The default
    /// reports nothing: then each whole answer must come within the timeout.
    fn advance_reporting(
        &mut self,
        inputs: &Waveform,
        progress: &mut dyn ProgressSink,
    ) -> Result<Vec<Fields>, String> {
        let _ = progress;
        self.advance(inputs)
    }
    /// The run is over: write final output, telling `progress` of the bytes written
    /// ([`ReportingWriter`]), so that a long write is not taken for a hang.
    fn finish(&mut self, progress: &mut dyn ProgressSink) -> Result<(), String>;
    /// Writes every output kept back from the accepted window, then the full state (solver, output
    /// bookkeeping) to `path` with [`crate::checkpoint::write`], telling `progress` of the bytes
    /// written; returns the checkpoint's size in bytes. A solver that cannot do this says so, and
    /// the run stops with that message.
    fn write_checkpoint(&mut self, path: &Path, progress: &mut dyn ProgressSink) -> Result<u64, String> {
        let _ = (path, progress);
        Err("this solver cannot write checkpoints".into())
    }
}

/// Command-line arguments every solver takes in participant mode (`SOLVER participant …`).
#[derive(clap::Args, Debug, Clone)]
pub struct ParticipantArgs {
    /// The case file.
    #[arg(long)]
    pub case: PathBuf,
    /// This participant's name in the case.
    #[arg(long)]
    pub name: String,
    /// Run id given by the coupler; it keeps the shared-memory services of concurrent runs apart.
    #[arg(long)]
    pub run_id: String,
    /// The coupler's process id; the participant stops when the coupler is gone.
    #[arg(long)]
    pub coupler_pid: u32,
    /// Folder for this participant's own output (VTU, CSV).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Continue from this checkpoint file (written on the coupler's `WriteCheckpoint`) instead of
    /// t = 0: the solver restores its state and appends to the output files in `--out`, which the
    /// coupler has cut back to their length at the checkpoint.
    #[arg(long)]
    pub resume: Option<PathBuf>,
    /// Simulate to this time [s] instead of the case's `case.end_time` (the coupler passes on its
    /// own `run --end-time`).
    #[arg(long, value_name = "SECONDS")]
    pub end_time: Option<f64>,
    /// Wall seconds between two progress reports while a window is computed (the coupler passes a
    /// quarter of `coupling.timeout`, at most 5 s).
    #[arg(
        long,
        value_name = "SECONDS",
        default_value_t = DEFAULT_PROGRESS_INTERVAL,
        value_parser = positive_seconds
    )]
    pub progress_interval: f64,
}

/// Wall seconds between progress reports when `--progress-interval` is not given.
pub const DEFAULT_PROGRESS_INTERVAL: f64 = 5.0;

/// A positive, finite number of seconds.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s.is_finite() && s > 0.0 => Ok(s),
        _ => Err(format!("must be a positive number of seconds, got `{text}`")),
    }
}

/// Why a participant stopped.
#[derive(Debug)]
pub enum ServeError {
    Link(LinkError),
    /// The coupler refused the handshake.
    Refused(String),
    /// The solver failed; the coupler was told.
    Solver(String),
    /// The coupler sent something out of order.
    Protocol(String),
    /// SIGTERM or SIGINT arrived; the participant stopped between two answers.
    Stopped,
}

impl std::fmt::Display for ServeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ServeError::Link(e) => write!(f, "link to the coupler: {e}"),
            ServeError::Refused(r) => write!(f, "the coupler refused this participant: {r}"),
            ServeError::Solver(m) => write!(f, "solver failed: {m}"),
            ServeError::Protocol(m) => write!(f, "protocol error: {m}"),
            ServeError::Stopped => write!(
                f,
                "stopped by SIGTERM or SIGINT between two windows; every output written so far is whole"
            ),
        }
    }
}

impl std::error::Error for ServeError {}

impl From<LinkError> for ServeError {
    fn from(e: LinkError) -> Self {
        ServeError::Link(e)
    }
}

/// How long a participant waits for its coupler to open the link.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(30);

/// Runs the participant protocol with this crate's protocol version.
pub fn serve<P: Participant>(
    args: &ParticipantArgs,
    case_hash: u64,
    solver: &mut P,
) -> Result<(), ServeError> {
    serve_announcing(args, case_hash, solver, PROTOCOL_VERSION)
}

/// Runs the participant protocol announcing `protocol` (another version is refused by the
/// coupler; tests use this to check the refusal).
pub fn serve_announcing<P: Participant>(
    args: &ParticipantArgs,
    case_hash: u64,
    solver: &mut P,
    protocol: u32,
) -> Result<(), ServeError> {
    crate::signals::install();
    stop_with_parent();
    match serve_until_stopped(args, case_hash, solver, protocol) {
        Err(_) if crate::signals::interrupted() => Err(ServeError::Stopped),
        other => other,
    }
}

fn serve_until_stopped<P: Participant>(
    args: &ParticipantArgs,
    case_hash: u64,
    solver: &mut P,
    protocol: u32,
) -> Result<(), ServeError> {
    let link = Link::open(&args.run_id, &args.name, Side::Participant)?;
    let coupler = args.coupler_pid;
    let mut alive = move || {
        if crate::signals::interrupted() {
            return Err("stopped by SIGTERM or SIGINT".to_string());
        }
        process_alive(coupler).map_err(|e| format!("the coupler (pid {coupler}) is gone: {e}"))
    };
    link.wait_for_peer(Instant::now() + CONNECT_TIMEOUT, &mut alive)?;
    let hello = Hello {
        protocol,
        role: solver.role(),
        name: args.name.clone(),
        case_hash,
        pid: std::process::id(),
        interface: solver.interface(),
    };
    link.send(&FromParticipant::Hello(hello))?;
    match link.recv::<ToParticipant>(None, &mut alive)? {
        ToParticipant::Welcome { .. } => {}
        ToParticipant::Refused { reason } => return Err(ServeError::Refused(reason)),
        other => {
            return Err(ServeError::Protocol(format!(
                "expected Welcome, got {}",
                name_of(&other)
            )))
        }
    }
    let outputs = solver.initial_outputs();
    let geometry = solver.geometry_update();
    link.send(&FromParticipant::Initial { outputs, geometry })?;
    let report_every = Duration::try_from_secs_f64(args.progress_interval).unwrap_or(Duration::MAX);
    // the window of the last request to advance, which the progress of the final writes names
    let mut last_window = 0;
    loop {
        if crate::signals::interrupted() {
            // A request may already be waiting, so the wait below would not look at the flag.
            return Err(ServeError::Stopped);
        }
        match link.recv::<ToParticipant>(None, &mut alive)? {
            ToParticipant::Advance {
                header,
                checkpoint,
                inputs,
            } => {
                last_window = header.window;
                let result = match checkpoint {
                    Checkpoint::None => Ok(()),
                    Checkpoint::Save => {
                        solver.save_checkpoint();
                        Ok(())
                    }
                    Checkpoint::Restore => solver.restore_checkpoint(),
                }
                .and_then(|()| {
                    let mut progress = LinkProgress::new(&link, header, report_every);
                    solver.advance_reporting(&inputs, &mut progress)
                })
                .and_then(|outputs| {
                    if outputs.len() == inputs.times.len() {
                        Ok(outputs)
                    } else {
                        Err(format!(
                            "the solver returned {} output samples for {} input times",
                            outputs.len(),
                            inputs.times.len()
                        ))
                    }
                });
                match result {
                    Ok(samples) => {
                        let outputs = Waveform {
                            times: inputs.times.clone(),
                            samples,
                        };
                        let geometry = solver.geometry_update();
                        let reached = Header {
                            time: solver.time(),
                            ..header
                        };
                        link.send(&FromParticipant::Advanced {
                            header: reached,
                            outputs,
                            geometry,
                        })?;
                    }
                    Err(diagnostic) => {
                        link.send(&FromParticipant::Failed {
                            header,
                            diagnostic: diagnostic.clone(),
                        })?;
                        return Err(ServeError::Solver(diagnostic));
                    }
                }
            }
            ToParticipant::WriteCheckpoint { window, path } => {
                let request = Header {
                    protocol,
                    window,
                    iteration: 0,
                    time: solver.time(),
                };
                let mut progress = LinkProgress::new(&link, request, report_every);
                match solver.write_checkpoint(Path::new(&path), &mut progress) {
                    Ok(bytes) => {
                        link.send(&FromParticipant::CheckpointWritten { window, bytes })?;
                    }
                    Err(diagnostic) => {
                        let header = Header {
                            protocol,
                            window,
                            iteration: 0,
                            time: solver.time(),
                        };
                        link.send(&FromParticipant::Failed {
                            header,
                            diagnostic: diagnostic.clone(),
                        })?;
                        return Err(ServeError::Solver(diagnostic));
                    }
                }
            }
            ToParticipant::Finish => {
                let request = Header {
                    protocol,
                    window: last_window,
                    iteration: 0,
                    time: solver.time(),
                };
                let mut progress = LinkProgress::new(&link, request, report_every);
                let done = solver.finish(&mut progress);
                link.send(&FromParticipant::Finished)?;
                return done.map_err(ServeError::Solver);
            }
            other => {
                return Err(ServeError::Protocol(format!(
                    "unexpected {} during the run",
                    name_of(&other)
                )))
            }
        }
    }
}

fn name_of(m: &ToParticipant) -> &'static str {
    match m {
        ToParticipant::Welcome { .. } => "Welcome",
        ToParticipant::Refused { .. } => "Refused",
        ToParticipant::Advance { .. } => "Advance",
        ToParticipant::Finish => "Finish",
        ToParticipant::WriteCheckpoint { .. } => "WriteCheckpoint",
    }
}

/// Asks the kernel to end this process when its parent (the coupler) dies.
fn stop_with_parent() {
    #[cfg(target_os = "linux")]
    // SAFETY: prctl(PR_SET_PDEATHSIG) takes a signal number and touches no memory of ours.
    unsafe {
        libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM);
    }
}
