//! A progress line on a terminal: simulated time, windows per second, ETA. Quiet otherwise.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

pub struct Progress {
    enabled: bool,
    started: Instant,
    last: Option<Instant>,
}

impl Progress {
    /// Enabled when stderr is a terminal.
    pub fn new() -> Progress {
        Progress {
            enabled: std::io::stderr().is_terminal(),
            started: Instant::now(),
            last: None,
        }
    }

    /// After window `done` of `total` ended at simulated time `t` of `end`; redrawn at most 10 times a second.
    pub fn update(&mut self, t: f64, end: f64, done: u64, total: u64) {
        if !self.enabled
            || self
                .last
                .is_some_and(|l| l.elapsed() < Duration::from_millis(100))
                && done < total
        {
            return;
        }
        self.last = Some(Instant::now());
        let elapsed = self.started.elapsed().as_secs_f64();
        let rate = done as f64 / elapsed.max(1e-9);
        let eta = (total - done) as f64 / rate.max(1e-9);
        let mut err = std::io::stderr();
        let _ = write!(
            err,
            "\r  t = {t:.4} / {end} s   window {done}/{total}   {rate:.1} windows/s   ETA {eta:.0} s    "
        );
        let _ = err.flush();
    }

    /// Ends the line.
    pub fn finish(&self) {
        if self.enabled {
            eprintln!();
        }
    }
}

impl Default for Progress {
    fn default() -> Self {
        Progress::new()
    }
}
