//! Helpers for the workspace tests that start real processes: where the built binaries are,
//! throw-away output folders, case files written from a template, and reading results back
//! from recordings.

use schemas::message::{FromParticipant, ToParticipant};
use schemas::recording::{Message, Recording};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The workspace root.
pub fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The folder of the built binaries (`target/release` when tests run with `--release`).
pub fn bin_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap_or_default();
    // target/<profile>/deps/<test binary>
    exe.parent()
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// A workspace binary or this crate's test helper (`faulty-participant`, an example), built first (once per test process) so the tests never run a stale one:
/// `cargo test` builds a package's binaries only for that package's own integration tests.
pub fn binary(name: &str) -> PathBuf {
    static BUILT: OnceLock<()> = OnceLock::new();
    BUILT.get_or_init(|| {
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut build = Command::new(cargo);
        build
            .args([
                "build",
                "--bins",
                "--workspace",
                "--example",
                "faulty-participant",
            ])
            .current_dir(workspace());
        if bin_dir().ends_with("release") {
            build.arg("--release");
        }
        if cfg!(feature = "mpi") {
            build.arg("--all-features");
        }
        let status = build
            .status()
            .unwrap_or_else(|e| panic!("cannot run cargo build: {e}"));
        assert!(status.success(), "cargo build --bins --workspace failed");
    });
    // test helpers are examples of this crate (see Cargo.toml)
    let helper = bin_dir().join("examples").join(name);
    let path = if helper.is_file() {
        helper
    } else {
        bin_dir().join(name)
    };
    assert!(
        path.is_file(),
        "{} is missing: run the tests with `cargo test --workspace --release`, which builds every binary",
        path.display()
    );
    path
}

/// A fresh, empty output folder for one test under `target/test-out/`.
pub fn out_dir(test: &str) -> PathBuf {
    let dir = bin_dir()
        .join("..")
        .join("test-out")
        .join(format!("{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
    dir
}

/// Runs `coupler run CASE --out OUT` to completion.
pub fn coupler_run(case: &Path, out: &Path) -> Output {
    coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
    ])
}

/// Runs `coupler run CASE --out OUT` for a case whose fluid may run on the GPU (`backend`, for
/// the messages): `None` when it failed for want of a GPU adapter and `REQUIRE_GPU` is not `1`
/// (the test skips, saying so on stderr); otherwise the run must succeed.
pub fn gpu_coupler_run(case: &Path, out: &Path, backend: &str) -> Option<Output> {
    let run = coupler_run(case, out);
    let err = stderr(&run);
    if !run.status.success()
        && err.contains("no GPU for backend")
        && std::env::var("REQUIRE_GPU").as_deref() != Ok("1")
    {
        eprintln!("skipped (set REQUIRE_GPU=1 to fail instead): no GPU adapter");
        return None;
    }
    assert!(run.status.success(), "{backend}: {err}");
    Some(run)
}

/// Runs `coupler ARGS…` to completion.
pub fn coupler(args: &[&str]) -> Output {
    Command::new(binary("coupler"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"))
}

/// The oscillator case of `cases/oscillator` with `key = value` lines replaced, written to `dir/case.toml`.
pub fn oscillator_case(dir: &Path, replace: &[(&str, &str)]) -> PathBuf {
    case_from("oscillator", dir, replace)
}

/// Coupling settings of an oscillator run.
pub struct OscillatorCoupling<'a> {
    pub window: f64,
    pub scheme: &'a str,
    pub samples: u32,
    pub predictor: &'a str,
    pub acceleration: &'a str,
}

/// Runs the oscillator with these settings in a fresh folder named after `test`; returns the
/// run's output folder and the finished coupler.
pub fn run_oscillator(test: &str, c: &OscillatorCoupling) -> (PathBuf, Output) {
    let dir = out_dir(test);
    let case = oscillator_case(
        &dir,
        &[
            ("window", &c.window.to_string()),
            ("scheme", &format!("\"{}\"", c.scheme)),
            ("samples", &c.samples.to_string()),
            ("predictor", &format!("\"{}\"", c.predictor)),
            ("acceleration", &format!("\"{}\"", c.acceleration)),
        ],
    );
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    (out, run)
}

/// The rows of a CSV file with a header line, as numbers (a field that is not a number, e.g. an
/// empty release time, as NaN); no rows when the file cannot be read.
pub fn csv_rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect())
        .collect()
}

/// The column names of a CSV file's header line (none when the file cannot be read).
pub fn csv_header(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap_or_default()
        .lines()
        .next()
        .unwrap_or_default()
        .split(',')
        .map(str::to_string)
        .collect()
}

/// `cases/NAME/case.toml` with the first `key = …` line of each key replaced, written to `dir/case.toml`.
pub fn case_from(name: &str, dir: &Path, replace: &[(&str, &str)]) -> PathBuf {
    let source = workspace().join("cases").join(name).join("case.toml");
    let template =
        std::fs::read_to_string(&source).unwrap_or_else(|e| panic!("cannot read {}: {e}", source.display()));
    let mut text = template;
    for (key, value) in replace {
        let start = text
            .find(&format!("\n{key} ="))
            .unwrap_or_else(|| panic!("no `{key} =` line in the template"));
        let line_end = text[start + 1..]
            .find('\n')
            .map(|i| start + 1 + i)
            .unwrap_or(text.len());
        text.replace_range(start + 1..line_end, &format!("{key} = {value}"));
    }
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    path
}

/// The last output of `participant`'s array `array` at the end of the run (converged window).
pub fn final_output(recording: &Path, participant: &str, array: &str) -> (f64, Vec<f64>) {
    let rec = Recording::read(recording).unwrap_or_else(|e| panic!("{e}"));
    let last = rec
        .frames
        .iter()
        .rev()
        .filter(|f| f.participant == participant)
        .find_map(|f| match &f.message {
            Message::From(FromParticipant::Advanced { header, outputs, .. }) => {
                Some((header.time, outputs.clone()))
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no answer of `{participant}` in {}", recording.display()));
    let fields = last.1.last().cloned().unwrap_or_default();
    let values = fields
        .arrays()
        .into_iter()
        .find(|(n, _)| *n == array)
        .map(|(_, a)| a.0.clone())
        .unwrap_or_default();
    (last.0, values)
}

/// Number of `Advance` messages sent to `participant` (sweeps) in a recording.
pub fn advances(recording: &Path, participant: &str) -> usize {
    let rec = Recording::read(recording).unwrap_or_else(|e| panic!("{e}"));
    rec.frames
        .iter()
        .filter(|f| {
            f.participant == participant && matches!(f.message, Message::To(ToParticipant::Advance { .. }))
        })
        .count()
}

/// Exact two-mass oscillator: u1 = ½(cos 2πt + cos 6πt), u2 = ½(cos 2πt − cos 6πt).
pub fn oscillator_exact(t: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    let (a, b) = ((2.0 * PI * t).cos(), (6.0 * PI * t).cos());
    (0.5 * (a + b), 0.5 * (a - b))
}

/// The coupled oscillator's error at its end time: max over both masses of |u − u_exact|.
pub fn oscillator_error(recording: &Path) -> f64 {
    let (t1, u1) = final_output(recording, "mass-left", "point_displacement");
    let (t2, u2) = final_output(recording, "mass-right", "point_displacement");
    let (e1, e2) = oscillator_exact(t1);
    assert_eq!(t1, t2, "both masses end at the same time");
    (u1[0] - e1).abs().max((u2[0] - e2).abs())
}

/// The coupled oscillator's largest error over all window ends: for each window, the outputs of
/// its last (converged) sweep against the exact solution, max over both masses.
pub fn oscillator_max_error(recording: &Path) -> f64 {
    let rec = Recording::read(recording).unwrap_or_else(|e| panic!("{e}"));
    let mut ends: std::collections::BTreeMap<(u64, bool), (f64, f64)> = std::collections::BTreeMap::new();
    for f in &rec.frames {
        if let Message::From(FromParticipant::Advanced { header, outputs, .. }) = &f.message {
            let u = outputs
                .last()
                .and_then(|o| o.point_displacement.first().copied())
                .unwrap_or(f64::NAN);
            ends.insert((header.window, f.participant == "mass-left"), (header.time, u));
        }
    }
    ends.iter()
        .map(|(&(_, left), &(t, u))| {
            let (e1, e2) = oscillator_exact(t);
            (u - if left { e1 } else { e2 }).abs()
        })
        .fold(0.0, f64::max)
}

/// stderr of a finished process as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The drag column of `tests/drag_coupling.rs` (issue 13), also resumed by `tests/resume.rs`
/// (`SCHEME` and `TOLERANCE` are placeholders for the coupling scheme and its settings). Tank 0.4 × 0.1 × 0.3 m, Δs = 0.01 m, a water column 0.1 × 0.1 × 0.1 m behind a board at
/// x = 0.1; the column at x = 0.25 from the floor to z = 0.15. Δt = 5e-4 s (c Δt/Δs = 0.6 with
/// c = 12.1 m/s), one fluid step per window, 0.2 s: the surge (≈ 1.5 m/s) passes the column at
/// about 0.1 s.
pub const DRAG_COLUMN_CASE: &str = r#"
[case]
name = "drag-column"
description = "Issue 13: a thin fixed column in a small dam break, unresolved drag coupling."
end_time = 0.2

[fluid.water]
spacing = 0.01
time_step = 5.0e-4
viscosity_term = false
sound_speed = 12.1
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [0.4, 0.1, 0.3], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.1, 0.1, 0.1]

[[fluid.water.gate]]
min = [0.1, 0.0, 0.0]
max = [0.13, 0.1, 0.1]

[structure.column]
max_step = 5.0e-4

[structure.column.frame]
time_step = 5.0e-4
gravity = [0.0, 0.0, -9.8]

[structure.column.frame.material]
young_modulus = 2.0e11
poisson = 0.3
density = 7850.0
yield_stress = 2.35e8

[[structure.column.frame.section]]
name = "bar"
kind = "rectangle"
width = 0.002
depth = 0.002

[[structure.column.frame.node]]
id = 1
position = [0.25, 0.05, 0.0]

[[structure.column.frame.node]]
id = 2
position = [0.25, 0.05, 0.15]

[[structure.column.frame.member]]
nodes = [1, 2]
section = "bar"
orientation = [1.0, 0.0, 0.0]

[[structure.column.frame.support]]
node = 1
fixed = ["x", "y", "z", "rx", "ry", "rz"]

[[structure.column.frame.support]]
node = 2
fixed = ["x", "y", "z", "rx", "ry", "rz"]

[coupling]
window = 5.0e-4
scheme = "SCHEME"
order = ["water", "column"]
predictor = "constant"
TOLERANCE

[[coupling.drag]]
fluid = "water"
structure = "column"
initial_flow = [1.0, 0.0, 0.0]
"#;

/// The drag column of [`DRAG_COLUMN_CASE`] as a breakable cantilever under implicit coupling
/// (issue 13, topology that changes; `tests/drag_coupling.rs`, `tests/resume.rs`): standing at
/// `x` [m] (the board's far side is at 0.13), its top support removed, a node at 5 cm, a yield
/// stress lowered to 1e4 Pa (plastic moment σ_y b h²/4 = 2e-5 N m: a few thousandths of a
/// newton of drag yield its base) and S2-17's critical curvature 0.01 1/m, so the surge breaks
/// it; implicit coupling with constant relaxation ω = 1, tolerance 1e-6, at most 30 sweeps;
/// `coupling` is added to the `[coupling]` section.
pub fn breakable_drag_column_case(x: f64, end_time: f64, coupling: &str) -> String {
    let settings = format!(
        "tolerance = 1e-6\nacceleration = \"constant\"\ninitial_relaxation = 1.0\nmax_iterations = 30{coupling}"
    );
    let weak = "yield_stress = 1.0e4\nfracture_curvature = [0.01, 0.01]";
    let middle = format!(
        "[[structure.column.frame.node]]\nid = 3\nposition = [{x}, 0.05, 0.05]\n\n\
         [[structure.column.frame.member]]\nnodes = [1, 3]"
    );
    let text = DRAG_COLUMN_CASE
        .replace("SCHEME", "implicit")
        .replace("TOLERANCE", &settings)
        .replace("end_time = 0.2", &format!("end_time = {end_time}"))
        .replace("[0.25, 0.05,", &format!("[{x}, 0.05,"))
        .replace("yield_stress = 2.35e8", weak)
        .replace(
            "[[structure.column.frame.support]]\nnode = 2\nfixed = [\"x\", \"y\", \"z\", \"rx\", \"ry\", \"rz\"]\n",
            "",
        )
        .replace(
            "[[structure.column.frame.member]]\nnodes = [1, 2]",
            &format!("{middle}\nsection = \"bar\"\norientation = [1.0, 0.0, 0.0]\n\n[[structure.column.frame.member]]\nnodes = [3, 2]"),
        );
    assert!(
        text.contains("nodes = [3, 2]") && !text.contains("node = 2\n"),
        "{text}"
    );
    text
}

/// The floating box of issue 5 (`tests/floating_at_rest.rs`, and with ISPH
/// `tests/isph_floating.rs`): Δs = 0.02 m, a 0.4 × 0.4 m tank with water 0.2 m deep; a 16 × 16 × 8 cm box (8 × 8 × 4
/// particles) of 400 kg/m³, centred in plan, placed with its bottom 4 cm under the surface (its
/// hydrostatic draft is 0.4 × 8 = 3.2 cm, so it has to rise 8 mm and settle). c = 12.1 m/s,
/// Δt = 8e-4 s (c Δt/Δs = 0.48). 2 s ≈ 5 heave periods.
pub const FLOATING_POOL_CASE: &str = r#"
[case]
name = "floating-at-rest"
description = "Issue 5: a box of 400 kg/m³ floating in still water settles at its hydrostatic draft."
end_time = 2.0

[fluid.pool]
spacing = 0.02
time_step = 8.0e-4
viscosity_term = false
sound_speed = 12.1
output_interval = 0.5
tank = { min = [0.0, 0.0, 0.0], max = [0.4, 0.4, 0.32] }

[[fluid.pool.block]]
min = [0.0, 0.0, 0.0]
max = [0.4, 0.4, 0.16]

[[fluid.pool.block]]
min = [0.0, 0.0, 0.16]
max = [0.12, 0.4, 0.2]

[[fluid.pool.block]]
min = [0.28, 0.0, 0.16]
max = [0.4, 0.4, 0.2]

[[fluid.pool.block]]
min = [0.12, 0.0, 0.16]
max = [0.28, 0.12, 0.2]

[[fluid.pool.block]]
min = [0.12, 0.28, 0.16]
max = [0.28, 0.4, 0.2]

[[fluid.pool.body]]
name = "box"
min = [0.12, 0.12, 0.16]
max = [0.28, 0.28, 0.24]

[structure.float]
max_step = 1.0e-4
gravity = [0.0, 0.0, -9.8]

[[structure.float.body]]
name = "box"
mass = 0.8192
centre = [0.2, 0.2, 0.2]
inertia = { box = [0.16, 0.16, 0.08] }

[structure.float.history]
interval = 0.01
bodies = ["box"]

[coupling]
window = 8.0e-4
scheme = "explicit"
order = ["pool", "float"]
predictor = "linear"

[[coupling.body]]
fluid = "pool/box"
structure = "float/box"
"#;

/// `text` with each `(from, to)` replaced once; panics when `from` is not in it (a case template
/// that changed under its test).
pub fn replaced(text: &str, replace: &[(&str, &str)]) -> String {
    replace.iter().fold(text.to_string(), |t, (from, to)| {
        assert!(t.contains(from), "the case text has no `{from}`");
        t.replacen(from, to, 1)
    })
}

/// Position and pressure of the fluid particles in a VTU frame written by the fluid (raw
/// appended data, UInt64 block headers, Float64 positions and pressures, UInt8 kinds; fluid =
/// kind 0).
pub fn fluid_particles(vtu: &Path) -> Vec<([f64; 3], f64)> {
    let bytes = std::fs::read(vtu).unwrap_or_else(|e| panic!("cannot read {}: {e}", vtu.display()));
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]).into_owned();
    let offset = |name: &str| -> usize {
        let at = text
            .find(&format!("Name=\"{name}\""))
            .unwrap_or_else(|| panic!("no {name} array"));
        let rest = &text[at..];
        let start = rest
            .find("offset=\"")
            .unwrap_or_else(|| panic!("no offset for {name}"))
            + 8;
        let end = rest[start..].find('"').unwrap_or(0) + start;
        rest[start..end]
            .parse()
            .unwrap_or_else(|e| panic!("offset of {name}: {e}"))
    };
    let marker = text
        .find("<AppendedData encoding=\"raw\">")
        .unwrap_or_else(|| panic!("no appended data"));
    let data = marker + text[marker..].find('_').unwrap_or(0) + 1;
    let block = |name: &str| -> &[u8] {
        let at = data + offset(name);
        let len = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap_or_default()) as usize;
        &bytes[at + 8..at + 8 + len]
    };
    let kinds = block("kind");
    let (position, pressure) = (block("position"), block("pressure"));
    let float = |b: &[u8], i: usize| f64::from_le_bytes(b[8 * i..8 * i + 8].try_into().unwrap_or_default());
    (0..kinds.len())
        .filter(|&i| kinds[i] == 0)
        .map(|i| {
            (
                [
                    float(position, 3 * i),
                    float(position, 3 * i + 1),
                    float(position, 3 * i + 2),
                ],
                float(pressure, i),
            )
        })
        .collect()
}

/// The free surface of the floating pool (`FLOATING_POOL_CASE`) in a fluid VTU frame, away from
/// the box (farther than 2 Δs from it in plan): as in the hydrostatic tank test, the height where
/// the pressure field's P = 0, S = mean(z + P/ρg) over the particles deeper than r_e = 3.1 Δs
/// below the highest one. (The top particle layer packs tighter than the lattice and sits lower:
/// its height + Δs/2 was 6 mm below S, which would read as a draft 19 % short.) Returns S, the
/// highest particle's height and how many particles the mean took.
pub fn pool_level(vtu: &Path) -> (f64, f64, usize) {
    const SPACING: f64 = 0.02;
    const RHO_G: f64 = 1000.0 * 9.8;
    let water: Vec<([f64; 3], f64)> = fluid_particles(vtu)
        .into_iter()
        .filter(|(r, _)| (r[0] - 0.2).abs() > 0.12 || (r[1] - 0.2).abs() > 0.12)
        .collect();
    let top = water.iter().map(|(r, _)| r[2]).fold(f64::MIN, f64::max);
    let interior: Vec<f64> = water
        .iter()
        .filter(|(r, _)| r[2] < top - 3.1 * SPACING)
        .map(|(r, p)| r[2] + p / RHO_G)
        .collect();
    let level = interior.iter().sum::<f64>() / interior.len().max(1) as f64;
    (level, top, interior.len())
}

/// A box floating across the cut of two slabs in a tank whose gravity leans 6 m/s² along x, so
/// the water flows under it (Δs = 0.02 m, 7 200 fluid particles, one fluid step per window,
/// 0.05 s): the fluid on `ranks` MPI ranks through OpenMPI's `mpirun` (as root, with more ranks
/// than cores allowed, waiting ranks yielding their core, as CI runs several tests' ranks on 2
/// cores), its probes on both sides of the cut, and the box's history
/// at every window. `coupling` is added to the `[coupling]` section.
pub fn ranked_floating_box(dir: &Path, ranks: usize, coupling: &str) -> PathBuf {
    let text = format!(
        r#"[case]
name = "ranked-floating-box"
end_time = 0.05

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
viscosity_term = false
gravity = [6.0, 0.0, -9.8]
output_interval = 0.025
probe_interval = 0.005
tank = {{ min = [0.0, 0.0, 0.0], max = [1.6, 0.2, 0.4], lid = true }}
ranks = {ranks}
launcher = "mpirun --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 -np {{ranks}}"

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [1.2, 0.2, 0.24]

# 0.2 × 0.12 × 0.06 m of 500 kg/m³ on the water, across the cut at x = 0.6 m
[[fluid.water.body]]
name = "box"
min = [0.5, 0.04, 0.24]
max = [0.7, 0.16, 0.30]

[[fluid.water.probe]]
name = "p-left-of-cut"
kind = "pressure"
position = [0.595, 0.1, 0.05]

[[fluid.water.probe]]
name = "p-right-of-cut"
kind = "pressure"
position = [0.605, 0.1, 0.05]

[[fluid.water.probe]]
name = "front"
kind = "surge-front"
axis = "x"

[structure.floater]
max_step = 1.0e-4
gravity = [6.0, 0.0, -9.8]

[[structure.floater.body]]
name = "box"
mass = 0.72
centre = [0.6, 0.1, 0.27]
inertia = {{ box = [0.2, 0.12, 0.06] }}

[structure.floater.history]
interval = 0.0005
bodies = ["box"]

[coupling]
window = 5.0e-4
order = ["water", "floater"]
predictor = "linear"
{coupling}

[[coupling.body]]
fluid = "water/box"
structure = "floater/box"
"#
    );
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    path
}
