//! Bodies from meshes (`[[fluid.NAME.body]]` with `mesh = { file, … }`): their files are read
//! when the case is loaded, and each placed mesh must lie inside the tank, hold at least one
//! lattice site, and keep its bounding box clear of the gates, wall boxes, other bodies, the
//! wave maker's paddle and the inflow strip (as a box body must). Water blocks may overlap it:
//! the body takes its sites first, as a `[[solid]]` does.

use super::{Aabb, FluidConfig, Loaded};
use crate::case::FieldError;
use crate::geometry::{sites_inside_mesh, Lattice};
use std::path::Path;
use std::sync::Arc;

impl FluidConfig {
    /// Reads, checks and places the meshes of the mesh bodies, relative to `dir` (the case file's
    /// folder); `key` is the section's dotted path. Errors are at `….body[i].mesh` and name the
    /// file.
    pub(super) fn load_mesh_bodies(&mut self, dir: &Path, key: &str) -> Result<(), FieldError> {
        let tank = self.tank.inner();
        let mut taken: Vec<(String, Aabb)> = Vec::new();
        taken.extend(
            self.gate
                .iter()
                .enumerate()
                .map(|(i, g)| (format!("{key}.gate[{i}]"), *g)),
        );
        taken.extend(
            self.wall
                .iter()
                .enumerate()
                .map(|(i, w)| (format!("{key}.wall[{i}]"), *w)),
        );
        if let Some(w) = &self.wave_maker {
            taken.push((format!("{key}.wave_maker"), w.paddle()));
        }
        if let Some(inflow) = &self.inflow {
            let strip = inflow.validate(&format!("{key}.inflow"), &tank, self.spacing)?;
            taken.push((format!("{key}.inflow"), strip));
        }
        for (i, b) in self.body.iter().enumerate() {
            if let Some(bb) = b.box_bounds() {
                taken.push((format!("{key}.body[{i}]"), bb));
            }
        }
        let lattice = Lattice {
            origin: tank.min,
            spacing: self.spacing,
            n: std::array::from_fn(|a| {
                ((tank.max[a] - tank.min[a]) / self.spacing).round().max(0.0) as usize
            }),
        };
        for (i, b) in self.body.iter_mut().enumerate() {
            let Some(m) = &b.mesh else { continue };
            let mk = format!("{key}.body[{i}].mesh");
            let placed = m.load(dir, &mk)?;
            let path = m.path(dir);
            let (min, max) = placed.aabb();
            let bounds = Aabb { min, max };
            if !tank.contains(&bounds) {
                return Err(FieldError::new(
                    &mk,
                    format!(
                        "{}: placed, the mesh spans {min:?} … {max:?}; a body must lie inside the tank {:?} … {:?} (check scale, rotate and translate)",
                        path.display(),
                        tank.min,
                        tank.max
                    ),
                ));
            }
            if let Some((k, _)) = taken.iter().find(|(_, t)| bounds.overlaps(t)) {
                return Err(FieldError::new(
                    &mk,
                    format!(
                        "{}: placed, the mesh's bounding box {min:?} … {max:?} overlaps `{k}`; a body must not share volume with gates, walls, other bodies, the paddle or the inflow strip",
                        path.display()
                    ),
                ));
            }
            if sites_inside_mesh(&placed, &lattice).count() == 0 {
                return Err(FieldError::new(
                    &mk,
                    format!(
                        "{}: placed, the mesh holds no particle: particles sit at tank.min + (k + ½)·spacing ({} m)",
                        path.display(),
                        self.spacing
                    ),
                ));
            }
            taken.push((mk, bounds));
            b.placed = Loaded(Some(Arc::new(placed)));
        }
        Ok(())
    }
}
