//! [`StepError`]: why an advance stopped (non-finite state, a rotation step that cannot be
//! solved), with the simulated time it happened at.

use std::fmt;

/// An advance that had to stop; the message names the point mass or body and what to change.
#[derive(Debug, Clone, PartialEq)]
pub struct StepError {
    /// Simulated time [s] at the start of the failing substep.
    pub time: f64,
    pub message: String,
}

impl StepError {
    pub fn new(time: f64, message: impl Into<String>) -> Self {
        Self {
            time,
            message: message.into(),
        }
    }
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "structure solver stopped at t = {} s: {}",
            self.time, self.message
        )
    }
}

impl std::error::Error for StepError {}
