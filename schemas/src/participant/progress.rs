//! Progress reports of a participant while it works on a window, so that the coupler tells a
//! long window from a hung participant.
//!
//! A solver tells its [`ProgressSink`] of every step it finishes, and of the bytes it writes to its
//! outputs and checkpoints ([`ReportingWriter`]); [`LinkProgress`] passes that on to the coupler as
//! [`FromParticipant::Progress`], at most once per interval of wall time and only after a step or a
//! write. A participant that stops stepping and writing (a stuck solver, SIGSTOP) therefore stops
//! reporting, and the coupler stops the run after `coupling.timeout` without a report or an answer.

use crate::link::Link;
use crate::message::{FromParticipant, Header};
use std::io::{self, Write};
use std::time::{Duration, Instant};

/// Where a solver reports its progress inside a window.
pub trait ProgressSink {
    /// One solver step is done; the solver is now at simulated time `time` [s].
    fn step_done(&mut self, time: f64);
    /// `bytes` more of an output file or a checkpoint are written: work without a solver step
    /// (a frame of many particles, a checkpoint at the end of a window, the last outputs).
    fn bytes_written(&mut self, bytes: u64);
}

/// A sink that drops every report: for advancing outside a coupled run (tests, tools).
pub struct DiscardProgress;

impl ProgressSink for DiscardProgress {
    fn step_done(&mut self, _time: f64) {}
    fn bytes_written(&mut self, _bytes: u64) {}
}

/// A writer that tells a [`ProgressSink`] of every byte it passes on.
pub struct ReportingWriter<'a, W> {
    inner: W,
    sink: &'a mut dyn ProgressSink,
}

impl<'a, W: Write> ReportingWriter<'a, W> {
    /// Writes to `inner`, reporting to `sink`.
    pub fn new(inner: W, sink: &'a mut dyn ProgressSink) -> ReportingWriter<'a, W> {
        ReportingWriter { inner, sink }
    }
}

impl<W: Write> Write for ReportingWriter<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.sink.bytes_written(n as u64);
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// Reports the progress of one `Advance` to the coupler through the link.
pub struct LinkProgress<'a> {
    link: &'a Link,
    /// The request being answered (its window and iteration).
    request: Header,
    interval: Duration,
    last_sent: Instant,
    steps: u64,
    /// Simulated time of the last step reported (the request's own until one is).
    time: f64,
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
            time: request.time,
        }
    }
}

impl LinkProgress<'_> {
    /// Sends a report when `interval` has passed since the last one.
    fn report_when_due(&mut self) {
        if self.last_sent.elapsed() < self.interval {
            return;
        }
        self.last_sent = Instant::now();
        let report = FromParticipant::Progress {
            header: Header {
                time: self.time,
                ..self.request
            },
            steps: self.steps,
        };
        // A report that cannot be sent is dropped: the coupler is gone or stopped the run, which
        // the send of the answer and the next wait for a request report.
        let _ = self.link.send(&report);
    }
}

impl ProgressSink for LinkProgress<'_> {
    fn step_done(&mut self, time: f64) {
        self.steps += 1;
        self.time = time;
        self.report_when_due();
    }

    fn bytes_written(&mut self, _bytes: u64) {
        self.report_when_due();
    }
}
