//! ParaView output: one VTU (XML unstructured grid, raw appended binary) per frame, listed in a PVD
//! time series (`schemas::pvd`). Frames hold every particle except dummies: position, velocity,
//! pressure, kind, id. A frame written in pieces (one per MPI rank) has a PVTU index naming them.

use crate::output::vtk_appended::{self, Array, Section};
use crate::particles::kind::DUMMY;
use crate::particles::Particles;
use schemas::participant::ProgressSink;
use std::io;
use std::path::Path;

/// Writes `p` to `path` as a VTU file (via a temporary file, so a frame is never half written),
/// telling `progress` of the bytes written.
pub fn write_vtu(path: &Path, p: &Particles, progress: &mut dyn ProgressSink) -> io::Result<()> {
    let keep: Vec<u32> = (0..p.len() as u32)
        .filter(|&i| p.kind[i as usize] != DUMMY)
        .collect();
    let n = keep.len();
    let arrays = sections(p, &keep);
    vtk_appended::write(
        path,
        "UnstructuredGrid",
        &format!("NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\""),
        &arrays,
        progress,
    )
}

/// Writes the PVTU index of a frame written in `pieces` (VTU files of [`write_vtu`], named
/// relative to `path`).
pub fn write_pvtu(path: &Path, pieces: &[String]) -> io::Result<()> {
    vtk_appended::write_index(
        path,
        "UnstructuredGrid",
        &sections(&Particles::default(), &[]),
        pieces,
    )
}

/// The arrays of a frame holding the particles `keep` of `p`.
fn sections<'a>(p: &'a Particles, keep: &'a [u32]) -> [Section<'a>; 3] {
    let n = keep.len();
    let kept = move || keep.iter().map(|&i| i as usize);
    [
        Section {
            element: "PointData",
            attributes: "Scalars=\"pressure\" Vectors=\"velocity\"".into(),
            arrays: vec![
                Array::new(
                    "Float64",
                    "velocity",
                    3,
                    3 * n,
                    move || kept().flat_map(|i| [p.vx[i], p.vy[i], p.vz[i]]),
                    f64::to_le_bytes,
                ),
                Array::new(
                    "Float64",
                    "pressure",
                    1,
                    n,
                    move || kept().map(|i| p.pressure[i]),
                    f64::to_le_bytes,
                ),
                Array::new(
                    "UInt8",
                    "kind",
                    1,
                    n,
                    move || kept().map(|i| p.kind[i]),
                    u8::to_le_bytes,
                ),
                Array::new(
                    "UInt32",
                    "id",
                    1,
                    n,
                    move || kept().map(|i| p.id[i]),
                    u32::to_le_bytes,
                ),
            ],
        },
        Section {
            element: "Points",
            attributes: String::new(),
            arrays: vec![Array::new(
                "Float64",
                "position",
                3,
                3 * n,
                move || kept().flat_map(|i| [p.x[i], p.y[i], p.z[i]]),
                f64::to_le_bytes,
            )],
        },
        Section {
            element: "Cells",
            attributes: String::new(),
            arrays: vec![
                Array::new(
                    "Int64",
                    "connectivity",
                    1,
                    n,
                    move || 0..n as i64,
                    i64::to_le_bytes,
                ),
                Array::new("Int64", "offsets", 1, n, move || 1..=n as i64, i64::to_le_bytes),
                Array::new(
                    "UInt8",
                    "types",
                    1,
                    n,
                    move || std::iter::repeat_n(1u8, n),
                    u8::to_le_bytes,
                ), // VTK_VERTEX
            ],
        },
    ]
}
