//! Record and replay: a recorded run replayed against each participant passes; a participant
//! that departs from a known window on, or a changed parameter, fails the replay at that window.

use stack_tests::{binary, coupler_run, oscillator_case, out_dir, stderr};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Records the implicit oscillator at window 0.02 (50 windows); returns the recording.
fn record(dir: &Path) -> PathBuf {
    let case = oscillator_case(dir, &[("window", "0.02")]);
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(run.status.success(), "{}", stderr(&run));
    out.join("recording.rec")
}

fn replay(recording: &Path, participant: &str, extra: &[String], env: &[(&str, &str)]) -> (bool, String) {
    let out = recording.with_file_name(format!("replay-{participant}-{}", extra.len() + env.len()));
    let result = Command::new(binary("coupler"))
        .args([
            "replay",
            recording.to_str().unwrap_or_default(),
            "--participant",
            participant,
        ])
        .args(["--out", out.to_str().unwrap_or_default()])
        .args(extra)
        .envs(env.iter().copied())
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!("{}{}", String::from_utf8_lossy(&result.stdout), stderr(&result));
    println!("{text}");
    (result.status.success(), text)
}

#[test]
fn replay_of_each_participant_against_its_recording_passes() {
    let dir = out_dir("replay-pass");
    let rec = record(&dir);
    for participant in ["mass-left", "mass-right"] {
        let (ok, text) = replay(&rec, participant, &[], &[]);
        assert!(ok, "{participant}: {text}");
        assert!(text.contains("PASS"), "{text}");
        assert!(
            text.contains("point_displacement"),
            "the table lists the compared fields: {text}"
        );
    }
}

#[test]
fn a_participant_perturbed_from_window_7_fails_the_replay_at_window_7() {
    let dir = out_dir("replay-perturbed");
    let rec = record(&dir);
    let faulty = binary("faulty-participant");
    let (ok, text) = replay(
        &rec,
        "mass-right",
        &[format!("--exe={}", faulty.display())],
        &[("FAULTY_PERTURB_FROM_WINDOW", "7")],
    );
    assert!(!ok, "a perturbed participant must fail: {text}");
    assert!(text.contains("DEPARTS in window 7"), "{text}");
    assert!(text.contains("participant `mass-right` in window 7"), "{text}");
}

#[test]
fn a_changed_parameter_fails_the_replay_in_the_first_window() {
    let dir = out_dir("replay-changed");
    let rec = record(&dir);
    let changed_dir = dir.join("changed");
    std::fs::create_dir_all(&changed_dir).unwrap_or_default();
    let changed = changed_dir.join("case.toml");
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap_or_default();
    // m2 = 1.001 kg instead of 1 kg: the answers differ from the first window on.
    let text = text.replacen("name = \"m2\"\nmass = 1.0", "name = \"m2\"\nmass = 1.001", 1);
    std::fs::write(&changed, text).unwrap_or_default();
    let (ok, out) = replay(
        &rec,
        "mass-right",
        &[format!("--case={}", changed.display())],
        &[],
    );
    assert!(!ok, "{out}");
    assert!(out.contains("DEPARTS in window 0"), "{out}");
}
