//! CI twins of `cases/prism-dam-break` and `cases/prism-washout` (issue 13, S2 §5–6): the same
//! scenes at particle size 0.02 m instead of 0.005 m (the time steps scaled alike, as
//! `cases/prism-dam-break/sweep.py --spacing 0.02` does), run through the real processes.

use schemas::validation::{largest_abs, record, Record};
use stack_tests::{coupler_run, csv_header, csv_rows, out_dir, stderr, workspace};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

/// `cases/NAME/FILE` at particle size 0.02 m (Δt 8e-4 s) ending at `end`, written into `dir`.
pub(crate) fn coarse_case(name: &str, file: &str, dir: &Path, end: f64) -> PathBuf {
    let source = workspace().join("cases").join(name).join(file);
    let text =
        std::fs::read_to_string(&source).unwrap_or_else(|e| panic!("cannot read {}: {e}", source.display()));
    for key in ["spacing = 0.005", "2.0e-4", "end_time = 0.5"] {
        assert!(text.contains(key), "{}: no `{key}` to scale", source.display());
    }
    let text = text
        .replace("spacing = 0.005", "spacing = 0.02")
        .replace("2.0e-4", "8.0e-4")
        .replace("end_time = 0.5", &format!("end_time = {end}"));
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    path
}

/// The unresolved prism's CI twin (`case.toml` to 0.3 s), run once for this file's test and
/// `gpu_prism.rs`' CPU reference (the case's `[report]` ladders do not change the run): its
/// output folder and what the coupler wrote to stderr.
pub(crate) fn unresolved_twin() -> &'static (PathBuf, String) {
    static RUN: OnceLock<(PathBuf, String)> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = out_dir("prism-dam-break-ci-unresolved");
        let case = coarse_case("prism-dam-break", "case.toml", &dir, 0.3);
        // the resolved prism the case names as its reference must sit beside it
        coarse_case("prism-dam-break", "resolved.toml", &dir, 0.3);
        let out = dir.join("out");
        let (_, _, log) = run(&case, &out);
        (out, log)
    })
}

/// Runs `case`; the ledger's rows and its header, and what the coupler wrote to stderr.
fn run(case: &Path, out: &Path) -> (Vec<Vec<f64>>, Vec<String>, String) {
    let run = coupler_run(case, out);
    let log = stderr(&run);
    assert!(run.status.success(), "{}: coupler failed:\n{log}", case.display());
    let ledger = out.join("ledger.csv");
    (csv_rows(&ledger), csv_header(&ledger), log)
}

pub(crate) fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

/// ∫ F_x dt over the run [N s].
pub(crate) fn impulse_x(rows: &[Vec<f64>], fx: usize) -> f64 {
    rows.windows(2)
        .map(|w| 0.5 * (w[0][fx] + w[1][fx]) * (w[1][1] - w[0][1]))
        .sum()
}

/// S2 §5(1): the 0.05 m prism, unresolved (drag law) against resolved (body particles), to
/// 0.3 s (the surge reaches the prism at about 0.15 s). The ledger balances to round-off (the
/// ledger's own 1e-12), and the X impulse per unit width of the unresolved prism lies within
/// [0.5, 1.0] of the resolved one. The band: above, 1, since a quasi-steady drag law has none of
/// the resolved prism's impact spike (185–275 N/m against 77–101) and takes less than its
/// impulse at every resolution run (cases/prism-dam-break/README.md: 0.62 at Δs = 0.02 m, 0.80
/// at 0.01 m, 0.72 at 5 mm); below, 0.5, a fifth under the smallest of those. Neither side is
/// converged at 0.02 m (the resolved prism 2.5 particles wide, the sample points 2.5 particles
/// upstream); measured 0.62 here. A factor of 2 either way in the law (a lost width factor, C_D
/// doubled or halved) leaves the band, as do drag on the wrong side and no submersion.
#[test]
fn the_unresolved_prism_takes_the_impulse_of_the_resolved_one_within_the_coarse_bound() {
    let dir = out_dir("prism-dam-break-ci");
    let resolved = coarse_case("prism-dam-break", "resolved.toml", &dir, 0.3);
    let started = Instant::now();
    let (unresolved, log) = unresolved_twin();
    let ledger = unresolved.join("ledger.csv");
    let (rows, header) = (csv_rows(&ledger), csv_header(&ledger));
    let (ref_rows, ref_header, _) = run(&resolved, &dir.join("resolved"));
    let run_time_s = started.elapsed().as_secs_f64();
    // 0.05 m is wider than the reaction's support 2.4 Δs = 0.048 m: the user is told.
    assert!(
        log.contains("warning: coupling.drag: a member 0.05 m wide is 1.0 times the radius 0.0480 m"),
        "no wide-member warning:\n{log}"
    );
    let balance = column(&header, "balance");
    let worst = largest_abs(rows.iter().map(|r| r[balance]));
    assert!(worst <= 1e-12, "ledger balance {worst:e}");
    let width = 0.05;
    let j = impulse_x(&rows, column(&header, "prism_fx")) / width;
    let j_ref = impulse_x(&ref_rows, column(&ref_header, "prism_fx")) / width;
    eprintln!(
        "impulse per unit width: unresolved {j:.4} N s/m, resolved {j_ref:.4} N s/m, ratio {:.3}",
        j / j_ref
    );
    assert!(
        j_ref > 1.0,
        "the surge must load the resolved prism: {j_ref} N s/m"
    );
    record(Record {
        id: "prism-unresolved-vs-resolved-impulse-ci".into(),
        capability: "unresolved drag coupling (S2 §5)".into(),
        reference: "the same prism resolved by body particles (S2 Fig. 4: close agreement at 0.05 m)".into(),
        case: "cases/prism-dam-break (case.toml and resolved.toml), CI twin, 0.3 s".into(),
        resolution: "E-MPS, Δs = 0.02 m, Δt = 8e-4 s, D = 0.05 m (2.5 particles)".into(),
        measure: "X impulse per unit width, unresolved / resolved".into(),
        value: j / j_ref,
        bound: None,
        bound_source: "the ratios measured at Δs = 0.02, 0.01 and 0.005 m (0.62, 0.80, 0.72, \
                       cases/prism-dam-break/README.md), all below 1 (a quasi-steady law has no impact \
                       spike): asserted within [0.5, 1.0], which a factor of 2 in the law leaves"
            .into(),
        source: "tests/tests/prism_cases.rs::the_unresolved_prism_takes_the_impulse_of_the_resolved_one_within_the_coarse_bound"
            .into(),
        run_time_s,
        note: Some("asserted within 0.5 … 1.0; S2 Fig. 4's close agreement is not reproduced at this size".into()),
        ..Default::default()
    });
    assert!(
        (0.5..=1.0).contains(&(j / j_ref)),
        "ratio {} (band [0.5, 1.0])",
        j / j_ref
    );
}

/// The frame's node positions in each of its VTU snapshots `prism/frame-*.vtu` under `out`, in
/// time order.
fn frame_snapshots(out: &Path) -> Vec<Vec<[f64; 3]>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(out.join("prism"))
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.retain(|f| {
        f.file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.starts_with("frame-") && n.ends_with(".vtu"))
    });
    files.sort();
    files
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).unwrap_or_default();
            let points = text
                .split("<Points>")
                .nth(1)
                .and_then(|p| p.split("</DataArray>").next())
                .and_then(|p| p.split_once('>'))
                .map_or("", |(_, values)| values);
            let values: Vec<f64> = points.split_whitespace().filter_map(|v| v.parse().ok()).collect();
            values.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect()
        })
        .collect()
}

/// S2 §6: with the lowered yield stress the drag breaks the prism (at 0.239 s at Δs = 0.02 m)
/// and the coupled run goes on through the fracture (the structure re-declares its geometry,
/// the drag law cuts the new members) with the ledger balanced to round-off. The pieces are
/// carried downstream on the channel's floor (the frame's wall at z = 0): no node goes more than
/// 1 mm below it (measured 3e-6 m; without the wall the pieces sank 24 mm by 0.45 s), none flies
/// above the water (0.2 m). The frame warns of nothing: its energy balance holds through the
/// fractures and every step reaches its equilibrium tolerance (measured with the case's 2.5e-5 s
/// frame steps: residual 7.5e-6 J against 6.8e-2 J of external work; before the restart after a fracture and the rule that a free end holds no
/// hinge, `structure-solver/src/frame/fracture.rs`, the balance was lost at 0.2424 s and ended at
/// −8.4e-2 J against 7.9e-2 J of external work).
#[test]
fn the_washout_prism_fractures_and_the_coupled_run_goes_on() {
    let dir = out_dir("prism-washout-ci");
    let case = coarse_case("prism-washout", "case.toml", &dir, 0.45);
    let out = dir.join("out");
    let (rows, header, log) = run(&case, &out);
    assert!(
        !log.contains("warning from prism"),
        "the frame's solution is not to be trusted:\n{log}"
    );
    let balance = column(&header, "balance");
    let worst = largest_abs(rows.iter().map(|r| r[balance]));
    assert!(worst <= 1e-12, "ledger balance {worst:e}");
    let events = std::fs::read_to_string(out.join("prism").join("hinge-events.csv")).unwrap_or_default();
    let fractures: Vec<&str> = events.lines().filter(|l| l.contains(",fracture,")).collect();
    eprintln!("{} fractures, first: {:?}", fractures.len(), fractures.first());
    assert!(!fractures.is_empty(), "no fracture:\n{events}");
    // a break separates two elements (or an element and its support): the prism's 4 elements have
    // 8 ends, so at most 8 fractures; a broken piece's free end must not split again and again
    // (it did, adding a node each step: 44 fractures by 0.26 s)
    assert!(
        fractures.len() <= 8,
        "{} fractures for 4 elements:\n{events}",
        fractures.len()
    );
    let first: f64 = fractures[0]
        .split(',')
        .next()
        .and_then(|t| t.parse().ok())
        .unwrap_or(f64::NAN);
    let last_window = rows.last().map_or(0.0, |r| r[1]);
    assert!(
        last_window > first,
        "the run must go on after the fracture at {first} s (ended at {last_window} s)"
    );
    let snapshots = frame_snapshots(&out);
    let nodes = snapshots.iter().flatten();
    let lowest = nodes.clone().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    let highest = nodes
        .map(|p| p[2])
        .fold(f64::NEG_INFINITY, schemas::validation::max_or_nan);
    let downstream = snapshots.last().map_or(0.0, |s| {
        s.iter().map(|p| p[0]).fold(0.0, schemas::validation::max_or_nan)
    });
    eprintln!(
        "{} snapshots: lowest node {lowest:.2e} m, highest {highest:.3} m, last farthest downstream x = {downstream:.3} m",
        snapshots.len()
    );
    assert!(snapshots.len() >= 40, "{} frame snapshots", snapshots.len());
    assert!(lowest > -1e-3, "a piece sank to z = {lowest} m");
    assert!(highest < 0.2, "a piece was thrown to z = {highest} m");
    assert!(
        downstream > 0.75,
        "the pieces were not carried: x = {downstream} m"
    );
}
