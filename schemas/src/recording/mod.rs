//! The recording of a run: every message the coupler sent and received, in order.
//!
//! Layout (version 3): the magic line `TSUNAMI-REC v3\n`, then frames of
//! `[u32 LE length][u32 LE CRC-32C of the payload][payload: bincode bytes]`. The first frame is a
//! [`RecordingHeader`]; every later frame is a [`Frame`]. Each frame is flushed when written, so a
//! run that dies leaves a readable recording: a cut last frame is reported and ignored, and a frame
//! whose checksum does not match is reported as corruption with its number and byte offset.
//!
//! The last frame of a version-3 recording says how the run ended: [`Message::End`] when it
//! finished, [`Message::Died`] (who and why) when the coupler stopped it on a failure. A recording
//! without either was cut — the coupler was killed while writing it, or the file was truncated —
//! even when it ends at a frame boundary; [`Recording::run_end`] tells the three apart.
//!
//! Older recordings are still read, because a user replays the recordings of earlier builds to
//! check a solver against them: version 2 (`TSUNAMI-REC v2\n`, the same frames, no end record)
//! and version 1 (`TSUNAMI-REC v1\n`, frames without the checksum). Having no end record, they
//! count as finished when every participant's last message is `Finished`, as stopped by the
//! coupler when they hold a [`Message::RunEnded`], and as cut otherwise; [`Recording::version`]
//! lets a reader say so. [`Recorder::append`] continues only version-3 recordings.

mod bounded_decode;
mod reader;
mod writer;

use crate::message::{FromParticipant, ToParticipant};
use bincode::{Decode, Encode};
use std::path::PathBuf;

pub use bounded_decode::decode_limit;
pub use writer::Recorder;

/// Magic line of version-1 recordings (no checksums).
pub const MAGIC_V1: &[u8] = b"TSUNAMI-REC v1\n";
/// Magic line of version-2 recordings (a CRC-32C per frame, no end record).
pub const MAGIC_V2: &[u8] = b"TSUNAMI-REC v2\n";
/// Magic line of version-3 recordings (a CRC-32C per frame, an end record), the version written.
pub const MAGIC_V3: &[u8] = b"TSUNAMI-REC v3\n";
/// The format version [`Recorder`] writes.
pub const VERSION: u32 = 3;

/// What a recording is of.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub struct RecordingHeader {
    pub protocol: u32,
    pub case_hash: u64,
    /// The case file as given to `coupler run`.
    pub case_path: String,
    /// The case text, so a replay needs nothing but the recording.
    pub case_text: String,
    pub run_id: String,
    /// Participants in serial order.
    pub participants: Vec<String>,
}

/// One recorded message.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub enum Message {
    To(ToParticipant),
    From(FromParticipant),
    /// The coupler stopped the run before its end (a participant died, hung or failed, Ctrl-C, …):
    /// the window it was in and why, as the coupler told the user. Its frame's participant is empty.
    /// Written by version-2 recordings; version 3 writes [`Message::Died`] instead, and still reads
    /// this as the same.
    RunEnded {
        window: Option<u64>,
        reason: String,
    },
    /// The run finished: `windows` coupling windows, to simulated time `time` [s]. The last frame
    /// of a version-3 recording of a run that ended cleanly; its frame's participant is empty.
    End {
        windows: u64,
        time: f64,
    },
    /// The coupler stopped the run on a failure: the window it was in (`None`: before the first or
    /// after the last, as `reason` says), the participant that died, hung or failed (`None` when
    /// the coupler stopped it itself: Ctrl-C, no convergence, instability, output it could not
    /// write) and why, as the coupler told the user. The last frame of a version-3 recording of a
    /// run that failed; its frame's participant is empty.
    Died {
        window: Option<u64>,
        participant: Option<String>,
        reason: String,
    },
}

/// A message with the participant it went to or came from.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub struct Frame {
    pub participant: String,
    /// Wall-clock seconds since the run started.
    pub wall_time: f64,
    pub message: Message,
}

/// How the readable part of a recording ends.
#[derive(Debug, Clone, PartialEq)]
pub enum RecordingEnd {
    /// At a frame boundary: every byte of the file was read.
    Whole,
    /// Inside frame `frame` (the header is frame 0), which starts at byte `offset`: the file
    /// was cut there (the run died while writing it, or the file was truncated) — or, when the
    /// frame claims more bytes than the file has left (`overrun`: claimed, left), its length
    /// field is damaged; the two cannot be told apart.
    Cut {
        frame: usize,
        offset: u64,
        overrun: Option<(u64, u64)>,
    },
    /// Frame `frame`, at byte `offset`, is damaged; nothing from it on was read.
    Corrupt { frame: usize, offset: u64, what: String },
}

impl std::fmt::Display for RecordingEnd {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RecordingEnd::Whole => write!(f, "the file ends at a frame boundary"),
            RecordingEnd::Cut {
                frame,
                offset,
                overrun: None,
            } => write!(
                f,
                "the file ends inside frame {frame} (byte offset {offset}): the run died while writing it, or the \
                 file was cut"
            ),
            RecordingEnd::Cut {
                frame,
                offset,
                overrun: Some((claimed, left)),
            } => write!(
                f,
                "frame {frame} (byte offset {offset}) claims {claimed} bytes but the file has {left} left: the run \
                 died while writing it, the file was cut, or the frame's length field is damaged"
            ),
            RecordingEnd::Corrupt { frame, offset, what } => {
                write!(f, "CORRUPT at frame {frame} (byte offset {offset}): {what}")
            }
        }
    }
}

/// How the run of a recording ended, as far as the recording tells ([`Recording::run_end`]).
#[derive(Debug, Clone, PartialEq)]
pub enum RunEnd {
    /// The run finished: `windows` windows, to simulated time `time` [s] (from the end record; for a
    /// version-1 or -2 recording, from its last `Advance`).
    Finished { windows: u64, time: f64 },
    /// The coupler stopped the run on a failure and recorded where, who and why
    /// ([`Message::Died`], or a version-2 [`Message::RunEnded`], which names no participant).
    Died {
        window: Option<u64>,
        participant: Option<String>,
        reason: String,
    },
    /// The recording has no end record: the coupler was killed while writing it, or the file was
    /// truncated. [`Recording::end`] says whether it also ends inside a frame.
    Cut,
    /// A damaged frame hides how the run ended ([`Recording::end`] says where).
    Corrupt,
}

impl std::fmt::Display for RunEnd {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunEnd::Finished { windows, time } => {
                write!(f, "the run finished: {windows} windows, to t = {time} s")
            }
            RunEnd::Died {
                window: Some(w),
                reason,
                ..
            } => write!(f, "the run died in window {w}: {reason}"),
            RunEnd::Died {
                window: None, reason, ..
            } => write!(f, "the run died: {reason}"),
            RunEnd::Cut => write!(
                f,
                "the recording was cut: it has no end record (the coupler was killed while writing it, or the \
                 file was truncated)"
            ),
            RunEnd::Corrupt => write!(f, "the recording is damaged before its end"),
        }
    }
}

/// A recording read back from a file: its complete frames, and how it ends.
#[derive(Debug)]
pub struct Recording {
    /// Format version: 1 (no checksums), 2 (no end record) or 3.
    pub version: u32,
    pub header: RecordingHeader,
    pub frames: Vec<Frame>,
    pub end: RecordingEnd,
}

/// A recording that cannot be read at all (no header).
#[derive(Debug)]
pub struct RecordingError {
    pub path: PathBuf,
    pub message: String,
}

impl std::fmt::Display for RecordingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for RecordingError {}
