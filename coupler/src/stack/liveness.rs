//! How the coupler tells a slow participant from a hung one. While a participant works on a
//! request it reports its solver steps (`FromParticipant::Progress`, not recorded); it is taken as
//! hung when neither a report nor an answer comes for `coupling.timeout`, however long the whole
//! window takes.

use std::time::Duration;

/// Longest wall time between two progress reports asked of a participant.
const MAX_PROGRESS_INTERVAL: Duration = Duration::from_secs(5);

/// Wall time between progress reports asked of the participants (`--progress-interval`): a quarter
/// of the timeout, at most 5 s, so that a participant that keeps stepping reports several times
/// within every timeout.
pub fn progress_interval(timeout: Duration) -> Duration {
    (timeout / 4).min(MAX_PROGRESS_INTERVAL)
}

/// The last progress report of a participant on the request it is answering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LastReport {
    /// Solver steps taken on the request.
    pub steps: u64,
    /// Simulated time reached [s].
    pub time: f64,
}

/// What the user is told when a participant sent neither an answer nor a progress report for
/// `timeout`, after `last` (none: it reported no step of the request).
pub fn no_progress(timeout: Duration, last: Option<&LastReport>) -> String {
    let limit = timeout.as_secs_f64();
    match last {
        Some(r) => format!(
            "no answer and no progress report for {limit:.1} s (hung?); it last reported step {} of this \
             request, at t = {:.6} s. Raise coupling.timeout if one solver step can take that long",
            r.steps, r.time
        ),
        None => format!(
            "no answer and no progress report for {limit:.1} s (hung?); it reported no step of this request. \
             Raise coupling.timeout if one solver step (or, for a solver that does not report its steps, one \
             answer) can take that long"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_interval_is_a_quarter_of_the_timeout_and_at_most_five_seconds() {
        assert_eq!(
            progress_interval(Duration::from_secs(2)),
            Duration::from_millis(500)
        );
        assert_eq!(
            progress_interval(Duration::from_secs(120)),
            Duration::from_secs(5)
        );
    }

    #[test]
    fn the_message_says_what_was_last_heard() {
        let last = LastReport {
            steps: 41,
            time: 0.0123,
        };
        let text = no_progress(Duration::from_secs(1), Some(&last));
        assert!(
            text.contains("for 1.0 s (hung?)") && text.contains("step 41"),
            "{text}"
        );
        let text = no_progress(Duration::from_secs(1), None);
        assert!(text.contains("reported no step"), "{text}");
    }
}
