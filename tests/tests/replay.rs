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

/// Byte offsets of the frames of a version-2 recording (header first): `[len][crc][payload]`.
fn frame_starts(bytes: &[u8]) -> Vec<usize> {
    let mut at = schemas::recording::MAGIC_V2.len();
    let mut starts = Vec::new();
    while at + 8 <= bytes.len() {
        starts.push(at);
        at += 8 + u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize;
    }
    starts
}

#[test]
fn a_recording_whose_second_frame_claims_2_pow_31_bytes_fails_with_a_count_instead_of_passing() {
    let dir = out_dir("replay-nothing");
    let rec = record(&dir);
    let mut bytes = std::fs::read(&rec).unwrap_or_default();
    let second = frame_starts(&bytes)[2];
    bytes[second..second + 4].copy_from_slice(&(1u32 << 31).to_le_bytes());
    let damaged = dir.join("claims-2-31.rec");
    std::fs::write(&damaged, bytes).unwrap_or_default();
    let (ok, text) = replay(&damaged, "mass-right", &[], &[]);
    assert!(!ok, "nothing compared must not pass: {text}");
    assert!(!text.contains("PASS"), "{text}");
    assert!(text.contains("no answer of `mass-right` to compare"), "{text}");
    assert!(text.contains("1 complete frames"), "{text}");
    assert!(
        text.contains("claims 2147483648 bytes but the file has"),
        "{text}"
    );
}

#[test]
fn a_flipped_bit_is_reported_as_corruption_not_as_a_departure() {
    let dir = out_dir("replay-flip");
    let rec = record(&dir);
    let mut bytes = std::fs::read(&rec).unwrap_or_default();
    let starts = frame_starts(&bytes);
    let k = starts.len() / 2;
    bytes[starts[k] + 8 + 30] ^= 0x10;
    let damaged = dir.join("flipped.rec");
    std::fs::write(&damaged, bytes).unwrap_or_default();
    let (ok, text) = replay(&damaged, "mass-right", &[], &[]);
    assert!(!ok, "{text}");
    assert!(
        text.contains(&format!("CORRUPT at frame {k} (byte offset {})", starts[k])),
        "{text}"
    );
    assert!(text.contains("checksum mismatch"), "{text}");
    assert!(!text.contains("DEPARTS") && !text.contains("PASS"), "{text}");
}

#[test]
fn a_version_1_recording_still_replays_with_a_note() {
    let dir = out_dir("replay-v1");
    let rec = record(&dir);
    let bytes = std::fs::read(&rec).unwrap_or_default();
    let mut v1 = schemas::recording::MAGIC_V1.to_vec();
    for start in frame_starts(&bytes) {
        let len =
            u32::from_le_bytes([bytes[start], bytes[start + 1], bytes[start + 2], bytes[start + 3]]) as usize;
        v1.extend_from_slice(&bytes[start..start + 4]);
        v1.extend_from_slice(&bytes[start + 8..start + 8 + len]);
    }
    let old = dir.join("v1.rec");
    std::fs::write(&old, v1).unwrap_or_default();
    let (ok, text) = replay(&old, "mass-left", &[], &[]);
    assert!(ok, "{text}");
    assert!(text.contains("version-1 recording"), "{text}");
    assert!(text.contains("PASS"), "{text}");
}

/// The recording `rec` with its header saying protocol version `protocol`, written to `dir/NAME`.
fn with_protocol(rec: &Path, protocol: u32, name: &str) -> PathBuf {
    let recording = schemas::recording::Recording::read(rec).unwrap_or_else(|e| panic!("{e}"));
    let mut header = recording.header.clone();
    header.protocol = protocol;
    let path = rec.with_file_name(name);
    let mut writer = schemas::recording::Recorder::create(&path, &header).unwrap_or_else(|e| panic!("{e}"));
    for frame in recording.frames {
        writer
            .record(&frame.participant, frame.wall_time, frame.message)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    drop(writer);
    path
}

/// A recording made by a build of another message protocol does not read back: the replay says
/// so from the header instead of calling the recording corrupt.
#[test]
fn a_recording_of_another_protocol_version_is_refused_by_name() {
    let dir = out_dir("replay-protocol");
    let rec = record(&dir);
    let older = schemas::message::OLDEST_REPLAYABLE_PROTOCOL - 1;
    let old = with_protocol(&rec, older, "older.rec");
    let (ok, text) = replay(&old, "mass-left", &[], &[]);
    assert!(!ok, "{text}");
    assert!(
        text.contains(&format!(
            "recorded with message protocol version {older}, this coupler speaks version {}",
            schemas::message::PROTOCOL_VERSION
        )),
        "{text}"
    );
    assert!(!text.contains("CORRUPT"), "{text}");
}

/// Protocol version 4 added only progress reports, which are never recorded: recordings of
/// version 3 hold the same messages and replay.
#[test]
fn a_recording_of_the_oldest_replayable_protocol_replays() {
    let dir = out_dir("replay-protocol-3");
    let rec = record(&dir);
    let old = with_protocol(&rec, schemas::message::OLDEST_REPLAYABLE_PROTOCOL, "v3.rec");
    let (ok, text) = replay(&old, "mass-left", &[], &[]);
    assert!(ok, "{text}");
    assert!(text.contains("PASS"), "{text}");
}

#[test]
fn a_recording_of_a_run_that_died_replays_everything_answered_and_says_where_it_ended() {
    let dir = out_dir("replay-died");
    let case = oscillator_case(&dir, &[("window", "0.02")]);
    let out = dir.join("out");
    let run = Command::new(binary("coupler"))
        .args(["run", case.to_str().unwrap_or_default(), "--out"])
        .arg(&out)
        .arg(format!(
            "--exe=mass-right={}",
            binary("faulty-participant").display()
        ))
        .env("FAULTY_EXIT_AT_WINDOW", "12")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!run.status.success(), "the run must fail: {}", stderr(&run));
    let rec = out.join("recording.rec");
    for participant in ["mass-right", "mass-left"] {
        let (ok, text) = replay(&rec, participant, &[], &[]);
        assert!(ok, "{participant}: {text}");
        assert!(text.contains("PASS"), "{text}");
        assert!(
            text.contains("the run died in window 12"),
            "{participant}: {text}"
        );
        assert!(text.contains("exit code 3"), "says why: {text}");
    }
}
