//! Tests of `schemas::recording`.

use schemas::link::bincode_config;
use schemas::message::{Checkpoint, Fields, Header, Waveform};
use schemas::recording::*;

fn header() -> RecordingHeader {
    RecordingHeader {
        protocol: 1,
        case_hash: 42,
        case_path: "case.toml".into(),
        case_text: "[case]".into(),
        run_id: "r1".into(),
        participants: vec!["a".into(), "b".into()],
    }
}

fn advance(window: u64) -> Message {
    let h = Header {
        protocol: 1,
        window,
        iteration: 0,
        time: 0.1 * window as f64,
    };
    let inputs = Waveform::constant(vec![0.0, 0.1], &Fields::default());
    Message::To(schemas::message::ToParticipant::Advance {
        header: h,
        checkpoint: Checkpoint::None,
        inputs,
    })
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rec-test-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir.join("run.rec")
}

fn three_frames(path: &std::path::Path) -> Vec<u8> {
    let mut rec = Recorder::create(path, &header()).unwrap_or_else(|e| panic!("{e}"));
    for w in 0..3 {
        rec.record("a", w as f64, advance(w))
            .unwrap_or_else(|e| panic!("{e}"));
    }
    drop(rec);
    std::fs::read(path).unwrap_or_else(|e| panic!("{e}"))
}

/// Three frames and the end record of a run that finished after 3 windows at t = 0.3 s.
fn finished_run(path: &std::path::Path) -> Vec<u8> {
    let mut rec = Recorder::create(path, &header()).unwrap_or_else(|e| panic!("{e}"));
    for w in 0..3 {
        rec.record("a", w as f64, advance(w))
            .unwrap_or_else(|e| panic!("{e}"));
    }
    rec.end(3.5, 3, 0.3).unwrap_or_else(|e| panic!("{e}"));
    std::fs::read(path).unwrap_or_else(|e| panic!("{e}"))
}

/// Byte offsets of the frames (header first) of a version-2 or -3 recording.
fn frame_starts(bytes: &[u8]) -> Vec<usize> {
    let mut at = MAGIC_V3.len();
    let mut starts = Vec::new();
    while at + 8 <= bytes.len() {
        starts.push(at);
        at += 8 + u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize;
    }
    starts
}

#[test]
fn frames_come_back_in_order_and_a_cut_frame_is_reported() {
    let path = scratch("order");
    let bytes = three_frames(&path);
    let back = Recording::read(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.version, 3);
    assert_eq!(back.header, header());
    assert_eq!(back.frames.len(), 3);
    assert_eq!(back.frames[2].message, advance(2));
    assert_eq!(back.end, RecordingEnd::Whole);

    let cut = Recording::from_bytes(&bytes[..bytes.len() - 5]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(cut.frames.len(), 2);
    assert!(
        matches!(cut.end, RecordingEnd::Cut { frame: 3, .. }),
        "{:?}",
        cut.end
    );
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_flipped_bit_is_reported_as_corruption_with_its_frame_and_offset() {
    let path = scratch("flip");
    let mut bytes = three_frames(&path);
    let whole = Recording::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(whole.frames.len(), 3);
    // The second frame after the header starts after the magic, the header frame and frame 1.
    let frame_len = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let header_at = MAGIC_V2.len();
    let frame1_at = header_at + 8 + frame_len(header_at) as usize;
    let frame2_at = frame1_at + 8 + frame_len(frame1_at) as usize;
    bytes[frame2_at + 8 + 20] ^= 0x04;
    let damaged = Recording::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(damaged.frames.len(), 1, "frames before the damage are kept");
    match &damaged.end {
        RecordingEnd::Corrupt { frame, offset, what } => {
            assert_eq!(*frame, 2);
            assert_eq!(*offset, frame2_at as u64);
            assert!(what.contains("checksum mismatch"), "{what}");
        }
        other => panic!("expected corruption, got {other:?}"),
    }
    assert!(damaged
        .end
        .to_string()
        .contains(&format!("frame 2 (byte offset {frame2_at})")));
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_version_1_recording_is_still_read() {
    let mut bytes = MAGIC_V1.to_vec();
    let mut push = |payload: Vec<u8>| {
        bytes.extend_from_slice(&(payload.len() as u32).to_le_bytes());
        bytes.extend_from_slice(&payload);
    };
    push(bincode::encode_to_vec(header(), bincode_config()).unwrap_or_default());
    for w in 0..2 {
        let frame = Frame {
            participant: "b".into(),
            wall_time: 0.5,
            message: advance(w),
        };
        push(bincode::encode_to_vec(frame, bincode_config()).unwrap_or_default());
    }
    let back = Recording::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.version, 1);
    assert_eq!(back.frames.len(), 2);
    assert_eq!(back.frames[1].message, advance(1));
    assert_eq!(back.end, RecordingEnd::Whole);
}

#[test]
fn the_decode_limit_grows_with_the_frame_and_stops_at_the_link_maximum() {
    assert_eq!(decode_limit(0), 1 << 20);
    assert_eq!(decode_limit(16 << 10), 1 << 20);
    assert_eq!(decode_limit((16 << 10) + 1), 1 << 24);
    assert_eq!(decode_limit(usize::MAX), schemas::link::MAX_MESSAGE_BYTES);
}

#[test]
fn a_clean_end_reads_as_finished_with_its_windows_and_time() {
    let path = scratch("clean");
    let bytes = finished_run(&path);
    assert!(bytes.starts_with(MAGIC_V3));
    let back = Recording::read(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.version, VERSION);
    assert_eq!(back.end, RecordingEnd::Whole);
    assert_eq!(back.frames.len(), 4, "three messages and the end record");
    assert_eq!(
        back.frames[3].message,
        Message::End {
            windows: 3,
            time: 0.3
        }
    );
    assert_eq!(
        back.run_end(),
        RunEnd::Finished {
            windows: 3,
            time: 0.3
        }
    );
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_recording_cut_at_half_its_size_reads_as_cut() {
    let path = scratch("half");
    let bytes = finished_run(&path);
    let cut = Recording::from_bytes(&bytes[..bytes.len() / 2]).unwrap_or_else(|e| panic!("{e}"));
    assert!(cut.frames.len() < 4, "{} frames", cut.frames.len());
    assert_eq!(cut.run_end(), RunEnd::Cut);
    assert!(cut.run_end().to_string().contains("no end record"));
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_recording_without_its_last_3_bytes_reads_as_cut_inside_the_end_record() {
    let path = scratch("minus3");
    let bytes = finished_run(&path);
    let end_at = frame_starts(&bytes)[4];
    let cut = Recording::from_bytes(&bytes[..bytes.len() - 3]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        cut.frames.len(),
        3,
        "the three messages before the end record are kept"
    );
    assert_eq!(
        cut.end,
        RecordingEnd::Cut {
            frame: 4,
            offset: end_at as u64,
            overrun: Some((
                (bytes.len() - end_at - 8) as u64,
                (bytes.len() - end_at - 11) as u64
            ))
        }
    );
    assert_eq!(cut.run_end(), RunEnd::Cut);
    let _ = std::fs::remove_file(&path);
}

/// A file that ends at a frame boundary but without its end record — the writer was killed
/// between two frames, or the file was cut exactly there — is cut, not finished.
#[test]
fn a_recording_missing_its_end_record_reads_as_cut() {
    let path = scratch("no-end");
    let bytes = three_frames(&path);
    let back = Recording::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.end, RecordingEnd::Whole, "every byte was read");
    assert_eq!(back.frames.len(), 3);
    assert_eq!(back.run_end(), RunEnd::Cut);

    let ended = finished_run(&path);
    let before_end = frame_starts(&ended)[4];
    let cut = Recording::from_bytes(&ended[..before_end]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(cut.end, RecordingEnd::Whole);
    assert_eq!(cut.run_end(), RunEnd::Cut);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_run_the_coupler_stopped_ends_with_who_died_and_why() {
    let path = scratch("died");
    let mut rec = Recorder::create(&path, &header()).unwrap_or_else(|e| panic!("{e}"));
    rec.record("b", 0.1, advance(0)).unwrap_or_else(|e| panic!("{e}"));
    let reason = "participant `b` in window 0: exited with exit code 3".to_string();
    rec.died(0.2, Some(0), Some("b".into()), reason.clone())
        .unwrap_or_else(|e| panic!("{e}"));
    let back = Recording::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let stopped = back.run_end();
    assert_eq!(
        stopped,
        RunEnd::Died {
            window: Some(0),
            participant: Some("b".into()),
            reason: reason.clone()
        }
    );
    assert_eq!(stopped.to_string(), format!("the run died in window 0: {reason}"));
    let _ = std::fs::remove_file(&path);
}

/// Version 2 had no end record: a run counts as finished when every participant's last message
/// is `Finished`, as stopped when it holds a `RunEnded`, and as cut otherwise.
#[test]
fn a_version_2_recording_is_judged_by_its_last_messages() {
    let mut bytes = MAGIC_V2.to_vec();
    let mut push = |payload: Vec<u8>| {
        bytes.extend_from_slice(&(payload.len() as u32).to_le_bytes());
        bytes.extend_from_slice(&crc32c::crc32c(&payload).to_le_bytes());
        bytes.extend_from_slice(&payload);
    };
    push(bincode::encode_to_vec(header(), bincode_config()).unwrap_or_default());
    let finished = |participant: &str| Frame {
        participant: participant.into(),
        wall_time: 1.0,
        message: Message::From(schemas::message::FromParticipant::Finished),
    };
    for frame in [
        Frame {
            participant: "a".into(),
            wall_time: 0.5,
            message: advance(4),
        },
        finished("a"),
        finished("b"),
    ] {
        push(bincode::encode_to_vec(frame, bincode_config()).unwrap_or_default());
    }
    let whole = Recording::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(whole.version, 2);
    assert_eq!(
        whole.run_end(),
        RunEnd::Finished {
            windows: 5,
            time: 0.4
        }
    );
    let before_last = frame_starts(&bytes)[3];
    let cut = Recording::from_bytes(&bytes[..before_last]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(cut.end, RecordingEnd::Whole);
    assert_eq!(cut.run_end(), RunEnd::Cut, "`b` never said Finished");
}

#[test]
fn a_recording_of_a_newer_format_is_refused_by_its_version() {
    let mut bytes = b"TSUNAMI-REC v4\n".to_vec();
    bytes.extend_from_slice(&[0; 16]);
    let err = Recording::from_bytes(&bytes).err().unwrap_or_default();
    assert!(err.contains("`TSUNAMI-REC v4`"), "{err}");
    assert!(err.contains("newer build"), "{err}");
}

#[test]
fn only_a_version_3_recording_is_continued() {
    let path = scratch("append");
    let bytes = finished_run(&path);
    let body_at = frame_starts(&bytes)[4];
    std::fs::write(&path, &bytes[..body_at]).unwrap_or_else(|e| panic!("{e}"));
    let rec = Recorder::append(&path).unwrap_or_else(|e| panic!("{e}"));
    rec.end(3.5, 3, 0.3).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(std::fs::read(&path).unwrap_or_default(), bytes);

    let mut old = bytes.clone();
    old[..MAGIC_V2.len()].copy_from_slice(MAGIC_V2);
    std::fs::write(&path, &old).unwrap_or_else(|e| panic!("{e}"));
    let err = Recorder::append(&path)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("version-2 recording"), "{err}");
    assert_eq!(
        std::fs::read(&path).unwrap_or_default(),
        old,
        "a refused file is left as it was"
    );
    let _ = std::fs::remove_file(&path);
}
