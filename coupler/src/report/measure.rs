//! Measuring a run from outside, as a user's `coupler run` is: wall time, CPU time of the coupler
//! and every solver it started, and peak resident memory of all of them.
//!
//! CPU time comes from `wait4`'s resource usage of the coupler process, which includes the
//! children it waited for (the solvers). Memory: every 20 ms the process tree under the coupler
//! is read from `/proc` and each process's peak resident set (`VmHWM`) kept; the run's peak is
//! the sum of these per-process peaks (the processes of a coupled run live side by side).
//! `wait4`'s `ru_maxrss` is not used: Linux carries a process's high-water mark across `exec`,
//! so a child started from the report reports the report's own size.

use schemas::signals;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How one run ended and what it cost.
#[derive(Debug, Clone)]
pub struct Measured {
    /// Exit code (None: killed by a signal).
    pub code: Option<i32>,
    pub wall: f64,
    /// User + system CPU seconds of the coupler and its solvers.
    pub cpu: f64,
    /// Peak resident memory of all processes of the run [bytes].
    pub peak_rss: u64,
    /// The run's stderr (the coupler's messages).
    pub stderr: String,
    /// Ctrl-C arrived during the run (the run was stopped).
    pub interrupted: bool,
}

impl Measured {
    pub fn success(&self) -> bool {
        self.code == Some(0) && !self.interrupted
    }
}

/// Runs `coupler run CASE --out OUT` (this executable) and measures it.
pub fn run_case(case: &Path, out: &Path) -> Result<Measured, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate the coupler's executable: {e}"))?;
    let _ = std::fs::remove_dir_all(out);
    if let Some(parent) = out.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    }
    // beside the run's folder: `coupler run` refuses an output folder that already holds files
    let log = std::path::PathBuf::from(format!("{}.log", out.display()));
    let file = std::fs::File::create(&log).map_err(|e| format!("cannot create {}: {e}", log.display()))?;
    let err = file
        .try_clone()
        .map_err(|e| format!("cannot write {}: {e}", log.display()))?;
    let started = Instant::now();
    let child = Command::new(exe)
        .arg("run")
        .arg(case)
        .arg("--out")
        .arg(out)
        .stdin(Stdio::null())
        .stdout(file)
        .stderr(err)
        .spawn()
        .map_err(|e| format!("cannot start `coupler run`: {e}"))?;
    let pid = child.id() as libc::pid_t;
    let mut peaks: BTreeMap<i32, u64> = BTreeMap::new();
    let mut interrupted = false;
    let (status, usage) = loop {
        sample_tree(pid, &mut peaks);
        if let Some(done) = try_wait4(pid)? {
            break done;
        }
        if signals::interrupted() && !interrupted {
            interrupted = true;
            // SAFETY: plain kill(2) of our own child; the coupler stops its solvers on SIGINT.
            unsafe { libc::kill(pid, libc::SIGINT) };
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let wall = started.elapsed().as_secs_f64();
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    let cpu = seconds(usage.ru_utime) + seconds(usage.ru_stime);
    let sum: u64 = peaks.values().sum();
    let code = if libc::WIFEXITED(status) {
        Some(libc::WEXITSTATUS(status))
    } else {
        None
    };
    Ok(Measured {
        code,
        wall,
        cpu,
        peak_rss: sum,
        stderr: std::fs::read_to_string(&log).unwrap_or_default(),
        interrupted: interrupted || signals::interrupted(),
    })
}

/// `wait4(pid, WNOHANG)`: the status and resource usage once the child has ended.
fn try_wait4(pid: libc::pid_t) -> Result<Option<(i32, libc::rusage)>, String> {
    let mut status = 0;
    // SAFETY: rusage is plain old data, filled in by the kernel.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: wait4 on our own child with valid pointers.
    let r = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
    match r {
        0 => Ok(None),
        r if r == pid => Ok(Some((status, usage))),
        _ => Err(format!(
            "waiting for `coupler run`: {}",
            std::io::Error::last_os_error()
        )),
    }
}

/// Reads the process tree under `root` and raises each process's recorded peak to its `VmHWM`.
fn sample_tree(root: libc::pid_t, peaks: &mut BTreeMap<i32, u64>) {
    let mut stack = vec![root];
    while let Some(pid) = stack.pop() {
        if let Some(hwm) = vm_hwm(pid) {
            let p = peaks.entry(pid).or_default();
            *p = (*p).max(hwm);
        }
        stack.extend(children(pid));
    }
}

/// Peak resident set of a process [bytes], from `/proc/PID/status`.
fn vm_hwm(pid: i32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Child process ids of every thread of `pid`.
fn children(pid: i32) -> Vec<i32> {
    let Ok(tasks) = std::fs::read_dir(format!("/proc/{pid}/task")) else {
        return Vec::new();
    };
    tasks
        .flatten()
        .filter_map(|t| std::fs::read_to_string(t.path().join("children")).ok())
        .flat_map(|s| {
            s.split_whitespace()
                .filter_map(|p| p.parse().ok())
                .collect::<Vec<i32>>()
        })
        .collect()
}

/// Timing of one setting: a warm-up run, then the minimum of `repeats` runs when the warm-up
/// took under [`LONG_RUN`] seconds; a longer warm-up is itself the one measured run.
#[derive(Debug, Clone)]
pub struct Timing {
    /// The run whose outputs are read (the last one).
    pub last: Measured,
    /// Fastest wall time [s].
    pub wall: f64,
    /// CPU time of the fastest run [s].
    pub cpu: f64,
    /// Largest peak memory over the runs [bytes].
    pub peak_rss: u64,
    /// Timed runs (1 when the warm-up was long).
    pub runs: u32,
    /// (slowest − fastest) / fastest over the timed runs.
    pub spread: f64,
}

/// A run longer than this many seconds is measured once (its warm-up is the measurement).
pub const LONG_RUN: f64 = 3.0;

/// Warm-up, then timed runs; stops at the first run that fails or is interrupted.
pub fn timed(case: &Path, out: &Path, repeats: u32) -> Result<Timing, String> {
    let warm = run_case(case, out)?;
    if !warm.success() || warm.wall > LONG_RUN {
        return Ok(Timing {
            wall: warm.wall,
            cpu: warm.cpu,
            peak_rss: warm.peak_rss,
            runs: 1,
            spread: 0.0,
            last: warm,
        });
    }
    let mut runs: Vec<Measured> = Vec::new();
    for _ in 0..repeats.max(1) {
        let m = run_case(case, out)?;
        let stop = !m.success();
        runs.push(m);
        if stop {
            break;
        }
    }
    let last = runs.last().cloned().unwrap_or(warm);
    if !last.success() {
        return Ok(Timing {
            wall: last.wall,
            cpu: last.cpu,
            peak_rss: last.peak_rss,
            runs: 1,
            spread: 0.0,
            last,
        });
    }
    let fastest = runs
        .iter()
        .min_by(|a, b| a.wall.total_cmp(&b.wall))
        .cloned()
        .unwrap_or_else(|| last.clone());
    let slowest = runs.iter().map(|m| m.wall).fold(0.0, f64::max);
    Ok(Timing {
        wall: fastest.wall,
        cpu: fastest.cpu,
        peak_rss: runs.iter().map(|m| m.peak_rss).max().unwrap_or(0),
        runs: runs.len() as u32,
        spread: (slowest - fastest.wall) / fastest.wall.max(1e-12),
        last,
    })
}
