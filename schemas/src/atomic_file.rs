//! Output files written whole or not at all: the contents go to `NAME.tmp` beside the target, which
//! is then renamed over it (a rename within a folder is atomic), so a reader or a killed run never
//! sees a half-written file. A write that fails removes its temporary file.

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes `contents` to `path` atomically.
pub fn write(path: &Path, contents: impl AsRef<[u8]>) -> io::Result<()> {
    write_with(path, |out| out.write_all(contents.as_ref()))
}

/// Writes to `path` atomically what `fill` writes into the (buffered) temporary file.
pub fn write_with(path: &Path, fill: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> io::Result<()> {
    let tmp = temporary(path);
    let written = File::create(&tmp).and_then(|file| {
        let mut out = BufWriter::new(file);
        fill(&mut out)?;
        out.flush()
    });
    match written {
        Ok(()) => fs::rename(&tmp, path),
        Err(e) => {
            // the write's error is the one to report; a leftover temporary file is only clutter
            let _ = fs::remove_file(&tmp);
            Err(e)
        }
    }
}

/// `path` with `.tmp` added to its name.
fn temporary(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    path.with_file_name(name)
}
