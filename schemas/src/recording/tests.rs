use super::*;
use crate::link::bincode_config;
use crate::message::{Checkpoint, Fields, Header, Waveform};

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
    Message::To(crate::message::ToParticipant::Advance {
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

#[test]
fn frames_come_back_in_order_and_a_cut_frame_is_reported() {
    let path = scratch("order");
    let bytes = three_frames(&path);
    let back = Recording::read(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.version, 2);
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
    assert_eq!(decode_limit(usize::MAX), crate::link::MAX_MESSAGE_BYTES);
}
