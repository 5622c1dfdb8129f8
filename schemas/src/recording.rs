//! The recording of a run: every message the coupler sent and received, in order.
//!
//! Layout: the magic line `TSUNAMI-REC v1\n`, then frames of `[u32 little-endian length][bincode bytes]`.
//! The first frame is a [`RecordingHeader`]; every later frame is a [`Frame`]. Each frame is
//! flushed when written, so a run that dies leaves a readable recording (a cut last frame is
//! reported and ignored).

use crate::link::bincode_config;
use crate::message::{FromParticipant, ToParticipant};
use bincode::{Decode, Encode};
use std::fs::File;
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

const MAGIC: &[u8] = b"TSUNAMI-REC v1\n";

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
}

/// A message with the participant it went to or came from.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub struct Frame {
    pub participant: String,
    /// Wall-clock seconds since the run started.
    pub wall_time: f64,
    pub message: Message,
}

/// Appends frames to a recording file.
pub struct Recorder {
    out: BufWriter<File>,
    path: PathBuf,
    scratch: Vec<u8>,
}

impl Recorder {
    /// Creates the file and writes its header.
    pub fn create(path: &Path, header: &RecordingHeader) -> io::Result<Recorder> {
        let mut out = BufWriter::new(File::create(path)?);
        out.write_all(MAGIC)?;
        let mut rec = Recorder {
            out,
            path: path.to_path_buf(),
            scratch: Vec::new(),
        };
        rec.write_frame(header)?;
        Ok(rec)
    }

    /// The file being written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one message and flushes it to the file.
    pub fn record(&mut self, participant: &str, wall_time: f64, message: Message) -> io::Result<()> {
        self.write_frame(&Frame {
            participant: participant.to_string(),
            wall_time,
            message,
        })
    }

    fn write_frame<T: Encode>(&mut self, value: &T) -> io::Result<()> {
        self.scratch.clear();
        bincode::encode_into_std_write(value, &mut self.scratch, bincode_config())
            .map_err(io::Error::other)?;
        let len = u32::try_from(self.scratch.len()).map_err(|_| {
            io::Error::other(format!(
                "a message of {} bytes is too large to record",
                self.scratch.len()
            ))
        })?;
        self.out.write_all(&len.to_le_bytes())?;
        self.out.write_all(&self.scratch)?;
        self.out.flush()
    }
}

/// A recording read back from a file.
#[derive(Debug)]
pub struct Recording {
    pub header: RecordingHeader,
    pub frames: Vec<Frame>,
    /// Set when the file ends inside a frame (the run died while writing it).
    pub truncated: bool,
}

/// A recording that cannot be read.
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

impl Recording {
    /// Reads a whole recording.
    pub fn read(path: &Path) -> Result<Recording, RecordingError> {
        let fail = |message: String| RecordingError {
            path: path.to_path_buf(),
            message,
        };
        let file = File::open(path).map_err(|e| fail(format!("cannot open: {e}")))?;
        let mut input = BufReader::new(file);
        let mut magic = vec![0u8; MAGIC.len()];
        input
            .read_exact(&mut magic)
            .map_err(|_| fail("not a recording (file too short)".into()))?;
        if magic != MAGIC {
            return Err(fail("not a recording of this project (wrong magic line)".into()));
        }
        let header: RecordingHeader = match read_frame(&mut input).map_err(&fail)? {
            Some(h) => h,
            None => return Err(fail("the recording has no header".into())),
        };
        let mut frames = Vec::new();
        let mut truncated = false;
        loop {
            match read_frame::<Frame>(&mut input) {
                Ok(Some(frame)) => frames.push(frame),
                Ok(None) => break,
                Err(e) if e.starts_with("cut") => {
                    truncated = true;
                    break;
                }
                Err(e) => return Err(fail(format!("frame {}: {e}", frames.len() + 1))),
            }
        }
        Ok(Recording {
            header,
            frames,
            truncated,
        })
    }
}

/// Reads one frame; `Ok(None)` at a clean end of file, `Err("cut …")` inside a frame.
fn read_frame<T: Decode<()>>(input: &mut impl Read) -> Result<Option<T>, String> {
    let mut len = [0u8; 4];
    match input.read(&mut len[..1]) {
        Ok(0) => return Ok(None),
        Ok(_) => {}
        Err(e) => return Err(e.to_string()),
    }
    input
        .read_exact(&mut len[1..])
        .map_err(|_| "cut inside a frame length".to_string())?;
    let mut bytes = vec![0u8; u32::from_le_bytes(len) as usize];
    input
        .read_exact(&mut bytes)
        .map_err(|_| "cut inside a frame".to_string())?;
    let (value, _) =
        bincode::decode_from_slice(&bytes, bincode_config()).map_err(|e| format!("cannot decode: {e}"))?;
    Ok(Some(value))
}

#[cfg(test)]
mod tests {
    use super::*;
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
        Message::To(ToParticipant::Advance {
            header: h,
            checkpoint: Checkpoint::None,
            inputs,
        })
    }

    #[test]
    fn frames_come_back_in_order_and_a_cut_frame_is_reported() {
        let dir = std::env::temp_dir().join(format!("rec-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("run.rec");
        let mut rec = Recorder::create(&path, &header()).unwrap();
        for w in 0..3 {
            rec.record("a", w as f64, advance(w)).unwrap();
        }
        drop(rec);
        let back = Recording::read(&path).unwrap();
        assert_eq!(back.header, header());
        assert_eq!(back.frames.len(), 3);
        assert_eq!(back.frames[2].message, advance(2));
        assert!(!back.truncated);

        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() - 5]).unwrap();
        let cut = Recording::read(&path).unwrap();
        assert_eq!(cut.frames.len(), 2);
        assert!(cut.truncated);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
