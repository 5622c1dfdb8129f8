//! Issue 16 item 10: checkpoint and resume through the real processes. Each case runs once
//! uninterrupted, and once killed (SIGKILL to the coupler and both participants, at a random moment
//! after the first checkpoint) and resumed with `coupler run CASE --resume OUT`; every output file of
//! the two runs must then be equal byte for byte. The fracturing frame is also resumed from each of
//! its two checkpoints, one before and one after the fracture; the floating pool is also resumed
//! with its fluid on the GPU. Excluded, because they hold wall-clock time or
//! the run's identity: the logs (`NAME.log`, appended to by the resumed run), the checkpoint folder,
//! and in `recording.rec` each frame's wall time, the run id (header, `Welcome`) and the pid in each `Hello`
//! (the recording is compared frame by frame on everything else).

use schemas::message::{FromParticipant, ToParticipant};
use schemas::recording::{Message, Recording};
use stack_tests::{
    binary, breakable_drag_column_case, case_from, coupler, coupler_run, csv_rows, gpu_coupler_run, out_dir,
    replaced, stderr, DRAG_COLUMN_CASE, FLOATING_POOL_CASE,
};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Adds `checkpoint_interval` to the case's `[coupling]` section.
pub(crate) fn with_checkpoints(case: &Path, interval: &str) {
    let text = std::fs::read_to_string(case).unwrap_or_default();
    assert!(
        text.contains("\n[coupling]\n"),
        "the case has a [coupling] section"
    );
    let text = text.replacen(
        "\n[coupling]\n",
        &format!("\n[coupling]\ncheckpoint_interval = {interval}\n"),
        1,
    );
    std::fs::write(case, text).unwrap_or_else(|e| panic!("{e}"));
}

/// A number in [0, n) that differs from run to run (the moment of the kill).
fn random_below(n: u64) -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.subsec_nanos())
        .unwrap_or(0);
    u64::from(nanos ^ std::process::id()) % n.max(1)
}

/// Whether `out` holds a complete checkpoint (a coupler manifest).
fn has_checkpoint(out: &Path) -> bool {
    std::fs::read_dir(out.join("checkpoint"))
        .map(|d| {
            d.filter_map(Result::ok).any(|e| {
                e.file_name().to_string_lossy().starts_with("coupler-")
                    && !e.file_name().to_string_lossy().ends_with(".tmp")
            })
        })
        .unwrap_or(false)
}

/// Starts `coupler run CASE --out OUT` and kills the whole stack with SIGKILL at a random moment
/// after its first complete checkpoint (within `spread` times the time it took to get there).
/// Returns whether the run was killed (it may have ended first).
fn run_and_kill(case: &Path, out: &Path, log: &Path, spread: f64) -> bool {
    let err = std::fs::File::create(log).unwrap_or_else(|e| panic!("{e}"));
    let mut child = Command::new(binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .stdout(Stdio::null())
        .stderr(err)
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    let started = Instant::now();
    let limit = started + Duration::from_secs(120);
    while !has_checkpoint(out) {
        if child.try_wait().ok().flatten().is_some() || Instant::now() > limit {
            panic!(
                "the run ended without a checkpoint:\n{}",
                std::fs::read_to_string(log).unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    // anywhere in the next `spread` checkpoint intervals (the run may end first)
    let delay = random_below((started.elapsed().as_millis() as f64 * spread) as u64);
    std::thread::sleep(Duration::from_millis(delay));
    // the participants' pids, from the coupler's "started NAME (EXE, pid N)" lines
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let pids: Vec<String> = text
        .lines()
        .filter_map(|l| l.strip_prefix("started "))
        .filter_map(|l| {
            l.rsplit_once("pid ")
                .map(|(_, p)| p.trim_end_matches(')').to_string())
        })
        .collect();
    assert_eq!(pids.len(), 2, "two participants started:\n{text}");
    let ended_first = child.try_wait().ok().flatten().is_some();
    let mut kill = Command::new("kill");
    kill.arg("-KILL").arg(child.id().to_string()).args(&pids);
    let _ = kill.status();
    let _ = child.wait();
    println!(
        "{} {delay} ms after the first checkpoint",
        if ended_first {
            "the run had ended"
        } else {
            "killed the stack"
        }
    );
    // the participants die with SIGKILL too; wait until they are gone
    for pid in &pids {
        let proc = PathBuf::from(format!("/proc/{pid}"));
        let gone = Instant::now() + Duration::from_secs(10);
        while proc.exists() && Instant::now() < gone {
            std::thread::sleep(Duration::from_millis(5));
        }
    }
    !ended_first
}

/// Every file under `dir` that must be equal byte for byte (relative paths, sorted).
fn compared_files(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, dir: &Path, found: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .filter_map(Result::ok)
        {
            let path = e.path();
            let rel = path.strip_prefix(root).unwrap_or(&path).to_path_buf();
            let name = rel
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or_default()
                .to_string();
            if path.is_dir() {
                if !rel.starts_with("checkpoint") {
                    walk(root, &path, found);
                }
            } else if !(name.ends_with(".log") || name == ".coupler.lock" || name == "recording.rec") {
                found.push(rel);
            }
        }
    }
    let mut found = Vec::new();
    walk(dir, dir, &mut found);
    found.sort();
    found
}

/// Asserts that the outputs of `a` and `b` are the same (see the module doc for what is excluded).
pub(crate) fn assert_same_outputs(a: &Path, b: &Path) {
    let files = compared_files(a);
    assert_eq!(files, compared_files(b), "the two runs wrote the same files");
    for rel in &files {
        let (x, y) = (std::fs::read(a.join(rel)), std::fs::read(b.join(rel)));
        let (x, y) = (x.unwrap_or_default(), y.unwrap_or_default());
        let at = x.iter().zip(&y).position(|(p, q)| p != q);
        assert!(
            x == y,
            "{} differs: {} and {} bytes, first difference at byte {at:?}",
            rel.display(),
            x.len(),
            y.len()
        );
    }
    let read = |d: &Path| Recording::read(&d.join("recording.rec")).unwrap_or_else(|e| panic!("{e}"));
    let (ra, rb) = (read(a), read(b));
    assert_eq!(ra.end, rb.end);
    let mut ha = ra.header.clone();
    ha.run_id = rb.header.run_id.clone();
    assert_eq!(ha, rb.header, "recording headers differ beyond the run id");
    assert_eq!(ra.frames.len(), rb.frames.len(), "recordings hold as many frames");
    for (i, (fa, fb)) in ra.frames.iter().zip(&rb.frames).enumerate() {
        let mut ma = fa.message.clone();
        match (&mut ma, &fb.message) {
            (Message::From(FromParticipant::Hello(ha)), Message::From(FromParticipant::Hello(hb))) => {
                ha.pid = hb.pid
            }
            (
                Message::To(ToParticipant::Welcome { run_id: a }),
                Message::To(ToParticipant::Welcome { run_id: b }),
            ) => a.clone_from(b),
            _ => {}
        }
        assert!(
            fa.participant == fb.participant && ma == fb.message,
            "recording frame {i} differs: {:?} vs {:?}",
            fa.participant,
            fb.participant
        );
    }
    println!(
        "{} files equal byte for byte, {} recording frames equal but for wall time",
        files.len(),
        ra.frames.len()
    );
}

/// Runs `coupler run CASE --resume OUT` to its end; returns its stderr (it says which checkpoint
/// it resumed from).
fn resume(case: &Path, out: &Path) -> String {
    let again = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--resume",
        out.to_str().unwrap_or_default(),
    ]);
    let err = stderr(&again);
    println!("{err}");
    assert!(again.status.success(), "the resumed run failed:\n{err}");
    assert!(err.contains("resuming from the checkpoint of window"), "{err}");
    err
}

/// Runs `case` uninterrupted into `dir/whole`, then killed and resumed into `dir/resumed`, and
/// compares the two.
fn killed_and_resumed_equals_uninterrupted(dir: &Path, case: &Path) {
    let run = coupler_run(case, &dir.join("whole"));
    let err = stderr(&run);
    assert!(run.status.success(), "{err}");
    assert!(
        err.contains("checkpoints "),
        "the output estimate counts the checkpoints: {err}"
    );
    killed_and_resumed_equals(dir, case);
}

/// Runs `case` killed and resumed into `dir/resumed` and compares it with the uninterrupted run
/// in `dir/whole`.
fn killed_and_resumed_equals(dir: &Path, case: &Path) {
    let whole = dir.join("whole");
    // Killed anywhere in the next 1.5 checkpoint intervals after the first checkpoint; a run
    // that ended before its kill tested no kill, so it is run again killed sooner (a quarter of
    // the interval each time), until a kill lands.
    let resumed = dir.join("resumed");
    let mut spread = 1.5;
    while !run_and_kill(case, &resumed, &dir.join("killed.txt"), spread) {
        spread /= 4.0;
        assert!(spread > 1e-3, "every run ended before its kill");
        std::fs::remove_dir_all(&resumed).unwrap_or_else(|e| panic!("{e}"));
    }
    resume(case, &resumed);
    assert_same_outputs(&whole, &resumed);
}

/// The floating pool with its fluid on the GPU (lavapipe in CI): a checkpoint copies the
/// particles back while the device steps on in its own order, and the resumed run uploads the
/// host's copy; the f32 sums must still come out in the same order, every frame and CSV equal.
#[test]
fn a_floating_box_on_the_gpu_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-gpu-floating-pool");
    let case = dir.join("case.toml");
    let text = replaced(
        FLOATING_POOL_CASE,
        &[
            ("end_time = 2.0", "end_time = 0.048"),
            ("[fluid.pool]\n", "[fluid.pool]\nbackend = \"gpu\"\n"),
            ("output_interval = 0.5", "output_interval = 0.008"),
        ],
    );
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    with_checkpoints(&case, "0.016");
    if gpu_coupler_run(&case, &dir.join("whole"), "gpu").is_none() {
        return;
    }
    killed_and_resumed_equals(&dir, &case);
}

#[test]
fn a_floating_box_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-floating-box");
    let case = case_from(
        "dam-break-floating-box",
        &dir,
        &[
            ("end_time", "0.03"),
            ("spacing", "0.02"),
            ("output_interval", "0.01"),
            ("surface_mesh", "true"),
            (
                "tank",
                "{ min = [0.0, 0.0, 0.0], max = [0.6, 0.44, 0.4], lid = true }",
            ),
        ],
    );
    // a whole number of windows also for the case's report ladders (windows up to 0.01 s)
    with_checkpoints(&case, "0.01");
    killed_and_resumed_equals_uninterrupted(&dir, &case);
}

/// The same box coupled implicitly (IQN-ILS): the fluid steps its bodies to the iterated
/// window-end pose, read afresh from each window's inputs, so nothing of it is left out of the
/// checkpoint.
#[test]
fn an_implicit_floating_box_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-floating-box-implicit");
    let case = case_from(
        "dam-break-floating-box",
        &dir,
        &[
            ("end_time", "0.03"),
            ("spacing", "0.02"),
            ("output_interval", "0.01"),
            (
                "tank",
                "{ min = [0.0, 0.0, 0.0], max = [0.6, 0.44, 0.4], lid = true }",
            ),
            (
                "scheme",
                "\"implicit\"\nacceleration = \"iqn-ils\"\ntolerance = 1.0e-4",
            ),
        ],
    );
    with_checkpoints(&case, "0.01");
    killed_and_resumed_equals_uninterrupted(&dir, &case);
}

#[test]
fn the_bridge_washout_with_inflow_outflow_and_a_release_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-bridge");
    // F_d = 0.1 MN: the bore lifts the deck off its bearings near t = 4 s, after the checkpoints
    // at 1.2, 2.4 and 3.6 s, so the resumed run makes the release again.
    let case = case_from(
        "bridge-washout-small",
        &dir,
        &[
            ("end_time", "4.32"),
            ("release_force", "1.0e5"),
            ("surface_mesh", "false"),
        ],
    );
    with_checkpoints(&case, "1.2");
    killed_and_resumed_equals_uninterrupted(&dir, &case);
    let releases = std::fs::read_to_string(dir.join("resumed/bridge/releases.csv")).unwrap_or_default();
    assert!(
        releases
            .lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("deck,") && l.len() > "deck,".len()),
        "the deck was released: {releases}"
    );
}

#[test]
fn an_implicit_oscillator_with_iqn_ils_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-oscillator");
    let case = case_from(
        "oscillator",
        &dir,
        &[("end_time", "2.0"), ("max_iterations", "30\nreuse_windows = 3")],
    );
    // a whole number of windows also for the case's report ladders (windows up to 0.04 s)
    with_checkpoints(&case, "0.4");
    killed_and_resumed_equals_uninterrupted(&dir, &case);
    // the resumed run's recording replays like an uninterrupted one's
    let recording = dir.join("resumed/recording.rec");
    let replay = coupler(&[
        "replay",
        recording.to_str().unwrap_or_default(),
        "--participant",
        "mass-right",
        "--out",
        dir.join("replay").to_str().unwrap_or_default(),
    ]);
    assert!(replay.status.success(), "{}", stderr(&replay));
}

/// The fluid on two MPI ranks (issue 39): each rank writes its own checkpoint file beside rank
/// 0's and resumes from it; the frames' pieces and indexes, the probes and the box's history
/// are written again byte for byte.
#[cfg(feature = "mpi")]
#[test]
fn a_floating_box_with_its_fluid_on_two_ranks_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-ranked-floating-box");
    let case = stack_tests::ranked_floating_box(&dir, 2, "scheme = \"explicit\"");
    with_checkpoints(&case, "0.01");
    killed_and_resumed_equals_uninterrupted(&dir, &case);
    let checkpoints: Vec<String> = std::fs::read_dir(dir.join("resumed/checkpoint"))
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        checkpoints.iter().any(|f| f.starts_with("water.r1-")),
        "rank 1 writes its own checkpoint file: {checkpoints:?}"
    );
}

#[test]
fn resuming_a_folder_without_a_checkpoint_is_refused_as_bad_usage() {
    let dir = out_dir("resume-none");
    let case = case_from("oscillator", &dir, &[("end_time", "0.1")]);
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(run.status.success(), "{}", stderr(&run));
    let again = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--resume",
        out.to_str().unwrap_or_default(),
    ]);
    let err = stderr(&again);
    assert_eq!(again.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no complete checkpoint") && err.contains("checkpoint_interval"),
        "{err}"
    );
    let missing = dir.join("no-such-folder");
    let again = coupler(&[
        "run",
        case.to_str().unwrap_or_default(),
        "--resume",
        missing.to_str().unwrap_or_default(),
    ]);
    assert_eq!(again.status.code(), Some(2), "{}", stderr(&again));
}

#[test]
fn a_checkpoint_interval_that_is_not_a_whole_number_of_windows_is_refused_by_check() {
    let dir = out_dir("resume-check");
    let case = case_from("oscillator", &dir, &[("end_time", "0.1")]);
    with_checkpoints(&case, "0.0125");
    let check = coupler(&["check", case.to_str().unwrap_or_default()]);
    let err = stderr(&check);
    assert_eq!(check.status.code(), Some(2), "{err}");
    assert!(
        err.contains("case.toml")
            && err.contains("coupling.checkpoint_interval")
            && err.contains("whole number"),
        "{err}"
    );
}

/// A fracturing frame in a coupled run: the two-part cantilever of
/// `structure-solver/tests/frame_fracture.rs` (a strong member from the clamped base to x = 1 m, a
/// weak one to the tip, critical curvature 0.2 1/m, a tip load in −z ramped to 12 kN over 0.06 s),
/// in a participant that also holds a point mass joined by a coupling spring to a point mass of a
/// second participant. Standalone, its weak member hinges at t = 0.0349 s and fractures at
/// 0.0618 s (one new node). Checkpoints at 0.04 s (a hinge, before the fracture) and 0.08 s (after
/// it); the run ends at 0.1 s, so both stay in the folder (two are kept). Histories of both frame
/// nodes, section forces, hinge events, the energy account and snapshots every 0.02 s.
const FRACTURING_FRAME: &str = concat!(
    r#"
[case]
name = "fracturing-frame"
end_time = 0.1

[structure.cantilever]
max_step = 1.0e-3

[[structure.cantilever.point_mass]]
name = "m1"
mass = 1.0
position = [0.0, 1.0, 0.0]
displacement = [0.01, 0.0, 0.0]

[[structure.cantilever.spring]]
a = "m1"
b = "ground"
stiffness = 400.0

"#,
    include_str!("../../structure-solver/tests/data/fracturing_cantilever_frame.toml"),
    r#"[structure.cantilever.history]
interval = 0.01
points = ["m1"]
nodes = [2, 3]
vtu_interval = 0.02

[structure.mass]
max_step = 1.0e-3

[[structure.mass.point_mass]]
name = "m2"
mass = 1.0
position = [1.0, 1.0, 0.0]

[[structure.mass.spring]]
a = "m2"
b = "ground"
stiffness = 400.0

[structure.mass.history]
interval = 0.01
points = ["m2"]

[coupling]
window = 5.0e-4
scheme = "explicit"
order = ["cantilever", "mass"]
checkpoint_interval = 0.04

[[coupling.spring]]
a = "cantilever/m1"
b = "mass/m2"
stiffness = 100.0
"#
);

/// Copies the files of folder `from` into a new folder `to`.
fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap_or_else(|e| panic!("{e}"));
    for e in std::fs::read_dir(from)
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
    {
        let target = to.join(e.file_name());
        if e.path().is_dir() {
            copy_folder(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap_or_else(|err| panic!("{err}"));
        }
    }
}

/// The checkpoint manifests in `out`, oldest first.
fn manifests(out: &Path) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(out.join("checkpoint"))
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("coupler-") && n.ends_with(".bin"))
        })
        .collect();
    found.sort();
    found
}

#[test]
fn a_fracturing_frame_killed_and_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-frame");
    let case = dir.join("case.toml");
    std::fs::write(&case, FRACTURING_FRAME).unwrap_or_else(|e| panic!("{e}"));
    let check = coupler(&["check", case.to_str().unwrap_or_default()]);
    assert!(check.status.success(), "{}", stderr(&check));
    // killed at a random moment after the first checkpoint, resumed from the last one
    killed_and_resumed_equals_uninterrupted(&dir, &case);
    let whole = dir.join("whole");
    let events = std::fs::read_to_string(whole.join("cantilever/hinge-events.csv")).unwrap_or_default();
    let fracture_time: f64 = events
        .lines()
        .find(|l| l.contains(",fracture,"))
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("the weak member fractured: {events}"));
    assert!(
        fracture_time > 0.04 && fracture_time < 0.08,
        "the fracture at {fracture_time} s is between the checkpoints"
    );
    let last = std::fs::read_to_string(whole.join("cantilever/frame-00005.vtu")).unwrap_or_default();
    assert!(
        last.contains("NumberOfPoints=\"6\" NumberOfCells=\"4\""),
        "the last snapshot has the node made by the fracture"
    );
    // the uninterrupted run kept both checkpoints: resume from each of them
    let kept = manifests(&whole);
    assert_eq!(kept.len(), 2, "checkpoints at 0.04 and 0.08 s: {kept:?}");
    // from 0.08 s: the fractured topology (6 nodes, the split element) is read back; from 0.04 s
    // (the later manifest gone, as when a run dies while writing it): a hinge is read back and
    // the fracture happens again in the resumed run
    resume_on_both_sides_of_a_fracture(&case, &whole, &dir, "0.08", "0.04");
}

/// Resumes copies of the uninterrupted run `whole` (two checkpoints) from its later checkpoint,
/// at t = `after`, and, with the later manifest removed, from the earlier one at t = `before`;
/// each resumed run's outputs must equal `whole`'s byte for byte.
fn resume_on_both_sides_of_a_fracture(case: &Path, whole: &Path, dir: &Path, after: &str, before: &str) {
    let later = dir.join("from-after-the-fracture");
    copy_folder(whole, &later);
    let err = resume(case, &later);
    assert!(err.contains(&format!("t = {after}")), "{err}");
    assert_same_outputs(whole, &later);
    let earlier = dir.join("from-before-the-fracture");
    copy_folder(whole, &earlier);
    std::fs::remove_file(manifests(&earlier)[1].as_path()).unwrap_or_else(|e| panic!("{e}"));
    let err = resume(case, &earlier);
    assert!(err.contains(&format!("t = {before}")), "{err}");
    assert_same_outputs(whole, &earlier);
}

#[test]
fn the_drag_column_resumed_after_the_surge_writes_the_same_outputs() {
    let dir = out_dir("resume-drag");
    let case = dir.join("case.toml");
    // checkpoints at 0.06, 0.12 and 0.18 s; the surge reaches the column at 0.152 s. The run
    // whole, then resumed from its last checkpoint, when the law has taken its sub-members' flow
    // directions from the surge (a random kill is left to the other cases: this one takes 3 s a run)
    let text = DRAG_COLUMN_CASE
        .replace("SCHEME", "explicit")
        .replace("TOLERANCE", "checkpoint_interval = 0.06");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let whole = dir.join("whole");
    let run = coupler_run(&case, &whole);
    assert!(run.status.success(), "{}", stderr(&run));
    let last = dir.join("from-the-last-checkpoint");
    copy_folder(&whole, &last);
    let err = resume(&case, &last);
    assert!(err.contains("t = 0.18"), "{err}");
    assert_same_outputs(&whole, &last);
    let ledger = csv_rows(&whole.join("ledger.csv"));
    // window,time,iterations,residual,water_fx,…,column_fx (8): drag before the last checkpoint
    let first = ledger
        .iter()
        .find(|r| r[8] != 0.0)
        .map_or(f64::INFINITY, |r| r[1]);
    println!("the column first took drag at t = {first} s");
    assert!(first < 0.18, "the column took no drag before the last checkpoint");
}

/// Resume across a fracture under implicit coupling (issue 13): the breakable drag column of
/// `tests/drag_coupling.rs` moved to x = 0.112 m, into the board's gap, so the surge breaks it at
/// t ≈ 0.052 s (fractures in two steps; 130 windows to 0.065 s; before the return to the squash
/// load's apex, whose hinge carries no moment, at 0.046 s). Checkpoints at 0.03 s (the column
/// intact) and 0.06 s (broken: the frame's new nodes and elements, the drag law's new
/// sub-members and their flow directions, the window the fracture ended unconverged behind it).
/// The run whole, then resumed from each checkpoint: from 0.06 s the broken topology is read
/// back, from 0.03 s the resumed run breaks the column again in the same sweeps; every output
/// equal byte for byte. No random kill (the other cases do that): the three runs take about 5 s
/// of CPU together.
#[test]
fn a_column_broken_under_implicit_drag_coupling_resumed_writes_the_same_outputs() {
    let dir = out_dir("resume-drag-fracture");
    let case = dir.join("case.toml");
    let text = breakable_drag_column_case(0.112, 0.065, "\ncheckpoint_interval = 0.03");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let whole = dir.join("whole");
    let run = coupler_run(&case, &whole);
    let log = stderr(&run);
    assert!(run.status.success(), "{log}");
    assert!(log.contains("changed (a fracture)"), "no topology note:\n{log}");
    let events = std::fs::read_to_string(whole.join("column/hinge-events.csv")).unwrap_or_default();
    let fractures: Vec<f64> = events
        .lines()
        .filter(|l| l.contains(",fracture,"))
        .filter_map(|l| l.split(',').next().and_then(|t| t.parse().ok()))
        .collect();
    println!("fractures at {fractures:?} s");
    assert!(
        !fractures.is_empty() && fractures.iter().all(|&t| t > 0.03 && t < 0.06),
        "the column breaks between the checkpoints: {events}"
    );
    let ledger = csv_rows(&whole.join("ledger.csv"));
    // window,time,iterations,residual (NaN: a window a fracture ended)
    assert!(
        ledger.iter().any(|r| r[3].is_nan() && r[1] < 0.06),
        "a window before the last checkpoint was ended by the fracture"
    );
    let kept = manifests(&whole);
    assert_eq!(kept.len(), 2, "checkpoints at 0.03 and 0.06 s: {kept:?}");
    // from 0.06 s: the broken column and the law's sub-members of its pieces are read back;
    // from 0.03 s (the later manifest gone): the resumed run breaks the column again
    resume_on_both_sides_of_a_fracture(&case, &whole, &dir, "0.06", "0.03");
}

/// Issue 41, item 9: a resume checks every input, not the case text alone. The oscillator with a
/// load on m1 from a table and checkpoints, killed after its first checkpoint: an edited load
/// table is refused naming the table, an edited setting is refused naming the case's settings,
/// and a comment added to the case resumes (the settings are the same).
#[test]
fn a_resume_refuses_an_edited_load_table_or_setting_but_not_a_comment() {
    let dir = out_dir("resume-inputs");
    // long enough (about 5 s) to be killed soon after its first checkpoint
    let case = case_from("oscillator", &dir, &[("end_time", "20.0")]);
    with_checkpoints(&case, "2");
    let text = std::fs::read_to_string(&case).unwrap_or_default();
    let load = "\n[[structure.mass-left.load]]\npoint = \"m1\"\nhistory = \"table\"\ntable = \"push.csv\"\n";
    let text = text.replacen(
        "\n[structure.mass-left.history]",
        &format!("{load}\n[structure.mass-left.history]"),
        1,
    );
    std::fs::write(&case, &text).unwrap_or_else(|e| panic!("{e}"));
    let push = "t, fx, fy, fz\n0, 0, 0, 0\n1, 1, 0, 0\n";
    std::fs::write(dir.join("push.csv"), push).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let mut spread = 1.0;
    while !run_and_kill(&case, &out, &dir.join("killed.txt"), spread) {
        spread /= 4.0;
        assert!(spread > 1e-4, "every run ended before its kill");
        std::fs::remove_dir_all(&out).unwrap_or_else(|e| panic!("{e}"));
    }
    let resume_with = || {
        coupler(&[
            "run",
            case.to_str().unwrap_or_default(),
            "--resume",
            out.to_str().unwrap_or_default(),
        ])
    };

    std::fs::write(dir.join("push.csv"), push.replace("1, 1, 0, 0", "1, 2, 0, 0"))
        .unwrap_or_else(|e| panic!("{e}"));
    let edited = resume_with();
    let err = stderr(&edited);
    println!("{err}");
    assert_eq!(edited.status.code(), Some(2), "{err}");
    assert!(
        err.contains("push.csv") && err.contains("changed since the run was started"),
        "{err}"
    );
    std::fs::write(dir.join("push.csv"), push).unwrap_or_else(|e| panic!("{e}"));

    std::fs::write(&case, text.replacen("mass = 1.0", "mass = 1.5", 1)).unwrap_or_else(|e| panic!("{e}"));
    let heavier = resume_with();
    let err = stderr(&heavier);
    assert_eq!(heavier.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the case's settings") && !err.contains("push.csv"),
        "{err}"
    );

    std::fs::write(&case, format!("# a comment added after the run\n{text}"))
        .unwrap_or_else(|e| panic!("{e}"));
    resume(&case, &out);
}

/// Runs `coupler ARGS…` and asserts that it succeeded; returns its stderr.
pub(crate) fn coupler_ok(args: &[&str]) -> String {
    let done = coupler(args);
    let err = stderr(&done);
    println!("{err}");
    assert!(done.status.success(), "coupler {args:?} failed:\n{err}");
    err
}

/// The window of each checkpoint manifest in `out`, oldest first.
fn manifest_windows(out: &Path) -> Vec<u64> {
    manifests(out)
        .iter()
        .filter_map(|p| p.file_stem()?.to_str()?.strip_prefix("coupler-")?.parse().ok())
        .collect()
}

/// Issue 41, item 9: `coupler run CASE --resume OUT --end-time T` extends a finished run. The
/// implicit oscillator (IQN-ILS, windows of 0.01 s, checkpoints every 0.4 s, m1's history every
/// 0.03 s so that neither end below is a history time) run to its end_time 0.5 s, which is not a
/// checkpoint time (its last checkpoint is at 0.4 s), extended to 0.8 s (a checkpoint time: the
/// run keeps a checkpoint there), then to 1.3 s: every output and the recording equal those of
/// one run of the same case with `--end-time 1.3`, and the extended recording replays.
#[test]
fn a_run_extended_twice_with_end_time_writes_what_a_run_to_that_time_writes() {
    let dir = out_dir("resume-extend");
    let case = case_from("oscillator", &dir, &[("end_time", "0.5"), ("interval", "0.03")]);
    with_checkpoints(&case, "0.4");
    let path = case.to_str().unwrap_or_default();
    let straight = dir.join("straight");
    let s = straight.to_str().unwrap_or_default();
    coupler_ok(&["run", path, "--out", s, "--end-time", "1.3"]);
    let ledger = csv_rows(&straight.join("ledger.csv"));
    assert_eq!(ledger.len(), 130, "130 windows to 1.3 s");
    assert!(
        (ledger[129][1] - 1.3).abs() < 1e-12,
        "the last window ends at 1.3 s"
    );
    // m1's rows: every 0.03 s, and the end, which is not a history time
    let m1: Vec<f64> = csv_rows(&straight.join("mass-left/point-m1.csv"))
        .iter()
        .map(|r| r[0])
        .collect();
    assert!(
        m1.len() == 45 && (m1[43] - 1.29).abs() < 1e-9 && m1[44] == 1.3,
        "rows at 0, 0.03, …, 1.29 and 1.3 s: {m1:?}"
    );

    let extended = dir.join("extended");
    let e = extended.to_str().unwrap_or_default();
    coupler_ok(&["run", path, "--out", e]);
    assert_eq!(
        manifest_windows(&extended),
        vec![39],
        "0.5 s is not a checkpoint time"
    );
    let err = coupler_ok(&["run", path, "--resume", e, "--end-time", "0.8"]);
    assert!(
        err.contains("(t = 0.4 s)") && err.contains("to end at t = 0.8 s"),
        "{err}"
    );
    assert_eq!(
        manifest_windows(&extended),
        vec![39, 79],
        "a checkpoint at the end, 0.8 s"
    );
    let err = coupler_ok(&["run", path, "--resume", e, "--end-time", "1.3"]);
    assert!(
        err.contains("window 79 (t = 0.8 s)"),
        "extended from its end: {err}"
    );
    // the rows written at the old ends (0.5 and 0.8 s, not history times) were cut off
    assert_same_outputs(&straight, &extended);

    let replay = coupler(&[
        "replay",
        extended.join("recording.rec").to_str().unwrap_or_default(),
        "--participant",
        "mass-left",
        "--out",
        dir.join("replay").to_str().unwrap_or_default(),
    ]);
    assert!(replay.status.success(), "{}", stderr(&replay));
}

/// The same for a fluid: the floating box (E-MPS, a rigid body, surface meshes, frames every
/// 0.01 s) run to 0.02 s, a checkpoint time, and extended to 0.03 s from its checkpoint there:
/// every output and the recording equal those of one run with `--end-time 0.03`.
#[test]
fn a_floating_box_extended_with_end_time_writes_what_a_run_to_that_time_writes() {
    let dir = out_dir("resume-extend-floating-box");
    let case = case_from(
        "dam-break-floating-box",
        &dir,
        &[
            ("end_time", "0.02"),
            ("spacing", "0.02"),
            ("output_interval", "0.01"),
            ("surface_mesh", "true"),
            (
                "tank",
                "{ min = [0.0, 0.0, 0.0], max = [0.6, 0.44, 0.4], lid = true }",
            ),
        ],
    );
    with_checkpoints(&case, "0.01");
    let path = case.to_str().unwrap_or_default();
    let straight = dir.join("straight");
    coupler_ok(&[
        "run",
        path,
        "--out",
        straight.to_str().unwrap_or_default(),
        "--end-time",
        "0.03",
    ]);
    let extended = dir.join("extended");
    let e = extended.to_str().unwrap_or_default();
    coupler_ok(&["run", path, "--out", e]);
    let err = coupler_ok(&["run", path, "--resume", e, "--end-time", "0.03"]);
    assert!(
        err.contains("window 39 (t = 0.02 s)"),
        "extended from its end: {err}"
    );
    assert_same_outputs(&straight, &extended);
}

/// A finished run whose end is a checkpoint time, resumed without a later end time, continues from
/// the checkpoint before its last (as a run killed after its last checkpoint, while its solvers
/// wrote their end-of-run output, is completed): its outputs end as they were. Then the case file
/// is edited: a changed value is refused, naming the settings; comments, layout and a later
/// `end_time` extend the run from its end, to the same outputs as a run of the unedited case with
/// `--end-time`.
#[test]
fn a_finished_run_resumed_to_its_end_ends_as_it_did_and_an_edited_end_time_extends_it() {
    let dir = out_dir("resume-extend-edited");
    let case = case_from("oscillator", &dir, &[("end_time", "0.8")]);
    with_checkpoints(&case, "0.4");
    let text = std::fs::read_to_string(&case).unwrap_or_default();
    let path = case.to_str().unwrap_or_default();
    let out = dir.join("out");
    let o = out.to_str().unwrap_or_default();
    coupler_ok(&["run", path, "--out", o]);
    assert_eq!(manifest_windows(&out), vec![39, 79]);

    let again = dir.join("again");
    copy_folder(&out, &again);
    let err = coupler_ok(&["run", path, "--resume", again.to_str().unwrap_or_default()]);
    assert!(
        err.contains("the last checkpoint (t = 0.8 s) is at the end time")
            && err.contains("window 39 (t = 0.4 s)"),
        "{err}"
    );
    assert_same_outputs(&out, &again);
    assert_eq!(manifest_windows(&again), vec![39, 79]);

    let heavier =
        text.replacen("mass = 1.0", "mass = 1.5", 1)
            .replacen("end_time = 0.8", "end_time = 1.3", 1);
    std::fs::write(&case, heavier).unwrap_or_else(|e| panic!("{e}"));
    let refused = coupler(&["run", path, "--resume", o]);
    let err = stderr(&refused);
    assert_eq!(refused.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the case's settings") && err.contains("changed since the run was started"),
        "{err}"
    );

    let edited = format!(
        "# extended to 1.3 s after the run\n{}",
        text.replacen("end_time = 0.8", "end_time   =   1.3   # was 0.8", 1)
            .replacen("mass = 1.0", "mass = 1.0  # kg", 1)
    );
    std::fs::write(&case, edited).unwrap_or_else(|e| panic!("{e}"));
    let err = coupler_ok(&["run", path, "--resume", o]);
    assert!(
        err.contains("window 79 (t = 0.8 s)") && err.contains("to end at t = 1.3 s"),
        "{err}"
    );

    std::fs::write(&case, &text).unwrap_or_else(|e| panic!("{e}"));
    let straight = dir.join("straight");
    coupler_ok(&[
        "run",
        path,
        "--out",
        straight.to_str().unwrap_or_default(),
        "--end-time",
        "1.3",
    ]);
    assert_same_outputs(&straight, &out);
}

/// What `--end-time` refuses, with exit code 2: an end time before the last checkpoint (naming its
/// time; resumed without `--end-time`, a case whose end_time is before it is told the end time the
/// run was going to), a time that is not a positive number, and a case without coupling.
#[test]
fn an_end_time_before_the_last_checkpoint_is_refused_naming_the_checkpoint_time() {
    let dir = out_dir("resume-extend-refused");
    let case = case_from("oscillator", &dir, &[("end_time", "0.8")]);
    with_checkpoints(&case, "0.4");
    let path = case.to_str().unwrap_or_default();
    let out = dir.join("out");
    let o = out.to_str().unwrap_or_default();
    // to 1.3 s: the last checkpoint is at 1.2 s
    coupler_ok(&["run", path, "--out", o, "--end-time", "1.3"]);
    assert_eq!(manifest_windows(&out), vec![79, 119]);
    let refused = |args: &[&str], expected: &[&str]| {
        let done = coupler(args);
        let err = stderr(&done);
        println!("{err}");
        assert_eq!(done.status.code(), Some(2), "{err}");
        for e in expected {
            assert!(err.contains(e), "`{e}` in: {err}");
        }
    };
    refused(
        &["run", path, "--resume", o, "--end-time", "1.1"],
        &[
            "last checkpoint is at t = 1.2 s (window 119)",
            "--end-time 1.1 s is before it",
        ],
    );
    refused(
        &["run", path, "--resume", o],
        &[
            "last checkpoint is at t = 1.2 s",
            "the case's end_time 0.8 s is before it",
            "the run was going to t = 1.3 s: --end-time 1.3",
        ],
    );
    for bad in ["0", "-1", "nan", "inf", "soon"] {
        let arg = format!("--end-time={bad}");
        refused(&["run", path, "--resume", o, &arg], &["greater than 0"]);
    }
    let alone = dir.join("alone.toml");
    std::fs::write(
        &alone,
        "[case]\nname = \"alone\"\nend_time = 0.1\n\n[structure.s]\nmax_step = 0.01\n\n\
         [[structure.s.point_mass]]\nname = \"m\"\nmass = 1.0\nposition = [0, 0, 0]\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    refused(
        &[
            "run",
            alone.to_str().unwrap_or_default(),
            "--out",
            dir.join("alone").to_str().unwrap_or_default(),
            "--end-time",
            "0.2",
        ],
        &["--end-time 0.2", "no [coupling]"],
    );
    // nothing was changed by the refusals: the run still extends
    let err = coupler_ok(&["run", path, "--resume", o, "--end-time", "1.5"]);
    assert!(err.contains("window 119 (t = 1.2 s)"), "{err}");
}
