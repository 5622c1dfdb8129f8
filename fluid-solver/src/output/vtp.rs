//! ParaView output of free-surface meshes: one VTP (XML PolyData, raw appended binary) per frame
//! and a PVD series `NAME_surface.pvd` beside the particle series `NAME.pvd`.

use crate::output::surface_mesh::{fluid_surface, TriangleMesh};
use crate::output::vtk_appended::{self, Array, Section};
use crate::particles::Particles;
use schemas::participant::ProgressSink;
use schemas::pvd::Collection;
use std::io;
use std::path::{Path, PathBuf};

/// Writes `mesh` to `path` as a VTP file (via a temporary file, so a frame is never half written):
/// points, per-point `normals`, and the triangles as polys; `progress` is told of the bytes written.
pub fn write_vtp(path: &Path, mesh: &TriangleMesh, progress: &mut dyn ProgressSink) -> io::Result<()> {
    let (n, m) = (mesh.vertices.len(), mesh.triangles.len());
    let sections = [
        Section {
            element: "PointData",
            attributes: "Normals=\"normals\"".into(),
            arrays: vec![Array::new(
                "Float32",
                "normals",
                3,
                3 * n,
                || mesh.normals.iter().flatten().copied(),
                f32::to_le_bytes,
            )],
        },
        Section {
            element: "Points",
            attributes: String::new(),
            arrays: vec![Array::new(
                "Float64",
                "position",
                3,
                3 * n,
                || mesh.vertices.iter().flatten().copied(),
                f64::to_le_bytes,
            )],
        },
        Section {
            element: "Polys",
            attributes: String::new(),
            arrays: vec![
                Array::new(
                    "Int64",
                    "connectivity",
                    1,
                    3 * m,
                    || mesh.triangles.iter().flatten().map(|&v| i64::from(v)),
                    i64::to_le_bytes,
                ),
                Array::new(
                    "Int64",
                    "offsets",
                    1,
                    m,
                    || (1..=m as i64).map(|t| 3 * t),
                    i64::to_le_bytes,
                ),
            ],
        },
    ];
    let piece = format!(
        "NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"{m}\""
    );
    vtk_appended::write(path, "PolyData", &piece, &sections, progress)
}

/// The surface-mesh frames of one fluid participant: `NAME_surface_00000.vtp`, … in `dir` and
/// their series `NAME_surface.pvd`.
#[derive(Debug, Clone)]
pub struct SurfaceFrames {
    dir: PathBuf,
    name: String,
    spacing: f64,
    series: Collection,
}

impl SurfaceFrames {
    /// Frames of fluid `name` with particle spacing `spacing` [m], written into `dir`.
    pub fn new(dir: &Path, name: &str, spacing: f64) -> SurfaceFrames {
        SurfaceFrames {
            dir: dir.to_path_buf(),
            name: name.to_string(),
            spacing,
            series: Collection::new(dir.join(format!("{name}_surface.pvd"))),
        }
    }

    /// The series so far (a checkpoint keeps it).
    pub fn series(&self) -> &Collection {
        &self.series
    }

    /// Frames that continue `series` (a resumed run); the `.pvd` is rewritten to list them.
    pub fn resumed(
        dir: &Path,
        name: &str,
        spacing: f64,
        series: Vec<(f64, String)>,
    ) -> io::Result<SurfaceFrames> {
        Ok(SurfaceFrames {
            dir: dir.to_path_buf(),
            name: name.to_string(),
            spacing,
            series: Collection::resumed(dir.join(format!("{name}_surface.pvd")), series)?,
        })
    }

    /// Meshes the fluid of `p`, writes it as frame `k` at `time` (telling `progress` of the bytes
    /// written) and adds it to the series; an error names the file that could not be written.
    pub fn write(
        &mut self,
        k: u64,
        time: f64,
        p: &Particles,
        progress: &mut dyn ProgressSink,
    ) -> Result<(), (PathBuf, io::Error)> {
        let file = format!("{}_surface_{k:05}.vtp", self.name);
        let path = self.dir.join(&file);
        let mesh = fluid_surface(p, self.spacing);
        write_vtp(&path, &mesh, progress).map_err(|e| (path, e))?;
        let pvd = self.dir.join(format!("{}_surface.pvd", self.name));
        self.series.add(time, &file).map_err(|e| (pvd, e))
    }
}
