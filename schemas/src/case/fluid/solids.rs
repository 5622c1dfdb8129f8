//! `[[fluid.NAME.solid]]` (a fixed solid from a closed triangle mesh) and
//! `[[fluid.NAME.terrain]]` (a sea bed from a height grid or a plane): wall particles on the
//! fluid's lattice, built like the wall boxes of `[[fluid.NAME.wall]]`.
//!
//! ```toml
//! [[fluid.flume.solid]]          # a pier drawn in CAD, in millimetres
//! mesh = "pier.stl"              # STL (binary or ASCII) or OBJ, relative to the case file
//! scale = 0.001                  # mm → m
//! rotate = [0.0, 0.0, 90.0]      # degrees about x, then y, then z (about the origin)
//! translate = [2.0, 0.3, 0.0]    # [m], applied last
//!
//! [[fluid.flume.terrain]]        # a 1:19.85 beach whose toe is at x = 5 m
//! plane = { point = [5.0, 0.0, 0.0], normal = [-1.0, 0.0, 19.85] }
//!
//! [[fluid.flume.terrain]]        # or a surveyed bed: an ESRI ASCII grid (DEM)
//! grid = "bathymetry.asc"
//! translate = [0.0, 0.0, -2.0]
//! ```
//!
//! A lattice site inside a solid or below a terrain's surface, and inside the tank, is a wall
//! site; only the solid's skin, `wall_layers` sites deep, is built (the inside of a hill costs
//! nothing). Water blocks fill around them: a beach with still water on it is a terrain and a
//! block up to the water level.

use super::{Aabb, FluidConfig};
use crate::case::error::check;
use crate::case::mesh_placement::MeshPlacement;
use crate::case::FieldError;
use crate::geometry::{read_geotiff, read_height_grid, HeightGrid, TriangleMesh};
use schemars::JsonSchema;
use serde::Deserialize;
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A mesh larger than this many tank extents along an axis is refused as a unit mistake.
pub const MAX_MESH_TO_TANK: f64 = 4.0;

/// Geometry read from a file the case names, once, when the case is loaded
/// ([`FluidConfig::load_files`]); not part of the case file's keys.
pub struct Loaded<T>(pub Option<Arc<T>>);

impl<T> Default for Loaded<T> {
    fn default() -> Self {
        Loaded(None)
    }
}

impl<T> Clone for Loaded<T> {
    fn clone(&self) -> Self {
        Loaded(self.0.clone())
    }
}

impl<T> fmt::Debug for Loaded<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.0.is_some() { "loaded" } else { "not loaded" })
    }
}

impl<T> Loaded<T> {
    /// The geometry; `None` before [`FluidConfig::load_files`].
    pub fn get(&self) -> Option<&T> {
        self.0.as_deref()
    }
}

/// `[[fluid.NAME.solid]]`: a fixed solid from a closed, outward-oriented triangle mesh.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolidConfig {
    /// The mesh file: `.stl` (binary or ASCII) or `.obj`, relative to the case file's folder.
    /// It must be closed (every edge shared by two triangles), consistently oriented with its
    /// normals outwards, and free of degenerate triangles.
    pub mesh: PathBuf,
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
    /// The placed mesh, read when the case is loaded.
    #[serde(skip)]
    #[schemars(skip)]
    pub placed: Loaded<TriangleMesh>,
}

impl SolidConfig {
    /// The mesh's file and placement, checked and read as every mesh of a case is
    /// ([`MeshPlacement`]).
    pub fn placement(&self) -> MeshPlacement {
        MeshPlacement {
            file: self.mesh.clone(),
            scale: self.scale,
            rotate: self.rotate,
            translate: self.translate,
        }
    }
}

/// `plane = { point, normal }`: the solid below an inclined plane.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaneConfig {
    /// A point of the plane `[x, y, z]` [m].
    pub point: [f64; 3],
    /// The plane's normal [–], pointing out of the solid into the water; need not be unit length
    /// (a 1:s beach rising towards +x is `[-1, 0, s]`). Its z component must be > 0.
    pub normal: [f64; 3],
}

impl PlaneConfig {
    /// The plane's height over (x, y): `z = z0 − (n_x (x − x0) + n_y (y − y0)) / n_z`.
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        let (p, n) = (self.point, self.normal);
        p[2] - (n[0] * (x - p[0]) + n[1] * (y - p[1])) / n[2]
    }
}

/// `[[fluid.NAME.terrain]]`: the ground below a surface z = h(x, y) inside the tank, from a
/// height grid or a plane (exactly one of `grid` and `plane`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TerrainConfig {
    /// An ESRI ASCII grid (`.asc`, the format DEMs are shared in) or a GeoTIFF (`.tif`, `.tiff`:
    /// one band, north up, placed by its pixel scale and tiepoint), relative to the case file's
    /// folder: heights [m] at cell centres, bilinear in between; no missing values inside the
    /// tank. Columns of the tank outside the grid's cell centres get no terrain.
    #[serde(default)]
    pub grid: Option<PathBuf>,
    /// An inclined plane instead of a grid.
    #[serde(default)]
    pub plane: Option<PlaneConfig>,
    /// Grid only: translation [m] of the grid's x, y and heights.
    #[serde(default)]
    pub translate: [f64; 3],
    /// Only this box of the tank gets terrain; default: the whole tank.
    #[serde(default)]
    pub region: Option<Aabb>,
    /// The grid, read when the case is loaded.
    #[serde(skip)]
    #[schemars(skip)]
    pub heights: Loaded<HeightGrid>,
}

impl TerrainConfig {
    /// The terrain's height at (x, y) [m]; `None` where it has none (outside the grid or the
    /// region). Before [`FluidConfig::load_files`] a grid terrain has none anywhere.
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        if let Some(r) = &self.region {
            if x < r.min[0] || x > r.max[0] || y < r.min[1] || y > r.max[1] {
                return None;
            }
        }
        let h = match (&self.plane, self.heights.get()) {
            (Some(plane), _) => plane.height_at(x, y),
            (None, Some(grid)) => {
                let t = self.translate;
                grid.height_at(x - t[0], y - t[1])? + t[2]
            }
            (None, None) => return None,
        };
        match &self.region {
            Some(r) => Some(h.min(r.max[2])).filter(|&h| h >= r.min[2]),
            None => Some(h),
        }
    }
}

fn unit_scale() -> f64 {
    1.0
}

impl FluidConfig {
    /// Checks the keys of the solids and terrains (their files are read by
    /// [`FluidConfig::load_files`]).
    pub(super) fn validate_solids(&self, key: &str) -> Result<(), FieldError> {
        for (i, s) in self.solid.iter().enumerate() {
            s.placement().validate(&format!("{key}.solid[{i}]"))?;
        }
        for (i, t) in self.terrain.iter().enumerate() {
            let tk = format!("{key}.terrain[{i}]");
            check::finite(&format!("{tk}.translate"), &t.translate)?;
            match (&t.grid, &t.plane) {
                (Some(_), Some(_)) | (None, None) => {
                    return Err(FieldError::new(
                        tk,
                        "needs exactly one of `grid` (an ESRI ASCII height grid) and `plane` (`{ point, normal }`)",
                    ))
                }
                (None, Some(plane)) => {
                    check::finite(&format!("{tk}.plane.point"), &plane.point)?;
                    check::finite(&format!("{tk}.plane.normal"), &plane.normal)?;
                    let n = plane.normal;
                    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    if n[2] <= 1e-6 * len {
                        return Err(FieldError::new(
                            format!("{tk}.plane.normal"),
                            format!(
                                "must point up, out of the ground into the water (a z component > 0; a 1:s beach rising towards +x is [-1, 0, s]), got {n:?}"
                            ),
                        ));
                    }
                    if t.translate != [0.0; 3] {
                        return Err(FieldError::new(
                            format!("{tk}.translate"),
                            "applies to a `grid`; move a plane by its `point`",
                        ));
                    }
                }
                (Some(_), None) => {}
            }
            if let Some(r) = &t.region {
                r.validate(&format!("{tk}.region"))?;
            }
        }
        Ok(())
    }

    /// Reads the mesh and grid files of the solids, terrains and mesh bodies, relative to `dir`
    /// (the case file's folder), checks them and keeps them placed; `key` is the section's dotted path.
    /// Errors name the key, the file and what is wrong.
    pub fn load_files(&mut self, dir: &Path, key: &str) -> Result<(), FieldError> {
        let tank = self.tank.inner();
        // an absolute path replaces `dir` (`Path::join`)
        let resolve = |p: &Path| dir.join(p);
        for (i, s) in self.solid.iter_mut().enumerate() {
            let sk = format!("{key}.solid[{i}].mesh");
            let path = resolve(&s.mesh);
            let placed = s.placement().load_as(dir, &sk)?;
            let (lo, hi) = placed.aabb();
            for a in 0..3 {
                let (extent, room) = (hi[a] - lo[a], tank.max[a] - tank.min[a]);
                if extent > MAX_MESH_TO_TANK * room {
                    return Err(FieldError::new(
                        &sk,
                        format!(
                            "{}: placed, the mesh is {extent} m long along {}, more than {MAX_MESH_TO_TANK} times the tank's {room} m: is it in millimetres (scale = 0.001)?",
                            path.display(),
                            ["x", "y", "z"][a]
                        ),
                    ));
                }
            }
            let placed_box = Aabb { min: lo, max: hi };
            if !tank.overlaps(&placed_box) {
                return Err(FieldError::new(
                    &sk,
                    format!(
                        "{}: placed, the mesh spans {lo:?} … {hi:?}, outside the tank {:?} … {:?}",
                        path.display(),
                        tank.min,
                        tank.max
                    ),
                ));
            }
            s.placed = Loaded(Some(Arc::new(placed)));
        }
        for (i, t) in self.terrain.iter_mut().enumerate() {
            let Some(file) = &t.grid else { continue };
            let tk = format!("{key}.terrain[{i}].grid");
            let path = resolve(file);
            let extension = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            let grid = match extension.as_deref() {
                Some("asc") => read_height_grid(&path),
                Some("tif" | "tiff") => read_geotiff(&path),
                _ => {
                    return Err(FieldError::new(
                        &tk,
                        format!(
                            "{}: a height grid is an ESRI ASCII grid (.asc) or a GeoTIFF (.tif, .tiff)",
                            path.display()
                        ),
                    ))
                }
            }
            .map_err(|e| FieldError::new(&tk, e.to_string()))?;
            let (lo, hi) = grid.centres_extent();
            let (t0, t1) = (t.translate[0], t.translate[1]);
            let overlaps = lo[0] + t0 < tank.max[0]
                && hi[0] + t0 > tank.min[0]
                && lo[1] + t1 < tank.max[1]
                && hi[1] + t1 > tank.min[1];
            if !overlaps {
                return Err(FieldError::new(
                    &tk,
                    format!(
                        "{}: the grid's cell centres span x {} … {}, y {} … {} (moved by translate = {:?}), outside the tank's x {} … {}, y {} … {}: is it in the case's coordinates?",
                        path.display(),
                        lo[0] + t0,
                        hi[0] + t0,
                        lo[1] + t1,
                        hi[1] + t1,
                        t.translate,
                        tank.min[0],
                        tank.max[0],
                        tank.min[1],
                        tank.max[1]
                    ),
                ));
            }
            t.heights = Loaded(Some(Arc::new(grid)));
        }
        self.load_mesh_bodies(dir, key)
    }
}
