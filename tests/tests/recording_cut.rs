//! A recording ends with a record of how the run ended (issue #41): a recording cut to half its
//! size, without its last 3 bytes, or without its end record replays with a non-zero exit that
//! names the file, what was read and that the recording was cut; the intact one still passes, and
//! so does the recording of a run that died, which says who died and why.

use schemas::recording::{Message, Recording, RunEnd};
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

/// `coupler replay RECORDING --participant mass-right`: its exit code and everything it printed.
fn replay(recording: &Path) -> (Option<i32>, String) {
    let out = recording.with_extension("replay");
    let result = Command::new(binary("coupler"))
        .args(["replay", recording.to_str().unwrap_or_default()])
        .args([
            "--participant",
            "mass-right",
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!("{}{}", String::from_utf8_lossy(&result.stdout), stderr(&result));
    println!("{text}");
    (result.status.code(), text)
}

/// Byte offsets of the frames of a version-3 recording (header first): `[len][crc][payload]`.
fn frame_starts(bytes: &[u8]) -> Vec<usize> {
    let mut at = schemas::recording::MAGIC_V3.len();
    let mut starts = Vec::new();
    while at + 8 <= bytes.len() {
        starts.push(at);
        at += 8 + u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize;
    }
    starts
}

/// Answers of `mass-right` in the first `frames` frames of a recording.
fn answers(recording: &Recording, frames: usize) -> usize {
    recording.frames[..frames]
        .iter()
        .filter(|f| f.participant == "mass-right")
        .filter(|f| {
            matches!(
                f.message,
                Message::From(schemas::message::FromParticipant::Advanced { .. })
            )
        })
        .count()
}

#[test]
fn a_cut_recording_fails_the_replay_and_the_intact_one_passes() {
    let dir = out_dir("recording-cut");
    let rec = record(&dir);
    let whole = Recording::read(&rec).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(whole.version, 3);
    assert!(
        matches!(whole.run_end(), RunEnd::Finished { windows: 50, time } if (time - 1.0).abs() < 1e-12),
        "{:?}",
        whole.run_end()
    );
    assert!(matches!(
        whole.frames.last().map(|f| &f.message),
        Some(Message::End { windows: 50, .. })
    ));

    let (code, text) = replay(&rec);
    assert_eq!(code, Some(0), "the intact recording passes: {text}");
    assert!(text.contains("PASS"), "{text}");
    assert!(!text.contains("cut"), "{text}");

    let bytes = std::fs::read(&rec).unwrap_or_default();
    let starts = frame_starts(&bytes);
    let last = *starts.last().unwrap_or(&0);
    let cuts = [
        ("half", bytes.len() / 2),
        ("minus-3-bytes", bytes.len() - 3),
        ("no-end-record", last),
    ];
    for (what, len) in cuts {
        let cut = dir.join(format!("{what}.rec"));
        std::fs::write(&cut, &bytes[..len]).unwrap_or_default();
        let read = Recording::read(&cut).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(read.run_end(), RunEnd::Cut, "{what}");
        let frames = read.frames.len();
        let held = answers(&whole, frames);
        assert!(held > 0, "{what}: the cut keeps some answers");

        let (code, text) = replay(&cut);
        assert_eq!(code, Some(1), "{what}: a cut recording must not pass: {text}");
        assert!(!text.contains("PASS"), "{what}: {text}");
        assert!(
            text.contains(&format!(
                "{}: the recording was cut: it has no end record",
                cut.display()
            )),
            "{what}: names the file and says it was cut: {text}"
        );
        assert!(
            text.contains(&format!(
                "read {frames} complete frames holding {held} answers of `mass-right`"
            )),
            "{what}: says what was read: {text}"
        );
        assert!(
            text.contains(&format!("compared {held} of the recording's {held} answers")),
            "{what}: replays what it holds: {text}"
        );
    }
}

#[test]
fn the_recording_of_a_run_that_died_names_who_and_why_and_replays() {
    let dir = out_dir("recording-died");
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
    assert_eq!(run.status.code(), Some(1), "the run must fail: {}", stderr(&run));
    let rec = out.join("recording.rec");
    let read = Recording::read(&rec).unwrap_or_else(|e| panic!("{e}"));
    match read.run_end() {
        RunEnd::Died {
            window,
            participant,
            reason,
        } => {
            assert_eq!(window, Some(12));
            assert_eq!(participant.as_deref(), Some("mass-right"));
            assert!(reason.contains("exit code 3"), "{reason}");
        }
        other => panic!("expected the recorded death, got {other:?}"),
    }
    let (code, text) = replay(&rec);
    assert_eq!(code, Some(0), "{text}");
    assert!(text.contains("PASS"), "{text}");
    assert!(text.contains("the run died in window 12"), "{text}");
    assert!(!text.contains("was cut"), "{text}");
}
