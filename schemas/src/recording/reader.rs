//! Reading a recording back: every complete frame, checked (versions 2 and 3: its CRC-32C), how
//! the file ends — whole, cut inside a frame, or damaged at a frame with its byte offset — and how
//! the run ended ([`Recording::run_end`]). Nothing read from the file is trusted for an allocation:
//! a frame's bytes are allocated only when the file still holds them, and decoding is bounded by
//! [`super::bounded_decode`].

use super::bounded_decode::decode;
use super::{
    Frame, Message, Recording, RecordingEnd, RecordingError, RecordingHeader, RunEnd, MAGIC_V1, MAGIC_V2,
    MAGIC_V3,
};
use crate::link::MAX_MESSAGE_BYTES;
use crate::message::{FromParticipant, ToParticipant};
use bincode::Decode;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

/// One attempt to read a frame.
enum Next<T> {
    Frame(T),
    /// A clean end of file before the frame.
    End,
    /// The file ends inside the frame; with what the frame claims and what the file has left
    /// when its length field overruns the file.
    Cut(Option<(u64, u64)>),
    /// The frame is damaged.
    Corrupt(String),
}

/// A byte source that knows how many bytes it still holds.
struct Source<R> {
    input: R,
    offset: u64,
    total: u64,
}

impl<R: Read> Source<R> {
    /// Reads exactly `buf.len()` bytes; false when the file ends first.
    fn fill(&mut self, buf: &mut [u8]) -> bool {
        let ok = self.input.read_exact(buf).is_ok();
        self.offset += buf.len() as u64;
        ok
    }

    fn remaining(&self) -> u64 {
        self.total.saturating_sub(self.offset)
    }

    fn frame<T: Decode<()>>(&mut self, version: u32) -> Next<T> {
        let mut first = [0u8; 1];
        match self.input.read(&mut first) {
            Ok(0) => return Next::End,
            Ok(_) => self.offset += 1,
            Err(_) => return Next::Cut(None),
        }
        let mut rest = [0u8; 3];
        if !self.fill(&mut rest) {
            return Next::Cut(None);
        }
        let len = u32::from_le_bytes([first[0], rest[0], rest[1], rest[2]]) as u64;
        let mut stored = None;
        if version >= 2 {
            let mut crc = [0u8; 4];
            if !self.fill(&mut crc) {
                return Next::Cut(None);
            }
            stored = Some(u32::from_le_bytes(crc));
        }
        if len > MAX_MESSAGE_BYTES as u64 {
            return Next::Corrupt(format!(
                "its length field claims {len} bytes, more than any message ({MAX_MESSAGE_BYTES})"
            ));
        }
        if len > self.remaining() {
            return Next::Cut(Some((len, self.remaining())));
        }
        let mut bytes = vec![0u8; len as usize];
        if !self.fill(&mut bytes) {
            return Next::Cut(None);
        }
        if let Some(stored) = stored {
            let computed = crc32c::crc32c(&bytes);
            if computed != stored {
                return Next::Corrupt(format!(
                    "checksum mismatch (stored {stored:08x}, computed {computed:08x} over its {len} bytes)"
                ));
            }
        }
        match decode(&bytes) {
            Ok(v) => Next::Frame(v),
            Err(e) if version >= 2 => Next::Corrupt(format!("checksum matches but the message {e}")),
            Err(e) => Next::Corrupt(format!(
                "the message {e} (a version-1 recording has no checksums: this is damage or a cut)"
            )),
        }
    }
}

impl Recording {
    /// Reads a whole recording; an error only when not even its header can be read.
    pub fn read(path: &Path) -> Result<Recording, RecordingError> {
        let fail = |message: String| RecordingError {
            path: path.to_path_buf(),
            message,
        };
        let file = File::open(path).map_err(|e| fail(format!("cannot open: {e}")))?;
        let total = file
            .metadata()
            .map_err(|e| fail(format!("cannot open: {e}")))?
            .len();
        Recording::from_reader(BufReader::new(file), total).map_err(fail)
    }

    /// Reads a recording held in memory.
    pub fn from_bytes(bytes: &[u8]) -> Result<Recording, String> {
        Recording::from_reader(bytes, bytes.len() as u64)
    }

    fn from_reader(input: impl Read, total: u64) -> Result<Recording, String> {
        let mut src = Source {
            input,
            offset: 0,
            total,
        };
        let mut magic = [0u8; MAGIC_V2.len()];
        if !src.fill(&mut magic) {
            return Err("not a recording (file too short)".into());
        }
        let version = match &magic[..] {
            m if m == MAGIC_V3 => 3,
            m if m == MAGIC_V2 => 2,
            m if m == MAGIC_V1 => 1,
            m if m.starts_with(b"TSUNAMI-REC v") => {
                return Err(format!(
                "a recording of format `{}`, which this build does not read (it reads versions 1 to 3): it \
                     was made by a newer build; replay it with that build",
                String::from_utf8_lossy(m.strip_suffix(b"\n").unwrap_or(m))
            ))
            }
            _ => return Err("not a recording of this project (wrong magic line)".into()),
        };
        let header: RecordingHeader = match src.frame(version) {
            Next::Frame(h) => h,
            Next::End => return Err("the recording has no header".into()),
            Next::Cut(_) => return Err("the file ends inside the header".into()),
            Next::Corrupt(what) => return Err(format!("the header is damaged: {what}")),
        };
        let mut frames = Vec::new();
        let end = loop {
            let offset = src.offset;
            let frame = frames.len() + 1;
            match src.frame::<Frame>(version) {
                Next::Frame(f) => frames.push(f),
                Next::End => break RecordingEnd::Whole,
                Next::Cut(overrun) => {
                    break RecordingEnd::Cut {
                        frame,
                        offset,
                        overrun,
                    }
                }
                Next::Corrupt(what) => break RecordingEnd::Corrupt { frame, offset, what },
            }
        };
        Ok(Recording {
            version,
            header,
            frames,
            end,
        })
    }
}

/// The run end an end record states, if `message` is one that says the run died.
fn died(message: &Message) -> Option<RunEnd> {
    match message {
        Message::Died {
            window,
            participant,
            reason,
        } => Some(RunEnd::Died {
            window: *window,
            participant: participant.clone(),
            reason: reason.clone(),
        }),
        Message::RunEnded { window, reason } => Some(RunEnd::Died {
            window: *window,
            participant: None,
            reason: reason.clone(),
        }),
        _ => None,
    }
}

impl Recording {
    /// How the recorded run ended. A file that ends inside a frame is [`RunEnd::Cut`], one with a
    /// damaged frame [`RunEnd::Corrupt`]. Otherwise, in version 3, the last frame says: an
    /// [`Message::End`] is [`RunEnd::Finished`], a [`Message::Died`] (or [`Message::RunEnded`]) is
    /// [`RunEnd::Died`], anything else — no end record — is [`RunEnd::Cut`]. Versions 1 and 2 have
    /// no end record: a `RunEnded` frame makes them [`RunEnd::Died`]; every participant's last
    /// message being `Finished` makes them [`RunEnd::Finished`] (windows and time from the last
    /// `Advance`); anything else is [`RunEnd::Cut`].
    pub fn run_end(&self) -> RunEnd {
        match self.end {
            RecordingEnd::Corrupt { .. } => return RunEnd::Corrupt,
            RecordingEnd::Cut { .. } => return RunEnd::Cut,
            RecordingEnd::Whole => {}
        }
        if self.version >= 3 {
            return match self.frames.last().map(|f| &f.message) {
                Some(Message::End { windows, time }) => RunEnd::Finished {
                    windows: *windows,
                    time: *time,
                },
                Some(other) => died(other).unwrap_or(RunEnd::Cut),
                None => RunEnd::Cut,
            };
        }
        if let Some(stopped) = self.frames.iter().rev().find_map(|f| died(&f.message)) {
            return stopped;
        }
        let participants = &self.header.participants;
        let finished = !participants.is_empty()
            && participants.iter().all(|p| {
                self.frames
                    .iter()
                    .rev()
                    .find(|f| &f.participant == p)
                    .is_some_and(|f| matches!(f.message, Message::From(FromParticipant::Finished)))
            });
        if !finished {
            return RunEnd::Cut;
        }
        let last = self.frames.iter().rev().find_map(|f| match &f.message {
            Message::To(ToParticipant::Advance { header, .. }) => Some((header.window + 1, header.time)),
            _ => None,
        });
        let (windows, time) = last.unwrap_or((0, 0.0));
        RunEnd::Finished { windows, time }
    }
}
