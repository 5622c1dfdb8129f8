//! Speed of the seed scenes through the three-process stack: wall time, particle-steps per
//! second and peak memory (sum over the processes of each one's peak RSS), and the coupling
//! overhead estimated against the same fluid scene run alone with its bodies held still (same
//! particles, same steps, no structure process, no coupling traffic).
//!
//! `cargo bench -p stack-tests --bench seed_scenes [-- NAME…]` (NAME: dam-break-floating-box,
//! bridge-washout, bridge-washout-small; default: all). `SEED_BENCH_END_TIME=0.5` shortens the runs.

use stack_tests::{binary, out_dir, workspace};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What one run cost.
struct Cost {
    wall: f64,
    /// Peak RSS [bytes] of each process.
    peaks: BTreeMap<String, u64>,
    /// What it printed on stderr.
    log: Vec<String>,
}

/// Peak resident set size of a process so far (VmHWM), if it is still there.
fn peak_rss(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace()
        .nth(1)?
        .parse::<u64>()
        .ok()
        .map(|kb| kb * 1024)
}

/// Runs `exe args…`, sampling the peak RSS of it and of every participant it reports starting.
fn measure(exe: &Path, args: &[&str]) -> Cost {
    let t0 = Instant::now();
    let mut child = Command::new(exe)
        .args(args)
        .stderr(Stdio::piped())
        .stdout(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {}: {e}", exe.display()));
    let own = child.id();
    let err = child.stderr.take().unwrap_or_else(|| panic!("no stderr"));
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let mut pids: BTreeMap<String, u32> = BTreeMap::from([("main".to_string(), own)]);
    let mut peaks: BTreeMap<String, u64> = BTreeMap::new();
    let mut log = Vec::new();
    loop {
        for line in rx.try_iter() {
            if let (Some(name), Some(pid)) = (
                line.strip_prefix("started ")
                    .and_then(|r| r.split_whitespace().next()),
                line.rsplit("pid ")
                    .next()
                    .and_then(|p| p.trim_end_matches(')').parse().ok()),
            ) {
                pids.insert(name.to_string(), pid);
            }
            log.push(line);
        }
        for (name, pid) in &pids {
            if let Some(rss) = peak_rss(*pid) {
                let peak = peaks.entry(name.clone()).or_insert(0);
                *peak = (*peak).max(rss);
            }
        }
        if let Ok(Some(status)) = child.try_wait() {
            assert!(status.success(), "{} failed:\n{}", exe.display(), log.join("\n"));
            break;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    log.extend(rx.try_iter());
    Cost {
        wall: t0.elapsed().as_secs_f64(),
        peaks,
        log,
    }
}

/// The case text without its structure and coupling sections (a fluid-only case: bodies held still).
fn fluid_only(text: &str) -> String {
    let mut keep = true;
    let mut out = String::new();
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with('[') {
            let name = t.trim_start_matches('[');
            keep = !(name.starts_with("structure") || name.starts_with("coupling"));
        }
        if keep {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// Replaces the `end_time = …` line.
fn with_end_time(text: &str, end_time: Option<&str>) -> String {
    match end_time {
        None => text.to_string(),
        Some(t) => text
            .lines()
            .map(|l| {
                if l.starts_with("end_time =") {
                    format!("end_time = {t}")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n"),
    }
}

/// The particle count in the fluid solver's closing line "done: N steps, P particles …".
fn particles_in(log: &[String]) -> Option<f64> {
    let line = log.iter().find(|l| l.starts_with("done:"))?;
    let before = line.split(" particles").next()?;
    before.rsplit(' ').next()?.parse().ok()
}

fn bench(name: &str, end_time: Option<&str>) {
    let dir = out_dir(&format!("bench-{name}"));
    let source = workspace().join("cases").join(name);
    for entry in std::fs::read_dir(&source).into_iter().flatten().flatten() {
        let _ = std::fs::copy(entry.path(), dir.join(entry.file_name()));
    }
    let text = with_end_time(
        &std::fs::read_to_string(source.join("case.toml")).unwrap_or_default(),
        end_time,
    );
    let coupled = dir.join("case.toml");
    std::fs::write(&coupled, &text).unwrap_or_default();
    let alone = dir.join("fluid-only.toml");
    std::fs::write(&alone, fluid_only(&text)).unwrap_or_default();

    let out = dir.join("coupled");
    let stack = measure(
        &binary("coupler"),
        &[
            "run",
            coupled.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ],
    );
    let ledger = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    let windows = ledger.lines().count().saturating_sub(1) as f64;
    let total_peak: u64 = stack.peaks.values().sum();
    let solo_out = dir.join("alone");
    let solo = measure(
        &binary("fluid-solver"),
        &[
            "run",
            alone.to_str().unwrap_or_default(),
            "--out",
            solo_out.to_str().unwrap_or_default(),
        ],
    );
    // Particles at the end of the run (inflow changes the count), from the fluid run alone.
    let particles = particles_in(&solo.log).unwrap_or(0.0);
    println!(
        "{name:<24} {particles:>9.0} {windows:>7.0} {:>9.1} {:>12.3e} {:>10.1} {:>9.1} {:>9.1}",
        stack.wall,
        particles * windows / stack.wall,
        total_peak as f64 / 1048576.0,
        solo.wall,
        100.0 * (stack.wall - solo.wall) / solo.wall,
    );
    for (process, peak) in &stack.peaks {
        println!(
            "{:<24}   peak RSS of {process}: {:.1} MB",
            "",
            *peak as f64 / 1048576.0
        );
    }
}

fn main() {
    let end_time = std::env::var("SEED_BENCH_END_TIME").ok();
    let wanted: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let all = ["dam-break-floating-box", "bridge-washout-small", "bridge-washout"];
    println!("seed scenes through the stack (fluid + structure + coupler processes)");
    println!(
        "{:<24} {:>9} {:>7} {:>9} {:>12} {:>10} {:>9} {:>9}",
        "case", "particles", "steps", "wall [s]", "p-steps/s", "peak [MB]", "alone [s]", "overhead%"
    );
    for name in all
        .iter()
        .filter(|n| wanted.is_empty() || wanted.iter().any(|w| w == *n))
    {
        if workspace().join("cases").join(name).join("case.toml").is_file() {
            bench(name, end_time.as_deref());
        }
    }
}
