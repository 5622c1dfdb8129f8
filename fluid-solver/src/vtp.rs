//! ParaView output of free-surface meshes: one VTP (XML PolyData, raw appended binary) per frame
//! and a PVD series `NAME_surface.pvd` beside the particle series `NAME.pvd`.

use crate::particles::Particles;
use crate::surface_mesh::{fluid_surface, TriangleMesh};
use crate::vtu::TimeSeries;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Writes `mesh` to `path` as a VTP file (via a temporary file, so a frame is never half written):
/// points, per-point `normals`, and the triangles as polys.
pub fn write_vtp(path: &Path, mesh: &TriangleMesh) -> io::Result<()> {
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let connectivity: Vec<i64> = mesh.triangles.iter().flatten().map(|&v| i64::from(v)).collect();
    let offsets: Vec<i64> = (1..=m as i64).map(|t| 3 * t).collect();
    let blocks: Vec<Vec<u8>> = vec![
        mesh.normals
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect(),
        mesh.vertices
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect(),
        connectivity.iter().flat_map(|v| v.to_le_bytes()).collect(),
        offsets.iter().flat_map(|v| v.to_le_bytes()).collect(),
    ];
    let mut offs = Vec::with_capacity(blocks.len());
    let mut at = 0usize;
    for b in &blocks {
        offs.push(at);
        at += 8 + b.len();
    }
    let da = |ty: &str, name: &str, comps: usize, off: usize| {
        format!(
            "<DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\" format=\"appended\" offset=\"{off}\"/>\n"
        )
    };
    let mut xml = String::new();
    xml.push_str("<?xml version=\"1.0\"?>\n");
    xml.push_str(
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    xml.push_str(&format!(
        "<PolyData>\n<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"{m}\">\n"
    ));
    xml.push_str("<PointData Normals=\"normals\">\n");
    xml.push_str(&da("Float32", "normals", 3, offs[0]));
    xml.push_str("</PointData>\n<Points>\n");
    xml.push_str(&da("Float64", "position", 3, offs[1]));
    xml.push_str("</Points>\n<Polys>\n");
    xml.push_str(&da("Int64", "connectivity", 1, offs[2]));
    xml.push_str(&da("Int64", "offsets", 1, offs[3]));
    xml.push_str("</Polys>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_");

    let tmp = path.with_extension("vtp.tmp");
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

/// The surface-mesh frames of one fluid participant: `NAME_surface_00000.vtp`, … in `dir` and
/// their series `NAME_surface.pvd`.
#[derive(Debug, Clone)]
pub struct SurfaceFrames {
    dir: PathBuf,
    name: String,
    spacing: f64,
    series: TimeSeries,
}

impl SurfaceFrames {
    /// Frames of fluid `name` with particle spacing `spacing` [m], written into `dir`.
    pub fn new(dir: &Path, name: &str, spacing: f64) -> SurfaceFrames {
        SurfaceFrames {
            dir: dir.to_path_buf(),
            name: name.to_string(),
            spacing,
            series: TimeSeries::new(dir.join(format!("{name}_surface.pvd"))),
        }
    }

    /// Meshes the fluid of `p`, writes it as frame `k` at `time` and adds it to the series; an
    /// error names the file that could not be written.
    pub fn write(&mut self, k: u64, time: f64, p: &Particles) -> Result<(), (PathBuf, io::Error)> {
        let file = format!("{}_surface_{k:05}.vtp", self.name);
        let path = self.dir.join(&file);
        let mesh = fluid_surface(p, self.spacing);
        write_vtp(&path, &mesh).map_err(|e| (path, e))?;
        let pvd = self.dir.join(format!("{}_surface.pvd", self.name));
        self.series.add(time, &file).map_err(|e| (pvd, e))
    }
}
