//! The progress bar over a report's runs (runs done, ETA); on a terminal only. Without one,
//! each finished run is one line on stderr.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

pub struct Bar {
    bar: ProgressBar,
    terminal: bool,
}

impl Bar {
    /// A bar over `total` runs.
    pub fn new(total: u64) -> Bar {
        let terminal = std::io::stderr().is_terminal();
        let bar = ProgressBar::with_draw_target(
            Some(total),
            if terminal {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            },
        );
        if let Ok(style) =
            ProgressStyle::with_template("{bar:30} {pos}/{len} runs, {elapsed} elapsed, ETA {eta}  {msg}")
        {
            bar.set_style(style);
        }
        Bar { bar, terminal }
    }

    /// A run starts.
    pub fn start(&self, what: &str) {
        self.bar.set_message(what.to_string());
    }

    /// The run ended.
    pub fn done(&self) {
        self.bar.inc(1);
    }

    /// A line above the bar (or on stderr without a terminal).
    pub fn note(&self, line: &str) {
        if self.terminal {
            self.bar.println(line);
        } else {
            crate::say!("{line}");
        }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
