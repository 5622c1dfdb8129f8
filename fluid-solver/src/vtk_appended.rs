//! The VTK XML layout with raw appended data, shared by the particle (VTU) and surface (VTP)
//! writers: an XML header whose `DataArray`s point at offsets in the appended block, then each
//! array as `[u64 length][bytes]`. Files are written through a temporary file and renamed, so a
//! frame on disk is never half written.

use std::fs;
use std::io::{self, Write};
use std::path::Path;

/// One data array: its VTK type, name, components per item and little-endian bytes.
pub struct Array {
    pub ty: &'static str,
    pub name: &'static str,
    pub components: usize,
    pub bytes: Vec<u8>,
}

impl Array {
    /// An array of `components` values per item.
    pub fn new(ty: &'static str, name: &'static str, components: usize, bytes: Vec<u8>) -> Array {
        Array {
            ty,
            name,
            components,
            bytes,
        }
    }
}

/// A group of arrays under one XML element, e.g. `("PointData", "Scalars=\"pressure\"", …)`.
pub struct Section {
    pub element: &'static str,
    pub attributes: String,
    pub arrays: Vec<Array>,
}

/// Little-endian bytes of a slice of numbers.
pub fn le_bytes<T: Copy, const N: usize>(values: &[T], to_le: impl Fn(T) -> [u8; N]) -> Vec<u8> {
    values.iter().flat_map(|&v| to_le(v)).collect()
}

/// Writes a `dataset` file (`UnstructuredGrid`, `PolyData`) with one piece.
pub fn write(path: &Path, dataset: &str, piece: &str, sections: &[Section]) -> io::Result<()> {
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
            offset += 8 + a.bytes.len();
        }
        xml.push_str(&format!("</{}>\n", s.element));
    }
    xml.push_str(&format!(
        "</Piece>\n</{dataset}>\n<AppendedData encoding=\"raw\">\n_"
    ));

    let tmp = path.with_extension("tmp");
    {
        let mut f = io::BufWriter::new(fs::File::create(&tmp)?);
        f.write_all(xml.as_bytes())?;
        for a in sections.iter().flat_map(|s| &s.arrays) {
            f.write_all(&(a.bytes.len() as u64).to_le_bytes())?;
            f.write_all(&a.bytes)?;
        }
        f.write_all(b"\n</AppendedData>\n</VTKFile>\n")?;
        f.flush()?;
    }
    fs::rename(&tmp, path)
}
