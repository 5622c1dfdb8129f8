//! Checkpoint files: a participant's or the coupler's full state, written whole or not at all and
//! read back with a check that it is whole.
//!
//! Layout: the magic line `TSUNAMI-CKPT v1\n`, then `[u64 LE length][u32 LE CRC-32C of the
//! payload][payload]`, the payload being the state encoded by serde into bincode 2 (`standard()`,
//! little endian, variable-length integers). The file is written to `NAME.tmp`, synced to disk,
//! renamed over `NAME` and the folder synced, so a run killed at any moment leaves either the
//! previous file or the new one, never a part of one.
//!
//! A checkpoint of window `w` is complete when the coupler's manifest `coupler-<w>.bin` exists: the
//! coupler writes it last, after every participant said its own file is written.

use crate::participant::{ProgressSink, ReportingWriter};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// First bytes of every checkpoint file.
pub const MAGIC: &[u8] = b"TSUNAMI-CKPT v1\n";

/// The folder, inside a run's output folder, that holds its checkpoints.
pub const FOLDER: &str = "checkpoint";

/// The file of participant (or `coupler`) `name`'s state at the end of window `window`.
pub fn file(out: &Path, name: &str, window: u64) -> PathBuf {
    out.join(FOLDER).join(format!("{name}-{window:09}.bin"))
}

fn config() -> bincode::config::Configuration {
    bincode::config::standard()
}

/// Bytes handed to the file at a time, so that a long write reports its progress as it goes.
const WRITE_CHUNK: usize = 8 << 20;

/// Encodes `state` and writes it to `path` atomically and durably, telling `progress` of the
/// bytes written.
pub fn write<T: Serialize>(path: &Path, state: &T, progress: &mut dyn ProgressSink) -> io::Result<u64> {
    let payload = bincode::serde::encode_to_vec(state, config()).map_err(io::Error::other)?;
    let mut bytes = Vec::with_capacity(MAGIC.len() + 12 + payload.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&crc32c::crc32c(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    write_durably(path, &bytes, progress)?;
    Ok(bytes.len() as u64)
}

/// Reads a state written by [`write`]; a file that is cut, damaged or of another layout is an
/// error saying which.
pub fn read<T: DeserializeOwned>(path: &Path) -> Result<T, String> {
    let bytes = fs::read(path).map_err(|e| format!("cannot read the checkpoint {}: {e}", path.display()))?;
    let bad = |what: &str| format!("the checkpoint {} is {what}", path.display());
    let rest = bytes
        .strip_prefix(MAGIC)
        .ok_or_else(|| bad("not a checkpoint file (wrong magic line)"))?;
    if rest.len() < 12 {
        return Err(bad("cut short"));
    }
    let len = u64::from_le_bytes(rest[..8].try_into().unwrap_or_default());
    let crc = u32::from_le_bytes(rest[8..12].try_into().unwrap_or_default());
    let payload = &rest[12..];
    if payload.len() as u64 != len {
        return Err(bad(&format!(
            "cut short or too long ({} bytes of payload, {len} expected)",
            payload.len()
        )));
    }
    if crc32c::crc32c(payload) != crc {
        return Err(bad("damaged (its checksum does not match)"));
    }
    let (state, used) = bincode::serde::decode_from_slice(payload, config())
        .map_err(|e| bad(&format!("not readable by this build ({e})")))?;
    if used != payload.len() {
        return Err(bad("not readable by this build (bytes left over)"));
    }
    Ok(state)
}

/// Writes `bytes` to `path.tmp` (in chunks, each reported to `progress`), syncs it, renames it
/// over `path` and syncs the folder.
pub fn write_durably(path: &Path, bytes: &[u8], progress: &mut dyn ProgressSink) -> io::Result<()> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    let tmp = path.with_file_name(name);
    let written = File::create(&tmp).and_then(|f| {
        let mut out = ReportingWriter::new(&f, progress);
        for chunk in bytes.chunks(WRITE_CHUNK) {
            out.write_all(chunk)?;
        }
        f.sync_all()
    });
    if let Err(e) = written {
        // the write's error is the one to report; the temporary file is only clutter
        let _ = fs::remove_file(&tmp);
        return Err(e);
    }
    fs::rename(&tmp, path)?;
    if let Some(dir) = path.parent() {
        File::open(dir)?.sync_all()?;
    }
    Ok(())
}

/// Opens an existing output file to append to it (a resumed run continues its files).
pub fn append(path: &Path) -> io::Result<File> {
    OpenOptions::new().append(true).open(path)
}
