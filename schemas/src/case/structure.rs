//! `[structure.NAME]`: a structure participant — point masses, springs, rigid bodies with washout
//! supports, prescribed loads, the histories to write, and (optionally) an ASI-Gauss frame.
//!
//! ```toml
//! [structure.tower]
//! max_step = 1e-3                # largest substep of point masses and bodies [s] (not needed for a frame alone)
//! gravity = [0, 0, -9.8]         # default 0
//!
//! [[structure.tower.point_mass]]
//! name = "m1"
//! mass = 1.0
//! position = [0, 0, 0]
//! displacement = [1, 0, 0]       # initial, default 0
//! velocity = [0, 0, 0]           # initial, default 0
//!
//! [[structure.tower.spring]]     # f_a = k (u_b − u_a), u: displacements
//! a = "m1"
//! b = "ground"                   # "ground", a point mass or a body (its centre)
//! stiffness = 39.478
//!
//! [[structure.tower.body]]
//! name = "deck"
//! mass = 2.0
//! centre = [0, 0, 1]
//! inertia = { box = [1, 0.5, 0.2] }   # or { tensor = [[..],[..],[..]] } or { particles = [[..], ..], particle_mass = m }
//!                                     # or { mesh = { file = "deck.stl" }, density = 500 } (no mass, centre)
//!
//! [[structure.tower.support]]    # S1-22: held until the upward force exceeds release_force
//! body = "deck"
//! release_force = 1e9
//!
//! [[structure.tower.load]]
//! point = "m1"                   # or body = "deck" (6 values: force, torque) or node = 12 (6 values)
//! value = [0, 0, 10]
//! history = "ramp"               # constant (default) | step | ramp | table
//! start = 0.0
//! end = 1.0
//!
//! [structure.tower.history]      # CSV histories (standalone mode, and participant mode with --out)
//! interval = 0.01
//! points = ["m1"]
//! bodies = ["deck"]
//! nodes = [12]                   # frame node ids
//! vtu_interval = 0.1             # optional: frame snapshots this often (default: every row)
//! vtu = true                     # optional: false writes no frame snapshots
//! section_forces = true          # optional: false writes no section-forces.csv
//!
//! [structure.tower.frame]        # optional ASI-Gauss frame: see `frame.rs`
//! ```

use super::error::check;
use super::frame::FrameConfig;
use super::mesh_placement::MeshPlacement;
use super::FieldError;
use crate::geometry::MassProperties;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The spring end that is fixed in space.
pub const GROUND: &str = "ground";

/// Configuration of one structure participant.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StructureConfig {
    /// Point masses and bodies only: largest integrator substep [s]; each advance lands exactly
    /// on its end time. Required with point masses or bodies; a frame takes its own `time_step`.
    /// Range: > 0.
    #[serde(default)]
    pub max_step: Option<f64>,
    /// Point masses and bodies only: gravity acceleration [m/s²] (a frame takes
    /// `frame.gravity`; when both are given they must agree).
    #[serde(default)]
    pub gravity: [f64; 3],
    /// Translating points with mass.
    #[serde(default)]
    pub point_mass: Vec<PointMassConfig>,
    /// Linear springs between point masses, bodies and the ground.
    #[serde(default)]
    pub spring: Vec<SpringConfig>,
    /// Rigid bodies with six degrees of freedom.
    #[serde(default)]
    pub body: Vec<BodyConfig>,
    /// Washout supports: bodies held until the upward force exceeds a threshold.
    #[serde(default)]
    pub support: Vec<SupportConfig>,
    /// Prescribed loads.
    #[serde(default)]
    pub load: Vec<LoadConfig>,
    /// Which histories are written as CSV, and how often.
    #[serde(default)]
    pub history: Option<HistoryConfig>,
    /// An ASI-Gauss framed structure (`[structure.NAME.frame]`).
    #[serde(default)]
    pub frame: Option<FrameConfig>,
}

/// `[[structure.NAME.point_mass]]`: a translating point with mass.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointMassConfig {
    /// The point's name, unique in the participant (`[[coupling.spring]]` names it
    /// `participant/name`).
    pub name: String,
    /// Mass [kg].
    pub mass: f64,
    /// Reference position [m]; displacements are measured from it.
    pub position: [f64; 3],
    /// Initial displacement [m].
    #[serde(default)]
    pub displacement: [f64; 3],
    /// Initial velocity [m/s].
    #[serde(default)]
    pub velocity: [f64; 3],
}

/// `[[structure.NAME.spring]]`: a linear spring on displacements, `f_a = k (u_b − u_a)`, `f_b = −f_a`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpringConfig {
    /// A point mass or body name.
    pub a: String,
    /// `"ground"`, a point mass or a body name.
    pub b: String,
    /// Stiffness [N/m].
    pub stiffness: f64,
}

/// `[[structure.NAME.body]]`: a 6-DOF rigid body (S1-17, S1-18).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyConfig {
    /// The body's name, unique in the participant (`[[coupling.body]]` names it
    /// `participant/name`).
    pub name: String,
    /// Mass [kg]; required with `inertia.box` / `inertia.tensor`, omitted with `inertia.particles`
    /// (then it is the particle count × `particle_mass`) and `inertia.mesh` (density × volume).
    #[serde(default)]
    pub mass: Option<f64>,
    /// Centre of mass [m]; required with `inertia.box` / `inertia.tensor`, omitted with
    /// `inertia.particles` (then it is the particles' centroid) and `inertia.mesh` (the volume
    /// centroid).
    #[serde(default)]
    pub centre: Option<[f64; 3]>,
    /// Initial orientation, unit quaternion `[w, x, y, z]` (body → world) [–].
    #[serde(default = "identity_quaternion")]
    pub orientation: [f64; 4],
    /// Initial velocity of the centre [m/s].
    #[serde(default)]
    pub velocity: [f64; 3],
    /// Initial angular velocity, world frame [rad/s].
    #[serde(default)]
    pub angular_velocity: [f64; 3],
    pub inertia: InertiaConfig,
}

fn identity_quaternion() -> [f64; 4] {
    [1.0, 0.0, 0.0, 0.0]
}

/// `inertia = { … }`: exactly one of `box`, `tensor`, `particles` (with `particle_mass`) or
/// `mesh` (with `density`), all in the body frame.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InertiaConfig {
    /// Edge lengths [m] of a homogeneous box along the body axes.
    #[serde(default, rename = "box")]
    pub box_size: Option<[f64; 3]>,
    /// Inertia tensor about the centre [kg m²], symmetric positive definite.
    #[serde(default)]
    pub tensor: Option<[[f64; 3]; 3]>,
    /// World positions [m] of the body's particles at t = 0; the body's mass is their count ×
    /// `particle_mass`, its centre their centroid.
    #[serde(default)]
    pub particles: Option<Vec<[f64; 3]>>,
    /// Mass of each particle [kg].
    #[serde(default)]
    pub particle_mass: Option<f64>,
    /// A closed mesh placed in world coordinates at t = 0 (as a fluid body's `mesh`): the body
    /// is the homogeneous solid it bounds, of `density`; its mass is `density` × volume and its
    /// centre the volume centroid (then `mass` and `centre` are omitted).
    #[serde(default)]
    pub mesh: Option<MeshPlacement>,
    /// Density of the mesh's solid [kg/m³] (with `mesh` only). Range: > 0.
    #[serde(default)]
    pub density: Option<f64>,
    /// The mesh's mass properties (world frame), computed when the case is loaded.
    #[serde(skip)]
    #[schemars(skip)]
    pub mesh_properties: Option<MassProperties>,
}

/// `[[structure.NAME.support]]`: holds a body fixed until the upward force exceeds
/// `release_force`, then releases it for good (washout, S1-22).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportConfig {
    /// The body held.
    pub body: String,
    /// F_d [N]: the body is released once the upward applied force exceeds it.
    pub release_force: f64,
}

/// How a prescribed load varies in time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum LoadHistory {
    /// `value` at all times.
    #[default]
    Constant,
    /// 0 before `start`, `value` from `start` on.
    Step,
    /// 0 before `start`, linear to `value` at `end`, `value` after.
    Ramp,
    /// Read from the CSV file `table`: columns t, then the components; linear in between,
    /// held constant outside.
    Table,
}

/// `[[structure.NAME.load]]`: a prescribed load on one point mass, body or frame node.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadConfig {
    /// A point mass name: 3 components (force).
    #[serde(default)]
    pub point: Option<String>,
    /// A body name: 6 components (force, torque about the centre; world frame).
    #[serde(default)]
    pub body: Option<String>,
    /// A frame node id: 6 components (force, moment; global).
    #[serde(default)]
    pub node: Option<u32>,
    /// How the load varies in time.
    #[serde(default)]
    pub history: LoadHistory,
    /// The components [N, N m]: 3 forces for a point mass, 3 forces and 3 torques or moments
    /// for a body or a node (not with `table`).
    #[serde(default)]
    pub value: Option<Vec<f64>>,
    /// Start time [s] of `step` and `ramp`.
    #[serde(default)]
    pub start: Option<f64>,
    /// End time [s] of `ramp`.
    #[serde(default)]
    pub end: Option<f64>,
    /// CSV file of `table`, relative to the case file.
    #[serde(default)]
    pub table: Option<PathBuf>,
}

/// What a load acts on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadTarget<'a> {
    Point(&'a str),
    Body(&'a str),
    Node(u32),
}

impl LoadTarget<'_> {
    /// Number of load components: 3 for a point mass, 6 for a body or a frame node.
    pub fn components(self) -> usize {
        match self {
            LoadTarget::Point(_) => 3,
            LoadTarget::Body(_) | LoadTarget::Node(_) => 6,
        }
    }
}

impl LoadConfig {
    /// The one target the load names; `key` is the load's dotted path.
    pub fn target(&self, key: &str) -> Result<LoadTarget<'_>, FieldError> {
        match (&self.point, &self.body, self.node) {
            (Some(p), None, None) => Ok(LoadTarget::Point(p)),
            (None, Some(b), None) => Ok(LoadTarget::Body(b)),
            (None, None, Some(n)) => Ok(LoadTarget::Node(n)),
            _ => Err(FieldError::new(
                key,
                "must name exactly one target: `point = \"NAME\"`, `body = \"NAME\"` or `node = ID`",
            )),
        }
    }
}

/// `[structure.NAME.history]`: which quantities standalone mode writes as CSV, and how often.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HistoryConfig {
    /// Output interval [s]. Range: > 0.
    pub interval: f64,
    /// Point masses: displacement and velocity.
    #[serde(default)]
    pub points: Vec<String>,
    /// Bodies: centre, quaternion, velocity, angular velocity, held flag.
    #[serde(default)]
    pub bodies: Vec<String>,
    /// Frame node ids: position, rotation vector, velocity and angular velocity.
    #[serde(default)]
    pub nodes: Vec<u32>,
    /// Frame snapshots (VTU) at the first history time at or after every multiple of this [s];
    /// absent: at every history time.
    #[serde(default)]
    pub vtu_interval: Option<f64>,
    /// Whether frame snapshots are written at all (default true).
    #[serde(default = "yes")]
    pub vtu: bool,
    /// Whether the frame's section forces (`section-forces.csv`) are written at the history times
    /// (default true when there is a frame).
    #[serde(default = "yes")]
    pub section_forces: bool,
}

fn yes() -> bool {
    true
}

impl StructureConfig {
    /// Checks every key; `key` is the section's dotted path, e.g. `structure.bridge`.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        match self.max_step {
            Some(h) => check::positive(&format!("{key}.max_step"), h)?,
            None if !(self.point_mass.is_empty() && self.body.is_empty()) => {
                return Err(FieldError::new(
                    format!("{key}.max_step"),
                    "is required when the participant has point masses or bodies (a frame alone \
                     steps by its own time_step)",
                ))
            }
            None => {}
        }
        check::finite(&format!("{key}.gravity"), &self.gravity)?;
        let mut names = BTreeSet::new();
        if let Some(f) = &self.frame {
            f.validate(&format!("{key}.frame"))?;
            let given = |g: &[f64; 3]| g.iter().any(|c| *c != 0.0);
            if given(&self.gravity) && given(&f.gravity) && self.gravity != f.gravity {
                return Err(FieldError::new(
                    format!("{key}.frame.gravity"),
                    format!(
                        "{:?} differs from {key}.gravity = {:?}; a participant has one gravity",
                        f.gravity, self.gravity
                    ),
                ));
            }
        }
        for (i, p) in self.point_mass.iter().enumerate() {
            let k = format!("{key}.point_mass[{i}]");
            check_name(&format!("{k}.name"), &p.name, &mut names)?;
            check::positive(&format!("{k}.mass"), p.mass)?;
            check::finite(&format!("{k}.position"), &p.position)?;
            check::finite(&format!("{k}.displacement"), &p.displacement)?;
            check::finite(&format!("{k}.velocity"), &p.velocity)?;
        }
        for (i, b) in self.body.iter().enumerate() {
            b.validate(&format!("{key}.body[{i}]"), &mut names)?;
        }
        for (i, s) in self.spring.iter().enumerate() {
            let k = format!("{key}.spring[{i}]");
            check::positive(&format!("{k}.stiffness"), s.stiffness)?;
            self.check_spring_end(&format!("{k}.a"), &s.a, false)?;
            self.check_spring_end(&format!("{k}.b"), &s.b, true)?;
            if s.a == s.b {
                return Err(FieldError::new(
                    k,
                    format!("both ends are `{}`; a spring joins two things", s.a),
                ));
            }
        }
        let mut supported = BTreeSet::new();
        for (i, s) in self.support.iter().enumerate() {
            let k = format!("{key}.support[{i}]");
            self.check_body(&format!("{k}.body"), &s.body)?;
            if !supported.insert(s.body.as_str()) {
                return Err(FieldError::new(
                    format!("{k}.body"),
                    format!(
                        "body `{}` already has a support; give each body at most one",
                        s.body
                    ),
                ));
            }
            check::non_negative(&format!("{k}.release_force"), s.release_force)?;
        }
        for (i, l) in self.load.iter().enumerate() {
            self.check_load(&format!("{key}.load[{i}]"), l)?;
        }
        if let Some(h) = &self.history {
            let k = format!("{key}.history");
            check::positive(&format!("{k}.interval"), h.interval)?;
            if let Some(v) = h.vtu_interval {
                check::positive(&format!("{k}.vtu_interval"), v)?;
            }
            for (i, p) in h.points.iter().enumerate() {
                self.check_point(&format!("{k}.points[{i}]"), p)?;
            }
            for (i, b) in h.bodies.iter().enumerate() {
                self.check_body(&format!("{k}.bodies[{i}]"), b)?;
            }
            for (i, id) in h.nodes.iter().enumerate() {
                self.check_node(&format!("{k}.nodes[{i}]"), *id)?;
            }
        }
        Ok(())
    }

    /// Names of the point masses this participant owns (coupling springs attach to them).
    pub fn point_names(&self) -> Vec<&str> {
        self.point_mass.iter().map(|p| p.name.as_str()).collect()
    }

    /// Names of the rigid bodies this participant owns.
    pub fn body_names(&self) -> Vec<&str> {
        self.body.iter().map(|b| b.name.as_str()).collect()
    }

    fn check_node(&self, key: &str, id: u32) -> Result<(), FieldError> {
        match &self.frame {
            None => Err(FieldError::new(
                key,
                "names a frame node but the participant has no [frame] section",
            )),
            Some(f) if f.node.iter().any(|n| n.id == id) => Ok(()),
            Some(f) => {
                let ids: Vec<u32> = f.node.iter().map(|n| n.id).take(20).collect();
                Err(FieldError::new(
                    key,
                    format!("frame node {id} does not exist; node ids include {ids:?}"),
                ))
            }
        }
    }

    fn check_point(&self, key: &str, name: &str) -> Result<(), FieldError> {
        if self.point_names().contains(&name) {
            Ok(())
        } else {
            Err(FieldError::new(
                key,
                format!(
                    "`{name}` is not a point mass; point masses are: {:?}",
                    self.point_names()
                ),
            ))
        }
    }

    fn check_body(&self, key: &str, name: &str) -> Result<(), FieldError> {
        if self.body_names().contains(&name) {
            Ok(())
        } else {
            Err(FieldError::new(
                key,
                format!("`{name}` is not a body; bodies are: {:?}", self.body_names()),
            ))
        }
    }

    fn check_spring_end(&self, key: &str, name: &str, ground_allowed: bool) -> Result<(), FieldError> {
        if (ground_allowed && name == GROUND)
            || self.point_names().contains(&name)
            || self.body_names().contains(&name)
        {
            return Ok(());
        }
        let mut allowed: Vec<&str> = if ground_allowed { vec![GROUND] } else { vec![] };
        allowed.extend(self.point_names());
        allowed.extend(self.body_names());
        let hint = if name == GROUND {
            " (put `ground` on end `b`)"
        } else {
            ""
        };
        Err(FieldError::new(
            key,
            format!("`{name}` is unknown{hint}; allowed: {allowed:?}"),
        ))
    }

    fn check_load(&self, key: &str, l: &LoadConfig) -> Result<(), FieldError> {
        let target = l.target(key)?;
        match target {
            LoadTarget::Point(p) => self.check_point(&format!("{key}.point"), p)?,
            LoadTarget::Body(b) => self.check_body(&format!("{key}.body"), b)?,
            LoadTarget::Node(id) => self.check_node(&format!("{key}.node"), id)?,
        }
        let n = target.components();
        let history = l.history;
        let forbid = |name: &str, present: bool| {
            if present {
                Err(FieldError::new(
                    format!("{key}.{name}"),
                    format!(
                        "is not used by history = \"{}\"; remove it",
                        history_name(history)
                    ),
                ))
            } else {
                Ok(())
            }
        };
        let require = |name: &str, value: Option<f64>| {
            value.ok_or_else(|| {
                FieldError::new(
                    format!("{key}.{name}"),
                    format!("is required with history = \"{}\"", history_name(history)),
                )
            })
        };
        if history == LoadHistory::Table {
            forbid("value", l.value.is_some())?;
            forbid("start", l.start.is_some())?;
            forbid("end", l.end.is_some())?;
            if l.table.is_none() {
                return Err(FieldError::new(
                    format!("{key}.table"),
                    "is required with history = \"table\": a CSV file with columns t and the components",
                ));
            }
            return Ok(());
        }
        forbid("table", l.table.is_some())?;
        let value = l
            .value
            .as_ref()
            .ok_or_else(|| FieldError::new(format!("{key}.value"), format!("is required: {n} components")))?;
        if value.len() != n {
            return Err(FieldError::new(
                format!("{key}.value"),
                format!("must have {n} components for this target, got {}", value.len()),
            ));
        }
        check::finite(&format!("{key}.value"), value)?;
        match history {
            LoadHistory::Constant => {
                forbid("start", l.start.is_some())?;
                forbid("end", l.end.is_some())
            }
            LoadHistory::Step => {
                forbid("end", l.end.is_some())?;
                let start = require("start", l.start)?;
                check::finite(&format!("{key}.start"), &[start])
            }
            LoadHistory::Ramp => {
                let start = require("start", l.start)?;
                let end = require("end", l.end)?;
                check::finite(&format!("{key}.start"), &[start])?;
                if end.is_finite() && end > start {
                    Ok(())
                } else {
                    Err(FieldError::new(
                        format!("{key}.end"),
                        format!("must be a finite time > start = {start}, got {end}"),
                    ))
                }
            }
            LoadHistory::Table => Ok(()),
        }
    }
}

impl BodyConfig {
    fn validate(&self, key: &str, names: &mut BTreeSet<String>) -> Result<(), FieldError> {
        check_name(&format!("{key}.name"), &self.name, names)?;
        let q = self.orientation;
        check::finite(&format!("{key}.orientation"), &q)?;
        let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        if (norm - 1.0).abs() > 1e-6 {
            return Err(FieldError::new(
                format!("{key}.orientation"),
                format!("must be a unit quaternion [w, x, y, z] (norm 1 ± 1e-6), got norm {norm}"),
            ));
        }
        check::finite(&format!("{key}.velocity"), &self.velocity)?;
        check::finite(&format!("{key}.angular_velocity"), &self.angular_velocity)?;
        let i = &self.inertia;
        let ik = format!("{key}.inertia");
        let given = [
            i.box_size.is_some(),
            i.tensor.is_some(),
            i.particles.is_some(),
            i.mesh.is_some(),
        ];
        if given.iter().filter(|g| **g).count() != 1 {
            return Err(FieldError::new(
                ik,
                "must give exactly one of `box = [lx, ly, lz]`, `tensor = [[..], [..], [..]]`, `particles = [[x, y, z], ..]` with `particle_mass`, or `mesh = { file = \"….stl\" }` with `density`",
            ));
        }
        if i.density.is_some() && i.mesh.is_none() {
            return Err(FieldError::new(
                format!("{ik}.density"),
                "is only used with `mesh`",
            ));
        }
        if let Some(m) = &i.mesh {
            m.validate(&format!("{ik}.mesh"))?;
            let density = i
                .density
                .ok_or_else(|| FieldError::new(format!("{ik}.density"), "is required with `mesh` [kg/m³]"))?;
            check::positive(&format!("{ik}.density"), density)?;
            if i.particle_mass.is_some() {
                return Err(FieldError::new(
                    format!("{ik}.particle_mass"),
                    "is only used with `particles`",
                ));
            }
            return self.refuse_mass_and_centre(key, "mesh", "the mesh (and `density`)");
        }
        if let Some(particles) = &i.particles {
            let pm = i.particle_mass.ok_or_else(|| {
                FieldError::new(format!("{ik}.particle_mass"), "is required with `particles`")
            })?;
            check::positive(&format!("{ik}.particle_mass"), pm)?;
            if particles.len() < 3 {
                return Err(FieldError::new(
                    format!("{ik}.particles"),
                    format!(
                        "needs at least 3 particles not on one line, got {}",
                        particles.len()
                    ),
                ));
            }
            for (j, p) in particles.iter().enumerate() {
                check::finite(&format!("{ik}.particles[{j}]"), p)?;
            }
            return self.refuse_mass_and_centre(key, "particles", "the particles");
        }
        if i.particle_mass.is_some() {
            return Err(FieldError::new(
                format!("{ik}.particle_mass"),
                "is only used with `particles`",
            ));
        }
        let mass = self.mass.ok_or_else(|| {
            FieldError::new(
                format!("{key}.mass"),
                "is required with `inertia.box` / `inertia.tensor`",
            )
        })?;
        check::positive(&format!("{key}.mass"), mass)?;
        let centre = self.centre.ok_or_else(|| {
            FieldError::new(
                format!("{key}.centre"),
                "is required with `inertia.box` / `inertia.tensor`",
            )
        })?;
        check::finite(&format!("{key}.centre"), &centre)?;
        if let Some(b) = i.box_size {
            for (j, l) in b.iter().enumerate() {
                check::positive(&format!("{ik}.box[{j}]"), *l)?;
            }
        }
        if let Some(t) = &i.tensor {
            check_inertia_tensor(&format!("{ik}.tensor"), t)?;
        }
        Ok(())
    }
}

impl BodyConfig {
    /// `mass` and `centre` must be omitted with `inertia.{what}`: they come from `from`.
    fn refuse_mass_and_centre(&self, key: &str, what: &str, from: &str) -> Result<(), FieldError> {
        for (name, given) in [("mass", self.mass.is_some()), ("centre", self.centre.is_some())] {
            if given {
                return Err(FieldError::new(
                    format!("{key}.{name}"),
                    format!("must be omitted with `inertia.{what}`: the {name} comes from {from}"),
                ));
            }
        }
        Ok(())
    }

    /// Reads the body's `inertia.mesh` (if any) relative to `dir` (the case file's folder) and
    /// keeps its mass properties; `key` is the body's dotted path. Errors are at
    /// `….inertia.mesh.file` and name the file.
    pub fn load_mesh(&mut self, dir: &Path, key: &str) -> Result<(), FieldError> {
        let i = &mut self.inertia;
        if let (Some(m), Some(density)) = (&i.mesh, i.density) {
            let placed = m.load(dir, &format!("{key}.inertia.mesh"))?;
            i.mesh_properties = Some(placed.mass_properties(density));
        }
        Ok(())
    }
}

/// An inertia tensor must be finite, symmetric and positive definite (Sylvester's criterion).
pub fn check_inertia_tensor(key: &str, t: &[[f64; 3]; 3]) -> Result<(), FieldError> {
    for row in t {
        check::finite(key, row)?;
    }
    let scale = t.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        if (t[r][c] - t[c][r]).abs() > 1e-12 * scale {
            return Err(FieldError::new(
                key,
                format!(
                    "must be symmetric, but [{r}][{c}] = {} and [{c}][{r}] = {}",
                    t[r][c], t[c][r]
                ),
            ));
        }
    }
    let m1 = t[0][0];
    let m2 = t[0][0] * t[1][1] - t[0][1] * t[1][0];
    let m3 = t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1])
        - t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0])
        + t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0]);
    let tiny = 1e-12;
    if m1 > tiny * scale && m2 > tiny * scale * scale && m3 > tiny * scale * scale * scale {
        Ok(())
    } else {
        Err(FieldError::new(
            key,
            format!(
                "must be positive definite (leading minors {m1:e}, {m2:e}, {m3:e} must all be > 0): {t:?}"
            ),
        ))
    }
}

/// Point-mass and body names share one namespace and `ground` is reserved.
fn check_name(key: &str, name: &str, names: &mut BTreeSet<String>) -> Result<(), FieldError> {
    if name.trim().is_empty() || name == GROUND || name.contains('/') {
        return Err(FieldError::new(
            key,
            format!("`{name}` is not allowed: names must be non-empty, not `ground`, and without `/`"),
        ));
    }
    if !names.insert(name.to_string()) {
        return Err(FieldError::new(
            key,
            format!("`{name}` is used twice; point masses and bodies of a participant need distinct names"),
        ));
    }
    Ok(())
}

fn history_name(h: LoadHistory) -> &'static str {
    match h {
        LoadHistory::Constant => "constant",
        LoadHistory::Step => "step",
        LoadHistory::Ramp => "ramp",
        LoadHistory::Table => "table",
    }
}
