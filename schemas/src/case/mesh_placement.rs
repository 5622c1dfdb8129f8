//! `mesh = { file, scale, rotate, translate }`: a closed triangle mesh placed in the case, for a
//! fluid body's particles (`[[fluid.NAME.body]]`) and a structure body's mass properties
//! (`inertia = { mesh = { … }, density }`). A vertex `v` of the file is placed at
//! `x = R_z R_y R_x (scale · v) + translate`, as a `[[fluid.NAME.solid]]`'s.

use crate::case::error::check;
use crate::case::FieldError;
use crate::geometry::{read_mesh, TriangleMesh};
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// A closed, outward-oriented triangle mesh and where it is placed.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshPlacement {
    /// The mesh file: `.stl` (binary or ASCII) or `.obj`, relative to the case file's folder.
    /// It must be closed (every edge shared by two triangles), consistently oriented with its
    /// normals outwards, and free of degenerate triangles.
    pub file: PathBuf,
    /// Scale factor applied first [–] (e.g. 0.001 for a mesh drawn in millimetres). Range: > 0.
    #[serde(default = "unit_scale")]
    pub scale: f64,
    /// Rotations [deg] about the x, then the y, then the z axis through the origin, applied after
    /// the scale.
    #[serde(default)]
    pub rotate: [f64; 3],
    /// Translation [m], applied last.
    #[serde(default)]
    pub translate: [f64; 3],
}

fn unit_scale() -> f64 {
    1.0
}

impl MeshPlacement {
    /// Checks the placement's numbers; `key` is the table's dotted path (`….mesh`).
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        check::positive(&format!("{key}.scale"), self.scale)?;
        check::finite(&format!("{key}.rotate"), &self.rotate)?;
        check::finite(&format!("{key}.translate"), &self.translate)
    }

    /// Reads the file relative to `dir` (the case file's folder), refuses a mesh that is not a
    /// closed solid ([`TriangleMesh::check_solid`]) and returns it placed. Errors are at
    /// `{key}.file` and name the file.
    pub fn load(&self, dir: &Path, key: &str) -> Result<TriangleMesh, FieldError> {
        self.load_as(dir, &format!("{key}.file"))
    }

    /// As [`MeshPlacement::load`], with the errors at `file_key` (a table whose file key has
    /// another name: `[[fluid.NAME.solid]]`'s `mesh`).
    pub fn load_as(&self, dir: &Path, file_key: &str) -> Result<TriangleMesh, FieldError> {
        // an absolute path replaces `dir` (`Path::join`)
        let path = dir.join(&self.file);
        let mesh = read_mesh(&path).map_err(|e| FieldError::new(file_key, e.to_string()))?;
        mesh.check_solid()
            .map_err(|e| FieldError::new(file_key, e.in_file(&path).to_string()))?;
        Ok(mesh.transformed([self.scale; 3], self.rotate, self.translate))
    }

    /// The file as the case resolves it from `dir`, for messages.
    pub fn path(&self, dir: &Path) -> PathBuf {
        dir.join(&self.file)
    }
}
