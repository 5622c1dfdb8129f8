//! What can stop a coupled run, each with the message a user needs.

use schemas::case::CaseError;
use std::fmt;

/// Why the coupler stopped before the end of the run.
#[derive(Debug)]
pub enum CouplerError {
    /// The case file is wrong; nothing was started.
    Case(CaseError),
    /// A command-line value is wrong; nothing was started.
    Usage(String),
    /// A participant died, hung, failed or broke the protocol.
    Participant {
        name: String,
        window: Option<u64>,
        message: String,
    },
    /// An implicit window did not converge.
    NotConverged {
        window: u64,
        time: f64,
        iterations: u32,
        residual: f64,
        field: String,
    },
    /// The coupling created energy at the interface beyond the detector's threshold
    /// ([`crate::stability`]).
    Unstable { window: u64, time: f64, message: String },
    /// Ctrl-C or SIGTERM.
    Interrupted { window: Option<u64> },
    /// Output could not be written.
    Io(String),
    /// A replay that cannot pass: nothing or less than the recording compared, or a damaged recording.
    Replay(String),
}

impl CouplerError {
    /// Exit code: 2 for bad input (nothing ran), 130 for Ctrl-C, 1 otherwise.
    pub fn exit_code(&self) -> i32 {
        match self {
            CouplerError::Case(_) | CouplerError::Usage(_) => 2,
            CouplerError::Interrupted { .. } => 130,
            _ => 1,
        }
    }

    /// The window the error happened in, when it is known.
    pub fn window(&self) -> Option<u64> {
        match self {
            CouplerError::Participant { window, .. } | CouplerError::Interrupted { window } => *window,
            CouplerError::NotConverged { window, .. } | CouplerError::Unstable { window, .. } => {
                Some(*window)
            }
            _ => None,
        }
    }
}

fn at(window: &Option<u64>) -> String {
    window
        .map(|w| format!(" in window {w}"))
        .unwrap_or_else(|| " before the first window".into())
}

impl fmt::Display for CouplerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CouplerError::Case(e) => write!(f, "bad case file: {e}"),
            CouplerError::Usage(m) => write!(f, "{m}"),
            CouplerError::Participant { name, window, message } => {
                write!(f, "participant `{name}`{}: {message}", at(window))
            }
            CouplerError::NotConverged { window, time, iterations, residual, field } => write!(
                f,
                "window {window} (t = {time:.6} s) did not converge in {iterations} iterations: relative residual \
                 {residual:.3e} in `{field}`; raise coupling.max_iterations, shorten coupling.window or change \
                 coupling.acceleration"
            ),
            CouplerError::Unstable { window, time, message } => {
                write!(f, "coupling instability in window {window} (t = {time:.6} s): {message}")
            }
            CouplerError::Interrupted { window } => write!(f, "interrupted{}; participants stopped", at(window)),
            CouplerError::Io(m) | CouplerError::Replay(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for CouplerError {}

impl From<CaseError> for CouplerError {
    fn from(e: CaseError) -> Self {
        CouplerError::Case(e)
    }
}
