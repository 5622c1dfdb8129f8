//! ParaView output: one VTU (XML unstructured grid, raw appended binary) per frame and a PVD
//! time series. Frames hold every particle except dummies: position, velocity, pressure, kind, id.

use crate::kind::DUMMY;
use crate::particles::Particles;
use std::fs;
use std::io::{self, Write};
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
    let types = vec![1u8; n]; // VTK_VERTEX

    let blocks: Vec<Vec<u8>> = vec![
        velocity.iter().flat_map(|v| v.to_le_bytes()).collect(),
        pressure.iter().flat_map(|v| v.to_le_bytes()).collect(),
        kind,
        id.iter().flat_map(|v| v.to_le_bytes()).collect(),
        points.iter().flat_map(|v| v.to_le_bytes()).collect(),
        connectivity.iter().flat_map(|v| v.to_le_bytes()).collect(),
        offsets.iter().flat_map(|v| v.to_le_bytes()).collect(),
        types,
    ];
    let mut offs = Vec::with_capacity(blocks.len());
    let mut at = 0usize;
    for b in &blocks {
        offs.push(at);
        at += 8 + b.len();
    }
    let mut xml = String::new();
    xml.push_str("<?xml version=\"1.0\"?>\n");
    xml.push_str("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
    xml.push_str(&format!(
        "<UnstructuredGrid>\n<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">\n"
    ));
    xml.push_str("<PointData Scalars=\"pressure\" Vectors=\"velocity\">\n");
    let da = |ty: &str, name: &str, comps: usize, off: usize| {
        format!(
            "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{off}\"/>\n"
        )
    };
    xml.push_str(&da("Float64", "velocity", 3, offs[0]));
    xml.push_str(&da("Float64", "pressure", 1, offs[1]));
    xml.push_str(&da("UInt8", "kind", 1, offs[2]));
    xml.push_str(&da("UInt32", "id", 1, offs[3]));
    xml.push_str("</PointData>\n<Points>\n");
    xml.push_str(&da("Float64", "position", 3, offs[4]));
    xml.push_str("</Points>\n<Cells>\n");
    xml.push_str(&da("Int64", "connectivity", 1, offs[5]));
    xml.push_str(&da("Int64", "offsets", 1, offs[6]));
    xml.push_str(&da("UInt8", "types", 1, offs[7]));
    xml.push_str("</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");

    let tmp = path.with_extension("vtu.tmp");
    {
        let mut f = io::BufWriter::new(fs::File::create(&tmp)?);
        f.write_all(xml.as_bytes())?;
        for b in &blocks {
            f.write_all(&(b.len() as u64).to_le_bytes())?;
            f.write_all(b)?;
        }
        f.write_all(b"\n</AppendedData>\n</VTKFile>\n")?;
        f.flush()?;
    }
    fs::rename(&tmp, path)
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
