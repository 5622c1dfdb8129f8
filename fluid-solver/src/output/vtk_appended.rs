//! The VTK XML layout with raw appended data, shared by the particle (VTU) and surface (VTP)
//! writers: an XML header whose `DataArray`s point at offsets in the appended block, then each
//! array as `[u64 length][bytes]`. Files are written whole or not at all (`schemas::atomic_file`).

use schemas::participant::{ProgressSink, ReportingWriter};
use std::io::{self, Write};
use std::path::Path;

/// One data array: its VTK type, name, components per item, and its values, which are written
/// into the file a chunk at a time (a frame's arrays are never copied into byte buffers whole:
/// for the bridge case that was about 50 MB at each output).
pub struct Array<'a> {
    pub ty: &'static str,
    pub name: &'static str,
    pub components: usize,
    /// Bytes the values take.
    bytes: usize,
    write_values: ValueWriter<'a>,
}

/// An array's values go to the file in chunks of this many bytes (one write through the
/// writers' layers per chunk, not per value: a 4 M-particle frame in 0.6 s instead of 0.9–1.1 s
/// on the 2-core machine, whose disk then sets the pace).
const CHUNK_BYTES: usize = 64 * 1024;

/// Writes an array's values as little-endian bytes.
type ValueWriter<'a> = Box<dyn Fn(&mut dyn Write) -> io::Result<()> + 'a>;

impl<'a> Array<'a> {
    /// An array of the `count` values that `values()` yields, each written as the `N` bytes of
    /// `to_le` (e.g. `f64::to_le_bytes`), `components` values per item.
    pub fn new<T: 'a, I, const N: usize>(
        ty: &'static str,
        name: &'static str,
        components: usize,
        count: usize,
        values: impl Fn() -> I + 'a,
        to_le: fn(T) -> [u8; N],
    ) -> Array<'a>
    where
        I: Iterator<Item = T>,
    {
        Array {
            ty,
            name,
            components,
            bytes: count * N,
            write_values: Box::new(move |out| {
                let mut chunk = Vec::with_capacity(CHUNK_BYTES + N);
                for v in values() {
                    chunk.extend_from_slice(&to_le(v));
                    if chunk.len() >= CHUNK_BYTES {
                        out.write_all(&chunk)?;
                        chunk.clear();
                    }
                }
                out.write_all(&chunk)
            }),
        }
    }
}

/// A group of arrays under one XML element, e.g. `("PointData", "Scalars=\"pressure\"", …)`.
pub struct Section<'a> {
    pub element: &'static str,
    pub attributes: String,
    pub arrays: Vec<Array<'a>>,
}

/// Counts the bytes written through it.
struct Counting<W> {
    inner: W,
    written: usize,
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.written += n;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// Writes a `dataset` file (`UnstructuredGrid`, `PolyData`) with one piece, telling `progress`
/// of the bytes written.
pub fn write(
    path: &Path,
    dataset: &str,
    piece: &str,
    sections: &[Section],
    progress: &mut dyn ProgressSink,
) -> io::Result<()> {
    let mut xml = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{dataset}\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n<{dataset}>\n<Piece {piece}>\n"
    );
    let mut offset = 0usize;
    for s in sections {
        let space = if s.attributes.is_empty() { "" } else { " " };
        xml.push_str(&format!("<{}{space}{}>\n", s.element, s.attributes));
        for a in &s.arrays {
            xml.push_str(&format!(
                "<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{offset}\"/>\n",
                a.ty, a.name, a.components
            ));
            offset += 8 + a.bytes;
        }
        xml.push_str(&format!("</{}>\n", s.element));
    }
    xml.push_str(&format!(
        "</Piece>\n</{dataset}>\n<AppendedData encoding=\"raw\">\n_"
    ));

    schemas::atomic_file::write_with(path, |out| {
        let out = &mut ReportingWriter::new(out, progress);
        out.write_all(xml.as_bytes())?;
        for a in sections.iter().flat_map(|s| &s.arrays) {
            out.write_all(&(a.bytes as u64).to_le_bytes())?;
            let mut counting = Counting {
                inner: &mut *out,
                written: 0,
            };
            (a.write_values)(&mut counting)?;
            if counting.written != a.bytes {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidData,
                    format!(
                        "array `{}` wrote {} bytes, its header says {}",
                        a.name, counting.written, a.bytes
                    ),
                ));
            }
        }
        out.write_all(b"\n</AppendedData>\n</VTKFile>\n")
    })
}

/// Writes the index of a `dataset` written in pieces (`PUnstructuredGrid` for
/// `UnstructuredGrid`): each section's arrays declared as the pieces hold them (`Cells` are not
/// declared in an index), and one `Piece` per file of `pieces` (paths relative to the index).
pub fn write_index(path: &Path, dataset: &str, sections: &[Section], pieces: &[String]) -> io::Result<()> {
    let mut xml = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"P{dataset}\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n<P{dataset} GhostLevel=\"0\">\n"
    );
    for s in sections.iter().filter(|s| s.element != "Cells") {
        let space = if s.attributes.is_empty() { "" } else { " " };
        xml.push_str(&format!("<P{}{space}{}>\n", s.element, s.attributes));
        for a in &s.arrays {
            xml.push_str(&format!(
                "<PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                a.ty, a.name, a.components
            ));
        }
        xml.push_str(&format!("</P{}>\n", s.element));
    }
    for piece in pieces {
        xml.push_str(&format!("<Piece Source=\"{piece}\"/>\n"));
    }
    xml.push_str(&format!("</P{dataset}>\n</VTKFile>\n"));
    schemas::atomic_file::write_with(path, |out| out.write_all(xml.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn section(arrays: Vec<Array<'_>>) -> [Section<'_>; 1] {
        [Section {
            element: "PointData",
            attributes: String::new(),
            arrays,
        }]
    }

    #[test]
    fn arrays_are_written_with_their_length_after_the_header() {
        let dir = std::env::temp_dir().join(format!("vtk-appended-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join("ok.vtu");
        let values = [1.5f64, -2.0];
        let arrays = vec![Array::new(
            "Float64",
            "a",
            1,
            2,
            || values.iter().copied(),
            f64::to_le_bytes,
        )];
        write(
            &path,
            "UnstructuredGrid",
            "",
            &section(arrays),
            &mut schemas::participant::DiscardProgress,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let bytes = fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
        let marker = b"encoding=\"raw\">\n_";
        let data = bytes.windows(marker.len()).position(|w| w == marker).unwrap_or(0) + marker.len();
        assert_eq!(bytes[data..data + 8], 16u64.to_le_bytes());
        assert_eq!(bytes[data + 8..data + 16], 1.5f64.to_le_bytes());
        assert_eq!(bytes[data + 16..data + 24], (-2.0f64).to_le_bytes());
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_array_shorter_than_its_count_is_an_error_and_no_file_is_left() {
        let dir = std::env::temp_dir().join(format!("vtk-appended-short-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join("short.vtu");
        let arrays = vec![Array::new(
            "UInt8",
            "a",
            1,
            3,
            || [1u8, 2].into_iter(),
            u8::to_le_bytes,
        )];
        let err = write(
            &path,
            "UnstructuredGrid",
            "",
            &section(arrays),
            &mut schemas::participant::DiscardProgress,
        )
        .expect_err("2 values for 3");
        assert_eq!(err.kind(), io::ErrorKind::InvalidData);
        assert!(
            err.to_string()
                .contains("array `a` wrote 2 bytes, its header says 3"),
            "{err}"
        );
        assert!(!path.exists());
        assert!(
            !dir.join("short.vtu.tmp").exists(),
            "the temporary file is removed"
        );
        let _ = fs::remove_dir_all(&dir);
    }
}
