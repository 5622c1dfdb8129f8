//! Progress reports of a participant while it works on a window, so that the coupler tells a
//! long window from a hung participant.
//!
//! A solver tells its [`ProgressSink`] of every step it finishes; [`LinkProgress`] passes that on
//! to the coupler as [`FromParticipant::Progress`], at most once per interval of wall time and only
//! after a step. A participant that stops stepping (a stuck solver, SIGSTOP) therefore stops
//! reporting, and the coupler stops the run after `coupling.timeout` without a report or an answer.

use crate::link::Link;
use crate::message::{FromParticipant, Header};
use std::time::{Duration, Instant};

/// Where a solver reports its progress inside a window.
pub trait ProgressSink {
    /// One solver step is done; the solver is now at simulated time `time` [s].
    fn step_done(&mut self, time: f64);
}

/// A sink that drops every report: for advancing outside a coupled run (tests, tools).
pub struct DiscardProgress;

impl ProgressSink for DiscardProgress {
    fn step_done(&mut self, _time: f64) {}
}

/// Reports the progress of one `Advance` to the coupler through the link.
pub struct LinkProgress<'a> {
    link: &'a Link,
    /// The request being answered (its window and iteration).
    request: Header,
    interval: Duration,
    last_sent: Instant,
    steps: u64,
}

impl<'a> LinkProgress<'a> {
    /// Reports of the `Advance` with header `request` on `link`, the first one `interval` of wall
    /// time from now.
    pub fn new(link: &'a Link, request: Header, interval: Duration) -> LinkProgress<'a> {
        LinkProgress {
            link,
            request,
            interval,
            last_sent: Instant::now(),
            steps: 0,
        }
    }
}

impl ProgressSink for LinkProgress<'_> {
    fn step_done(&mut self, time: f64) {
        self.steps += 1;
        if self.last_sent.elapsed() < self.interval {
            return;
        }
        self.last_sent = Instant::now();
        let report = FromParticipant::Progress {
            header: Header { time, ..self.request },
            steps: self.steps,
        };
        // A report that cannot be sent is dropped: the coupler is gone or stopped the run, which
        // the send of the answer and the next wait for a request report.
        let _ = self.link.send(&report);
    }
}
