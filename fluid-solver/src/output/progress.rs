//! Progress of a run for its user: a line at a steady wall-clock interval in the log (simulated
//! time, steps, particle-steps/s, ETA), redrawn as a bar when stderr is a terminal, and the
//! summary every run ends with ([`RunSummary`]).

use schemas::case::fluid::MAX_ADVECTIVE_COURANT;
use std::fmt;
use std::io::Write;
use std::time::{Duration, Instant};

/// Shortest time between redraws of the bar on a terminal.
const BAR_REDRAW: Duration = Duration::from_millis(200);
/// Characters of the bar.
const BAR_WIDTH: usize = 24;

/// Progress reports of one run to stderr.
#[derive(Debug, Clone)]
pub struct Progress {
    name: String,
    end: f64,
    interval: Duration,
    terminal: bool,
    started: Instant,
    last: Instant,
    drawn: bool,
    /// Fluid particles removed over an open top, as last logged.
    escaped: u64,
}

impl Progress {
    /// Reports of run `name` to `end` [s]: a line every `interval_s` wall seconds, or a bar on a
    /// `terminal`.
    pub fn new(name: &str, end: f64, interval_s: f64, terminal: bool) -> Progress {
        let now = Instant::now();
        Progress {
            name: name.to_string(),
            end,
            interval: Duration::from_secs_f64(interval_s),
            terminal,
            started: now,
            last: now,
            drawn: false,
            escaped: 0,
        }
    }

    /// Wall seconds since the run started.
    pub fn elapsed(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Reports the state at simulated time `t` after `steps` steps and `particle_steps`
    /// particle-steps, when a report is due.
    pub fn update(&mut self, t: f64, steps: u64, particle_steps: u64, particles: usize) {
        let due = if self.terminal { BAR_REDRAW } else { self.interval };
        if self.last.elapsed() < due {
            return;
        }
        self.last = Instant::now();
        let elapsed = self.elapsed();
        let rate = particle_steps as f64 / elapsed.max(1e-9);
        let fraction = (t / self.end).clamp(0.0, 1.0);
        let eta = if t > 0.0 {
            elapsed * (self.end - t).max(0.0) / t
        } else {
            f64::NAN
        };
        let mut err = std::io::stderr();
        if self.terminal {
            let filled = (fraction * BAR_WIDTH as f64).round() as usize;
            let _ = write!(
                err,
                "\r{} [{}{}] {:5.1} %  t = {t:.4} / {} s  step {steps}  {rate:.3e} particle-steps/s  ETA {}   ",
                self.name,
                "#".repeat(filled),
                "-".repeat(BAR_WIDTH - filled),
                100.0 * fraction,
                self.end,
                duration(eta)
            );
            self.drawn = true;
        } else {
            let _ = writeln!(
                err,
                "{}: t = {t:.4} / {} s ({:.1} %), step {steps}, {particles} particles, {rate:.3e} particle-steps/s, {} elapsed, ETA {}",
                self.name,
                self.end,
                100.0 * fraction,
                duration(elapsed),
                duration(eta)
            );
        }
        let _ = err.flush();
    }

    /// Logs fluid particles newly removed over an open top (`escaped`: the count so far).
    pub fn note_escapes(&mut self, t: f64, escaped: u64) {
        if escaped > self.escaped {
            self.finish();
            eprintln!(
                "{}: t = {t:.4} s: {} fluid particle(s) left over the walls and were removed ({escaped} in all)",
                self.name,
                escaped - self.escaped
            );
            self.escaped = escaped;
        }
    }

    /// Ends the bar's line (nothing to do for log lines).
    pub fn finish(&mut self) {
        if self.drawn {
            eprintln!();
            self.drawn = false;
        }
    }
}

/// What a finished run did: the summary line every run ends with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSummary {
    pub time: f64,
    pub steps: u64,
    pub particles: usize,
    pub fluid_particles: usize,
    pub frames: usize,
    pub wall_seconds: f64,
    pub particle_steps: u64,
    /// Peak resident memory of the process [bytes], where the system tells it.
    pub peak_memory: Option<u64>,
    /// Fluid particles removed after leaving through the open top.
    pub escaped: u64,
    /// Fluid particles removed behind an outflow plane.
    pub outflow_removed: u64,
    /// On the GPU path: whole copies of the particles to the host, and their wall seconds.
    pub host_copies: (u64, f64),
    /// On the GPU path: where the steps' wall time went.
    pub device_seconds: crate::gpu::DeviceSeconds,
    /// ISPH's steps cut short because the fluid outran the case's Δt, and the fastest fluid
    /// speed that cut one [m/s] (`isph::step_length`).
    pub advective_cuts: (u64, f64),
}

impl fmt::Display for RunSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "t = {} s in {} steps, {} wall, {:.3e} particle-steps/s, {} particles ({} fluid), {} frames, peak memory {}, fluid particles removed: {} (open top {}, outflow {})",
            self.time,
            self.steps,
            duration(self.wall_seconds),
            self.particle_steps as f64 / self.wall_seconds.max(1e-9),
            self.particles,
            self.fluid_particles,
            self.frames,
            self.peak_memory
                .map_or("unknown".to_string(), |b| format!("{:.1} MiB", b as f64 / 1048576.0)),
            self.escaped + self.outflow_removed,
            self.escaped,
            self.outflow_removed
        )?;
        let (copies, seconds) = self.host_copies;
        if copies > 0 {
            write!(f, "; {copies} whole copies from the GPU in {}", duration(seconds))?;
        }
        let d = self.device_seconds;
        if d.steps > 0.0 {
            write!(f, "; GPU steps {}", duration(d.steps))?;
        }
        if d.open_boundaries > 0.0 {
            write!(
                f,
                ", open boundaries {} (the host's strip rule {})",
                duration(d.open_boundaries),
                duration(d.strip_rule)
            )?;
        }
        match self.advective_cuts {
            (0, _) => Ok(()),
            (k, u) => write!(
                f,
                "; {k} steps cut short where the fluid outran time_step (u·Δt/Δs ≤ {MAX_ADVECTIVE_COURANT}; fastest {u:.3} m/s)"
            ),
        }
    }
}

/// Peak resident memory of this process (`VmHWM` of /proc/self/status), where available.
pub fn peak_memory_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// `s` as "1 h 02 min", "3 min 20 s" or "12.3 s" ("?" when not finite).
pub fn duration(s: f64) -> String {
    if !s.is_finite() {
        return "?".into();
    }
    if s >= 3600.0 {
        format!(
            "{} h {:02} min",
            (s / 3600.0) as u64,
            ((s % 3600.0) / 60.0) as u64
        )
    } else if s >= 60.0 {
        format!("{} min {:02} s", (s / 60.0) as u64, (s % 60.0) as u64)
    } else {
        format!("{s:.1} s")
    }
}
