//! The recording of a run: every message the coupler sent and received, in order.
//!
//! Layout (version 2): the magic line `TSUNAMI-REC v2\n`, then frames of
//! `[u32 LE length][u32 LE CRC-32C of the payload][payload: bincode bytes]`. The first frame is a
//! [`RecordingHeader`]; every later frame is a [`Frame`]. Each frame is flushed when written, so a
//! run that dies leaves a readable recording: a cut last frame is reported and ignored, and a frame
//! whose checksum does not match is reported as corruption with its number and byte offset.
//! Version 1 (`TSUNAMI-REC v1\n`, frames without the checksum) is still read, without that check.

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
/// Magic line of version-2 recordings (a CRC-32C per frame).
pub const MAGIC_V2: &[u8] = b"TSUNAMI-REC v2\n";

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
    RunEnded {
        window: Option<u64>,
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

/// A recording read back from a file: its complete frames, and how it ends.
#[derive(Debug)]
pub struct Recording {
    /// Format version: 1 (no checksums) or 2.
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

#[cfg(test)]
mod tests;
