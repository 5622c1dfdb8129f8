//! Time to solution of seed 000's scene through the whole stack (`coupler run`: the fluid with
//! its inflow, outflow, levees, piers and the deck, the structure holding the deck on its
//! bearings), with the fluid on the GPU and on the CPU threads, in a table: particles, fluid
//! steps, the fluid's own wall time and particle-steps per second (from its log), and the whole
//! run's wall time. Frames are written every 1 s of flow (not every 0.24 s), without free-surface
//! meshes, so the table measures the solvers rather than the disk.
//!
//! Build the solvers first (`cargo build --release`), then:
//! - `cargo bench -p coupler --bench gpu_scenes` on a machine with a GPU: `cases/bridge-washout`
//!   at the seed's Δs = 2 m on the GPU and on the CPU, and at Δs = 1 m and 0.5 m on the GPU
//!   (Δt scaled with Δs, keeping Table II's c Δt/Δs = 0.67);
//! - `… -- SPACING…` chooses the spacings (both backends at each; `gpu` or `cpu` among them: that
//!   backend only).
//!
//! It first runs `cases/bridge-washout-small` for 1.2 s on both, which checks the bench and
//! names the GPU; with only a software Vulkan device (lavapipe) it stops there (those numbers are
//! not GPU speed).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The workspace's root.
fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// `key = value` lines of `text` replaced (the first of each key).
fn with_keys(mut text: String, keys: &[(&str, String)]) -> Result<String, String> {
    for (key, value) in keys {
        let start = text
            .find(&format!("\n{key} ="))
            .ok_or_else(|| format!("the case has no `{key} =` line"))?;
        let end = text[start + 1..].find('\n').map_or(text.len(), |i| start + 1 + i);
        text.replace_range(start + 1..end, &format!("{key} = {value}"));
    }
    Ok(text)
}

/// What one run measured.
struct Measured {
    /// The GPU as the fluid's log names it (empty on the CPU).
    device: String,
    particles: String,
    steps: String,
    fluid_wall: String,
    rate: String,
    /// Whole copies of the particles from the GPU and their time (frames; empty on the CPU).
    copies: String,
    /// The device steps' time and the open boundaries' (with the host's strip rule) (empty on
    /// the CPU).
    device_time: String,
    wall: f64,
}

/// The text of `line` between `start` and the next `end` after it (empty when either is missing).
fn between<'a>(line: &'a str, start: &str, end: &str) -> &'a str {
    line.split_once(start)
        .and_then(|(_, rest)| rest.split_once(end))
        .map_or("", |(text, _)| text)
}

/// The word before `unit` in `line` (e.g. the number before " steps").
fn before<'a>(line: &'a str, unit: &str) -> &'a str {
    line.split(unit)
        .next()
        .and_then(|s| s.split_whitespace().last())
        .unwrap_or("?")
        .trim_end_matches(',')
}

/// Runs `case` (a case folder under `cases/`) at `spacing` (None: the case's) to `end` on
/// `backend` in `scratch`.
fn run(
    case: &str,
    spacing: Option<f64>,
    end: Option<f64>,
    backend: &str,
    scratch: &Path,
) -> Result<Measured, String> {
    let source = workspace().join("cases").join(case).join("case.toml");
    let text = std::fs::read_to_string(&source).map_err(|e| format!("{}: {e}", source.display()))?;
    let mut keys = vec![
        ("output_interval", "1.0".to_string()),
        ("surface_mesh", "false".to_string()),
    ];
    if let Some(ds) = spacing {
        let (s0, dt0) = (value_of(&text, "spacing")?, value_of(&text, "time_step")?);
        keys.push(("spacing", format!("{ds}\nbackend = \"{backend}\"")));
        keys.push(("time_step", format!("{:e}", dt0 * ds / s0)));
    } else {
        let s0 = value_of(&text, "spacing")?;
        keys.push(("spacing", format!("{s0}\nbackend = \"{backend}\"")));
    }
    if let Some(t) = end {
        keys.push(("end_time", format!("{t}")));
    }
    let text = with_keys(text, &keys)?;
    let dir = scratch.join(format!(
        "{case}-{}-{backend}",
        spacing.map_or("case".into(), |s| s.to_string())
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let file = dir.join("case.toml");
    std::fs::write(&file, text).map_err(|e| format!("{}: {e}", file.display()))?;
    let out = dir.join("out");
    let _ = std::fs::remove_dir_all(&out);
    let started = Instant::now();
    let status = Command::new(env!("CARGO_BIN_EXE_coupler"))
        .arg("run")
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .output()
        .map_err(|e| format!("cannot start the coupler: {e}"))?
        .status;
    let wall = started.elapsed().as_secs_f64();
    let log = std::fs::read_to_string(out.join("river.log")).unwrap_or_default();
    if !status.success() {
        let tail: Vec<&str> = log.lines().rev().take(3).collect();
        return Err(format!(
            "the run failed ({status}); the fluid's log ends: {tail:?}"
        ));
    }
    let done = log
        .lines()
        .find(|l| l.contains(": done: t ="))
        .ok_or("the fluid's log has no `done:` line")?;
    let device = log
        .lines()
        .find_map(|l| l.split("on the GPU: ").nth(1))
        .unwrap_or("")
        .to_string();
    Ok(Measured {
        device,
        particles: before(done, " particles").to_string(),
        steps: before(done, " steps").to_string(),
        fluid_wall: between(done, " steps, ", " wall").to_string(),
        rate: before(done, " particle-steps/s").to_string(),
        copies: segment(done, " whole copies from the GPU").replace(" whole copies from the GPU", ""),
        device_time: segment(done, "GPU steps ").replace("GPU steps ", ""),
        wall,
    })
}

/// The `; `-separated part of `line` that holds `label` (empty when none does).
fn segment(line: &str, label: &str) -> String {
    line.split("; ")
        .find(|s| s.contains(label))
        .unwrap_or("")
        .to_string()
}

/// The number on the first `key = …` line of `text`.
fn value_of(text: &str, key: &str) -> Result<f64, String> {
    text.lines()
        .find_map(|l| l.trim().strip_prefix(&format!("{key} =")))
        .and_then(|v| v.split('#').next())
        .and_then(|v| v.trim().parse().ok())
        .ok_or_else(|| format!("the case has no number for `{key}`"))
}

/// Prints one row of the table for `case` at `spacing` (None: the case's) to `end` on `backend`;
/// returns the GPU's name in the fluid's log (empty on the CPU or after an error).
fn row(case: &str, spacing: Option<f64>, end: Option<f64>, backend: &str, scratch: &Path) -> String {
    let ds = spacing.map_or("case's".to_string(), |s| s.to_string());
    match run(case, spacing, end, backend, scratch) {
        Ok(m) => {
            println!(
                "| {case} | {ds} | {backend} | {} | {} | {} | {} | {} | {} | {:.1} |",
                m.particles, m.steps, m.fluid_wall, m.rate, m.copies, m.device_time, m.wall
            );
            m.device
        }
        Err(e) => {
            println!("| {case} | {ds} | {backend} | error: {e} |");
            String::new()
        }
    }
}

fn main() {
    let scratch = std::env::temp_dir().join(format!("gpu-scenes-{}", std::process::id()));
    let args: Vec<String> = std::env::args().skip(1).collect();
    let spacings: Vec<f64> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let only: Vec<&str> = ["gpu", "cpu"]
        .into_iter()
        .filter(|b| args.iter().any(|a| a == b))
        .collect();
    let both = ["gpu", "cpu"];
    let backends: &[&str] = if only.is_empty() { &both } else { &only };
    println!("| case | Δs [m] | fluid on | particles | fluid steps | fluid wall | particle-steps/s | whole copies from the GPU | GPU steps, open boundaries (host's strip rule) | whole run [s] |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    // the small scene first: it checks the bench, and its log names the GPU
    let device = row("bridge-washout-small", None, Some(1.2), "gpu", &scratch);
    row("bridge-washout-small", None, Some(1.2), "cpu", &scratch);
    println!("GPU: {}", if device.is_empty() { "none found" } else { &device });
    if device.is_empty() || device.contains("Cpu)") {
        println!("no hardware GPU: the seed's scene is not run (the rows above are not GPU speed)");
        let _ = std::fs::remove_dir_all(&scratch);
        return;
    }
    let plan: Vec<(f64, &[&str])> = match spacings.is_empty() {
        true => vec![
            (2.0, &["gpu", "cpu"][..]),
            (1.0, &["gpu"][..]),
            (0.5, &["gpu"][..]),
        ],
        false => spacings.iter().map(|&s| (s, backends)).collect(),
    };
    for (ds, backends) in plan {
        for backend in backends {
            row("bridge-washout", Some(ds), None, backend, &scratch);
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
}
