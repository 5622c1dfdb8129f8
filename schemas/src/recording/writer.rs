//! [`Recorder`]: appends checksummed frames (format version 2) to a recording file.

use super::{Frame, Message, RecordingHeader, MAGIC_V2};
use crate::link::bincode_config;
use bincode::Encode;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Appends frames to a recording file, each flushed as it is written.
pub struct Recorder {
    out: BufWriter<File>,
    path: PathBuf,
    scratch: Vec<u8>,
}

impl Recorder {
    /// Creates the file and writes its header.
    pub fn create(path: &Path, header: &RecordingHeader) -> io::Result<Recorder> {
        let mut out = BufWriter::new(File::create(path)?);
        out.write_all(MAGIC_V2)?;
        let mut rec = Recorder {
            out,
            path: path.to_path_buf(),
            scratch: Vec::new(),
        };
        rec.write_frame(header)?;
        Ok(rec)
    }

    /// Continues a recording (a resumed run, cut back to a frame boundary at its checkpoint).
    pub fn append(path: &Path) -> io::Result<Recorder> {
        let mut file = crate::checkpoint::append(path)?;
        let mut magic = vec![0; MAGIC_V2.len()];
        std::io::Read::read_exact(&mut File::open(path)?, &mut magic)?;
        if magic != MAGIC_V2 {
            return Err(io::Error::other("not a version-2 recording"));
        }
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
