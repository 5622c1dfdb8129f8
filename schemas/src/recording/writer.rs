//! [`Recorder`]: appends checksummed frames (format version 3) to a recording file, and its end
//! record when the run ends.

use super::{Frame, Message, RecordingHeader, MAGIC_V1, MAGIC_V2, MAGIC_V3};
use crate::link::bincode_config;
use bincode::Encode;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Appends frames to a recording file, each flushed as it is written. [`Recorder::end`] and
/// [`Recorder::died`] write the end record and close the recording; a recorder dropped without
/// either leaves a recording that reads as cut.
pub struct Recorder {
    out: BufWriter<File>,
    path: PathBuf,
    scratch: Vec<u8>,
}

impl Recorder {
    /// Creates the file and writes its header.
    pub fn create(path: &Path, header: &RecordingHeader) -> io::Result<Recorder> {
        let mut out = BufWriter::new(File::create(path)?);
        out.write_all(MAGIC_V3)?;
        let mut rec = Recorder {
            out,
            path: path.to_path_buf(),
            scratch: Vec::new(),
        };
        rec.write_frame(header)?;
        Ok(rec)
    }

    /// Continues a recording (a resumed run, cut back to a frame boundary at its checkpoint). Only
    /// a version-3 recording is continued: an older one would end up with frames of two formats.
    pub fn append(path: &Path) -> io::Result<Recorder> {
        let mut magic = vec![0; MAGIC_V3.len()];
        std::io::Read::read_exact(&mut File::open(path)?, &mut magic)?;
        if magic != MAGIC_V3 {
            let what = if magic == MAGIC_V2 || magic == MAGIC_V1 {
                format!(
                    "it is a version-{} recording, made by an older build; this build continues only \
                     version-3 recordings: resume the run with the build that started it, or start it again",
                    if magic == MAGIC_V2 { 2 } else { 1 }
                )
            } else {
                "it is not a version-3 recording (wrong magic line)".to_string()
            };
            return Err(io::Error::other(what));
        }
        let mut file = crate::checkpoint::append(path)?;
        file.flush()?;
        Ok(Recorder {
            out: BufWriter::new(file),
            path: path.to_path_buf(),
            scratch: Vec::new(),
        })
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

    /// Ends the recording of a run that finished: its end record ([`Message::End`]) after
    /// `windows` windows, at simulated time `time` [s].
    pub fn end(mut self, wall_time: f64, windows: u64, time: f64) -> io::Result<()> {
        self.record("", wall_time, Message::End { windows, time })
    }

    /// Ends the recording of a run the coupler stopped on a failure: its end record
    /// ([`Message::Died`]) with the window, the participant that died (`None`: the coupler stopped
    /// the run itself) and why.
    pub fn died(
        mut self,
        wall_time: f64,
        window: Option<u64>,
        participant: Option<String>,
        reason: String,
    ) -> io::Result<()> {
        let message = Message::Died {
            window,
            participant,
            reason,
        };
        self.record("", wall_time, message)
    }

    /// `[length][CRC-32C][payload]`, written to the file in one flush.
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
        self.out.write_all(&crc32c::crc32c(&self.scratch).to_le_bytes())?;
        self.out.write_all(&self.scratch)?;
        self.out.flush()
    }
}
