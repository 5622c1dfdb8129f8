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
    /// A participant failed while the run was being finished, after its last window (its output
    /// of the whole run was written).
    AfterLastWindow { name: String, message: String },
    /// An implicit window did not converge; `history` is the worst relative residual of each sweep.
    NotConverged {
        window: u64,
        time: f64,
        iterations: u32,
        residual: f64,
        field: String,
        history: Vec<f64>,
    },
    /// The coupling created energy at the interface beyond the detector's threshold
    /// ([`crate::stability`]).
    Unstable { window: u64, time: f64, message: String },
    /// Ctrl-C, SIGTERM or SIGHUP (named in the message).
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

    /// The error of a participant that failed while the run was being finished: the same error
    /// placed after the last window instead of before the first.
    pub fn after_last_window(self) -> CouplerError {
        match self {
            CouplerError::Participant {
                name,
                window: None,
                message,
            } => CouplerError::AfterLastWindow { name, message },
            other => other,
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
            CouplerError::Participant {
                name,
                window,
                message,
            } => {
                write!(f, "participant `{name}`{}: {message}", at(window))
            }
            CouplerError::AfterLastWindow { name, message } => {
                write!(f, "participant `{name}` after the last window: {message}")
            }
            CouplerError::NotConverged {
                window,
                time,
                iterations,
                residual,
                field,
                history,
            } => {
                write!(
                    f,
                    "window {window} (t = {time:.6} s) did not converge in {iterations} iterations: relative residual \
                     {residual:.3e} in `{field}`; "
                )?;
                match stalled(history) {
                    Some((early, late)) => write!(
                        f,
                        "the residual stopped falling (best {early:.3e} in the first half of the sweeps, {late:.3e} \
                         in the second), so this window may have no fixed point: the response jumps between \
                         iterates (for a light body, the fluid's collision stage switching on and off); more \
                         iterations will not help: shorten coupling.window, make the body heavier or use \
                         coupling.scheme = \"explicit\""
                    ),
                    None => write!(
                        f,
                        "raise coupling.max_iterations, shorten coupling.window or change coupling.acceleration"
                    ),
                }
            }
            CouplerError::Unstable {
                window,
                time,
                message,
            } => {
                write!(
                    f,
                    "coupling instability in window {window} (t = {time:.6} s): {message}"
                )
            }
            CouplerError::Interrupted { window } => {
                let by = schemas::signals::received()
                    .map(|s| format!(" by {s}"))
                    .unwrap_or_default();
                write!(f, "interrupted{}{by}; participants stopped", at(window))
            }
            CouplerError::Io(m) | CouplerError::Replay(m) => write!(f, "{m}"),
        }
    }
}

/// The best residual of the first and of the second half of a window's sweeps when the second
/// half did not halve it (at least 6 sweeps): iterating longer is then not the way out.
fn stalled(history: &[f64]) -> Option<(f64, f64)> {
    if history.len() < 6 {
        return None;
    }
    let best = |r: &[f64]| r.iter().copied().fold(f64::INFINITY, f64::min);
    let (first, second) = history.split_at(history.len() / 2);
    let (early, late) = (best(first), best(second));
    (late > 0.5 * early).then_some((early, late))
}

impl std::error::Error for CouplerError {}

impl From<CaseError> for CouplerError {
    fn from(e: CaseError) -> Self {
        CouplerError::Case(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn not_converged(history: Vec<f64>) -> String {
        CouplerError::NotConverged {
            window: 34,
            time: 0.34,
            iterations: history.len() as u32,
            residual: *history.last().unwrap_or(&f64::NAN),
            field: "fluid.force".into(),
            history,
        }
        .to_string()
    }

    /// A residual that keeps falling, only too slowly, asks for more iterations; one that
    /// cycles (IQN-ILS on the light box's window 28, period 13: docs/notes/implicit-coupling-light-bodies.md) says why more
    /// iterations will not help.
    #[test]
    fn a_stalled_window_is_told_apart_from_a_slow_one() {
        let slow: Vec<f64> = (0..10).map(|k| 0.5f64.powi(k)).collect();
        assert!(not_converged(slow).contains("raise coupling.max_iterations"));
        let cycling: Vec<f64> = (0..10).map(|k| [3e-2, 1e-2, 4e-3, 2e-2][k % 4]).collect();
        let message = not_converged(cycling);
        assert!(message.contains("no fixed point"), "{message}");
        assert!(!message.contains("raise coupling.max_iterations"), "{message}");
        assert!(not_converged(vec![1.0, 0.9]).contains("raise coupling.max_iterations"));
    }

    /// An error while finishing the run is placed after the last window (it read "before the
    /// first window" for a participant that exited with an error after Finish); one with a
    /// window keeps it.
    #[test]
    fn an_error_while_finishing_says_after_the_last_window() {
        let failed = |window| CouplerError::Participant {
            name: "fluid".into(),
            window,
            message: "exited with exit code 1 after the run".into(),
        };
        let message = failed(None).after_last_window().to_string();
        assert_eq!(
            message,
            "participant `fluid` after the last window: exited with exit code 1 after the run"
        );
        assert_eq!(failed(None).after_last_window().exit_code(), 1);
        assert!(failed(Some(7))
            .after_last_window()
            .to_string()
            .contains("in window 7"));
    }
}
