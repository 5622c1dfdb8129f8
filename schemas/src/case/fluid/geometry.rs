//! Boxes of a fluid section: `tank` ([`TankConfig`]), `[[fluid.NAME.block]]`,
//! `[[fluid.NAME.gate]]`, `[[fluid.NAME.wall]]` (an [`Aabb`] each) and `[[fluid.NAME.body]]`
//! ([`BodyConfig`]: a box or a closed mesh).

use super::Loaded;
use crate::case::error::check;
use crate::case::mesh_placement::MeshPlacement;
use crate::case::FieldError;
use crate::geometry::TriangleMesh;
use schemars::JsonSchema;
use serde::Deserialize;

/// An axis-aligned box `[min, max]` [m].
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Aabb {
    /// Lower corner `[x, y, z]` [m].
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m]; above `min` on every axis, inside the tank.
    pub max: [f64; 3],
}

impl Aabb {
    /// Checks that the box is finite and has positive extent along every axis.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        check::finite(&format!("{key}.min"), &self.min)?;
        check::finite(&format!("{key}.max"), &self.max)?;
        for a in 0..3 {
            if self.max[a] <= self.min[a] {
                return Err(FieldError::new(
                    format!("{key}.max"),
                    format!(
                        "must be greater than `min` along every axis; axis {} has min {} and max {}",
                        ["x", "y", "z"][a],
                        self.min[a],
                        self.max[a]
                    ),
                ));
            }
        }
        Ok(())
    }

    /// True when `other` lies inside `self` (faces may touch).
    pub fn contains(&self, other: &Aabb) -> bool {
        (0..3).all(|a| other.min[a] >= self.min[a] - 1e-12 && other.max[a] <= self.max[a] + 1e-12)
    }

    /// True when the two boxes share a volume (touching faces do not overlap).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        (0..3).all(|a| self.min[a] < other.max[a] - 1e-12 && other.min[a] < self.max[a] - 1e-12)
    }

    /// True when `p` lies inside the box (faces included).
    pub fn contains_point(&self, p: [f64; 3]) -> bool {
        (0..3).all(|a| p[a] >= self.min[a] && p[a] <= self.max[a])
    }
}

/// `tank = { min, max }`: the inner faces of the walls; walls are `wall_layers` particle layers
/// outside it. Extents that are not whole spacings are rounded to the nearest lattice face.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TankConfig {
    /// Lower corner `[x, y, z]` [m].
    pub min: [f64; 3],
    /// Upper corner `[x, y, z]` [m]: at least one spacing above `min` on every axis.
    pub max: [f64; 3],
    /// Close the top with a wall too (default: open top).
    #[serde(default)]
    pub lid: bool,
}

impl TankConfig {
    /// The tank's inner box.
    pub fn inner(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }
}

/// `[[fluid.NAME.body]]`: a rigid body made of `Body` particles: a box (`min`, `max`) or the
/// lattice sites inside a closed mesh (`mesh`), exactly one of the two. In a fluid-only run it is
/// held fixed (an obstacle); coupled scenes move it with the structure's kinematics.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyConfig {
    /// The body's name, unique in the participant (`[[coupling.body]]` names it
    /// `fluid-participant/name`).
    pub name: String,
    /// Box body: lower corner `[x, y, z]` [m].
    #[serde(default)]
    pub min: Option<[f64; 3]>,
    /// Box body: upper corner `[x, y, z]` [m].
    #[serde(default)]
    pub max: Option<[f64; 3]>,
    /// Mesh body, instead of `min`/`max`: every lattice site inside the placed mesh is a body
    /// particle, and the body's centre is the mesh's volume centroid (give the structure body
    /// `inertia = { mesh = … }` with the same mesh so the two centres agree).
    #[serde(default)]
    pub mesh: Option<MeshPlacement>,
    /// The placed mesh, read when the case is loaded.
    #[serde(skip)]
    #[schemars(skip)]
    pub placed: Loaded<TriangleMesh>,
}

impl BodyConfig {
    /// A box body `[min, max]`.
    pub fn from_box(name: &str, min: [f64; 3], max: [f64; 3]) -> BodyConfig {
        BodyConfig {
            name: name.into(),
            min: Some(min),
            max: Some(max),
            mesh: None,
            placed: Loaded::default(),
        }
    }

    /// The box of a box body; `None` for a mesh body.
    pub fn box_bounds(&self) -> Option<Aabb> {
        match (self.min, self.max) {
            (Some(min), Some(max)) => Some(Aabb { min, max }),
            _ => None,
        }
    }

    /// The body's placed mesh: `None` for a box body, or before [`FluidConfig::load_files`].
    ///
    /// [`FluidConfig::load_files`]: super::FluidConfig::load_files
    pub fn placed_mesh(&self) -> Option<&TriangleMesh> {
        self.placed.get()
    }

    /// The body's centre at t = 0 [m], the reference of its pose and moments: a box body's
    /// middle `(min + max) / 2`, a mesh body's volume centroid `∫ x dV / V` (NaN for a mesh body
    /// before [`FluidConfig::load_files`]).
    ///
    /// [`FluidConfig::load_files`]: super::FluidConfig::load_files
    pub fn centre(&self) -> [f64; 3] {
        match (self.box_bounds(), self.placed_mesh()) {
            (Some(b), _) => std::array::from_fn(|a| 0.5 * (b.min[a] + b.max[a])),
            (None, Some(mesh)) => mesh.mass_properties(1.0).centre,
            (None, None) => [f64::NAN; 3],
        }
    }
}
