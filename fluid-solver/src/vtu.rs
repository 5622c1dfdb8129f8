//! ParaView output: one VTU (XML unstructured grid, raw appended binary) per frame and a PVD
//! time series. Frames hold every particle except dummies: position, velocity, pressure, kind, id.

use crate::kind::DUMMY;
use crate::particles::Particles;
use crate::vtk_appended::{self, le_bytes, Array, Section};
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// Writes `p` to `path` as a VTU file (via a temporary file, so a frame is never half written).
pub fn write_vtu(path: &Path, p: &Particles) -> io::Result<()> {
    let keep: Vec<usize> = (0..p.len()).filter(|&i| p.kind[i] != DUMMY).collect();
    let n = keep.len();
    let points: Vec<f64> = keep.iter().flat_map(|&i| [p.x[i], p.y[i], p.z[i]]).collect();
    let velocity: Vec<f64> = keep.iter().flat_map(|&i| [p.vx[i], p.vy[i], p.vz[i]]).collect();
    let pressure: Vec<f64> = keep.iter().map(|&i| p.pressure[i]).collect();
    let kind: Vec<u8> = keep.iter().map(|&i| p.kind[i]).collect();
    let id: Vec<u32> = keep.iter().map(|&i| p.id[i]).collect();
    let connectivity: Vec<i64> = (0..n as i64).collect();
    let offsets: Vec<i64> = (1..=n as i64).collect();
    let sections = [
        Section {
            element: "PointData",
            attributes: "Scalars=\"pressure\" Vectors=\"velocity\"".into(),
            arrays: vec![
                Array::new("Float64", "velocity", 3, le_bytes(&velocity, f64::to_le_bytes)),
                Array::new("Float64", "pressure", 1, le_bytes(&pressure, f64::to_le_bytes)),
                Array::new("UInt8", "kind", 1, kind),
                Array::new("UInt32", "id", 1, le_bytes(&id, u32::to_le_bytes)),
            ],
        },
        Section {
            element: "Points",
            attributes: String::new(),
            arrays: vec![Array::new(
                "Float64",
                "position",
                3,
                le_bytes(&points, f64::to_le_bytes),
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
                    le_bytes(&connectivity, i64::to_le_bytes),
                ),
                Array::new("Int64", "offsets", 1, le_bytes(&offsets, i64::to_le_bytes)),
                Array::new("UInt8", "types", 1, vec![1u8; n]), // VTK_VERTEX
            ],
        },
    ];
    vtk_appended::write(
        path,
        "UnstructuredGrid",
        &format!("NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\""),
        &sections,
    )
}

/// A PVD time series, rewritten whole after each frame so that it always lists the frames on disk.
#[derive(Debug, Clone)]
pub struct TimeSeries {
    path: PathBuf,
    frames: Vec<(f64, String)>,
}

impl TimeSeries {
    /// A series written to `path`; frame files are named relative to its folder.
    pub fn new(path: PathBuf) -> TimeSeries {
        TimeSeries {
            path,
            frames: Vec::new(),
        }
    }

    /// Adds a frame file (relative to the PVD's folder) at `time` and rewrites the PVD.
    pub fn add(&mut self, time: f64, file: &str) -> io::Result<()> {
        self.frames.push((time, file.to_string()));
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n",
        );
        for (t, f) in &self.frames {
            s.push_str(&format!(
                "<DataSet timestep=\"{t}\" group=\"\" part=\"0\" file=\"{f}\"/>\n"
            ));
        }
        s.push_str("</Collection>\n</VTKFile>\n");
        let tmp = self.path.with_extension("pvd.tmp");
        fs::write(&tmp, s)?;
        fs::rename(&tmp, &self.path)
    }
}
