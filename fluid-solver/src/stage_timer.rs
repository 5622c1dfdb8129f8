//! Wall time per named stage of the step, summed over the run: the step reads as a list of
//! stages and the benchmark prints where the time goes.

use std::time::Instant;

/// Seconds spent in each stage, in the order the stages first ran.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StageTimes {
    stages: Vec<(&'static str, f64)>,
}

impl StageTimes {
    /// Starts timing the next stage.
    pub fn start(&self) -> Instant {
        Instant::now()
    }

    /// Adds the time since `since` to stage `name`; returns the start of the next stage.
    pub fn lap(&mut self, since: Instant, name: &'static str) -> Instant {
        let now = Instant::now();
        let dt = now.duration_since(since).as_secs_f64();
        match self.stages.iter_mut().find(|(n, _)| *n == name) {
            Some((_, s)) => *s += dt,
            None => self.stages.push((name, dt)),
        }
        now
    }

    /// (stage, seconds) in the order the stages first ran.
    pub fn stages(&self) -> &[(&'static str, f64)] {
        &self.stages
    }

    /// Seconds of stage `name` (0 if it never ran).
    pub fn seconds(&self, name: &str) -> f64 {
        self.stages.iter().find(|(n, _)| *n == name).map_or(0.0, |s| s.1)
    }

    /// Seconds of every stage together.
    pub fn total(&self) -> f64 {
        self.stages.iter().map(|s| s.1).sum()
    }
}
