//! Progress of a coupled run: simulated time, windows, windows per second, ETA. On a terminal a
//! bar redrawn at most 5 times a second; otherwise (a log, a pipe) one line every
//! [`LOG_INTERVAL`], so a run that nobody watches still shows its speed. Each participant writes
//! its own progress lines and summary (particle-steps/s, peak memory, particles removed) to its
//! log.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

/// Wall time between progress lines when stderr is not a terminal.
pub const LOG_INTERVAL: Duration = Duration::from_secs(10);
/// Shortest time between redraws of the bar on a terminal.
const BAR_REDRAW: Duration = Duration::from_millis(200);
/// Characters of the bar.
const BAR_WIDTH: usize = 24;

pub struct Progress {
    terminal: bool,
    started: Instant,
    last: Instant,
    drawn: bool,
}

impl Progress {
    /// A bar when stderr is a terminal, log lines otherwise.
    pub fn new() -> Progress {
        let now = Instant::now();
        Progress {
            terminal: std::io::stderr().is_terminal(),
            started: now,
            last: now,
            drawn: false,
        }
    }

    /// After window `done` of `total` ended at simulated time `t` of `end`.
    pub fn update(&mut self, t: f64, end: f64, done: u64, total: u64) {
        let due = if self.terminal { BAR_REDRAW } else { LOG_INTERVAL };
        if self.last.elapsed() < due && done < total {
            return;
        }
        self.last = Instant::now();
        let elapsed = self.started.elapsed().as_secs_f64();
        let rate = done as f64 / elapsed.max(1e-9);
        let eta = total.saturating_sub(done) as f64 / rate.max(1e-9);
        let fraction = done as f64 / total.max(1) as f64;
        let mut err = std::io::stderr();
        if self.terminal {
            let filled = (fraction * BAR_WIDTH as f64).round() as usize;
            let _ = write!(
                err,
                "\r  [{}{}] {:5.1} %  t = {t:.4} / {end} s   window {done}/{total}   {rate:.1} windows/s   ETA {eta:.0} s    ",
                "#".repeat(filled),
                "-".repeat(BAR_WIDTH.saturating_sub(filled)),
                100.0 * fraction
            );
            self.drawn = true;
        } else {
            let _ = writeln!(
                err,
                "progress: t = {t:.4} / {end} s ({:.1} %), window {done}/{total}, {rate:.2} windows/s, {elapsed:.0} s elapsed, ETA {eta:.0} s",
                100.0 * fraction
            );
        }
        let _ = err.flush();
    }

    /// Ends the bar's line.
    pub fn finish(&self) {
        if self.drawn {
            crate::say!();
        }
    }
}

impl Default for Progress {
    fn default() -> Self {
        Progress::new()
    }
}
