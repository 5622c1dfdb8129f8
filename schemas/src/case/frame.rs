//! `[structure.NAME.frame]`: an ASI-Gauss framed structure (S2 §3).
//!
//! ```toml
//! [structure.bridge.frame]
//! time_step = 1.0e-4                 # Newmark Δt [s]
//! gravity = [0.0, 0.0, -9.81]        # [m/s²], applied to the lumped masses
//! geometry = "corotational"          # optional: or "linear" (first order: small displacements)
//!
//! [structure.bridge.frame.material]
//! young_modulus = 2.0e11             # E [Pa]
//! poisson = 0.3
//! density = 7850.0                   # [kg/m³]
//! yield_stress = 2.35e8              # [Pa]; fully plastic section forces come from it
//! fracture_curvature = [0.05, 0.05]  # optional, S2-17: critical curvatures about local y, z [1/m]
//! fracture_axial_strain = 0.1        # optional, S2-17
//! fracture_shear_strain = [0.1, 0.1] # optional, S2-17: critical shear strains in local y, z
//!
//! [[structure.bridge.frame.section]]
//! name = "column"
//! kind = "rectangle"                 # width along local y, depth along local z
//! width = 0.1
//! depth = 0.15
//! yield_function = "rectangle"       # optional: "rectangle" (default), "i_section", "quadratic"
//!
//! [[structure.bridge.frame.section]]
//! name = "pipe"
//! kind = "general"                   # every property given
//! area = 1.0e-3
//! iy = 1.0e-6
//! iz = 1.0e-6
//! j = 2.0e-6
//! shear_area_y = 5.0e-4
//! shear_area_z = 5.0e-4
//! plastic_modulus_y = 2.0e-5
//! plastic_modulus_z = 2.0e-5
//! width = 0.05                       # projected width for drag
//!
//! [[structure.bridge.frame.node]]
//! id = 1
//! position = [0.0, 0.0, 0.0]
//!
//! [[structure.bridge.frame.member]]
//! nodes = [1, 2]
//! section = "column"
//! orientation = [0.0, 1.0, 0.0]      # optional: direction of the local y axis
//!
//! [[structure.bridge.frame.support]]
//! node = 1
//! fixed = ["x", "y", "z", "rx", "ry", "rz"]
//!
//! [structure.bridge.frame.contact]    # optional: penalty contact
//! stiffness = 1.0e7                  # [N/m] per particle pair
//! damping_ratio = 0.2                # optional, share of critical (default 0)
//! members = true                     # optional: members touch each other (default true)
//!
//! [structure.bridge.frame.damping]    # optional: Rayleigh C = a0 M + a1 K (tangent K)
//! frequencies = [2.0, 20.0]          # [Hz] … with the damping ratios wanted there,
//! ratios = [0.05, 0.05]              # or mass = a0 [1/s] and/or stiffness = a1 [s]
//!
//! [[structure.bridge.frame.wall]]     # optional, needs [contact]
//! point = [0.0, 0.0, 0.0]
//! normal = [0.0, 0.0, 1.0]
//! ```

use super::error::check;
use super::key_reference::one_of;
use super::FieldError;
use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// The six degrees of freedom of a frame node, as written in `fixed`.
pub const DOF_NAMES: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// `[structure.NAME.frame]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrameConfig {
    /// Newmark time step [s].
    pub time_step: f64,
    /// Gravitational acceleration [m/s²], global axes.
    pub gravity: [f64; 3],
    /// The material of every member.
    pub material: MaterialConfig,
    /// Cross-sections, named for the members.
    #[serde(default)]
    pub section: Vec<SectionConfig>,
    /// Nodes, by id.
    #[serde(default)]
    pub node: Vec<NodeConfig>,
    /// Members between two nodes.
    #[serde(default)]
    pub member: Vec<MemberConfig>,
    /// Fixed degrees of freedom of nodes.
    #[serde(default)]
    pub support: Vec<SupportConfig>,
    /// Penalty contact between members and with walls; absent: no contact.
    #[serde(default)]
    pub contact: Option<ContactConfig>,
    /// Rigid planes the members stay on one side of (needs `contact`).
    #[serde(default)]
    pub wall: Vec<WallConfig>,
    /// Equilibrium iterations [–]: absent, one linear solve per step, the unbalanced force
    /// carried into the next step (ASI-Gauss as Isobe runs it; fast, needs a short Δt when
    /// hinges form or members spin); present, each step is corrected until the unbalanced force
    /// falls below this fraction of its first value (slower; keeps energy in large, fast
    /// rotations).
    #[serde(default)]
    pub equilibrium_tolerance: Option<f64>,
    /// Rayleigh damping `C = a0 M + a1 K` (K the tangent stiffness); absent: none.
    #[serde(default)]
    pub damping: Option<DampingConfig>,
    /// Element kinematics: co-rotational (large displacements and rotations, the default) or
    /// linear (first order, for checks against hand calculations).
    #[serde(default)]
    pub geometry: Geometry,
}

/// `geometry` of a frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Geometry {
    /// Co-rotational (updated-Lagrangian) elements: large displacements and rotations.
    #[default]
    Corotational,
    /// First order: the elements' strains from the displacements and rotations in their
    /// undeformed axes, no geometric stiffness (small displacements, no P-Δ).
    Linear,
}

/// `[structure.NAME.frame.damping]`: Rayleigh damping, by its coefficients (`mass` = a0 [1/s],
/// `stiffness` = a1 [s], either may be left out) or by two frequencies [Hz] and the damping ratios
/// wanted at them (`frequencies`, `ratios`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DampingConfig {
    /// a0, the mass-proportional coefficient [1/s] (not with `frequencies`). Range: ≥ 0.
    #[serde(default)]
    pub mass: Option<f64>,
    /// a1, the stiffness-proportional coefficient [s] (not with `frequencies`). Range: ≥ 0.
    #[serde(default)]
    pub stiffness: Option<f64>,
    /// Two different frequencies [Hz] at which `ratios` are wanted. Range: > 0.
    #[serde(default)]
    pub frequencies: Option<[f64; 2]>,
    /// The damping ratios wanted at `frequencies` [–]. Range: ≥ 0, and such that a0, a1 ≥ 0.
    #[serde(default)]
    pub ratios: Option<[f64; 2]>,
}

impl DampingConfig {
    /// `(a0, a1)` from the coefficients or from ζᵢ = a0/(2ωᵢ) + a1 ωᵢ/2 at the two frequencies;
    /// `key` is the table's path for errors.
    pub fn coefficients(&self, key: &str) -> Result<(f64, f64), FieldError> {
        match (self.frequencies, self.ratios) {
            (Some(f), Some(z)) => {
                if self.mass.is_some() || self.stiffness.is_some() {
                    return Err(FieldError::new(
                        key,
                        "give either mass and stiffness, or frequencies and ratios, not both",
                    ));
                }
                for (i, v) in f.iter().enumerate() {
                    check::positive(&format!("{key}.frequencies[{i}]"), *v)?;
                }
                for (i, v) in z.iter().enumerate() {
                    check::non_negative(&format!("{key}.ratios[{i}]"), *v)?;
                }
                if f[0] == f[1] {
                    return Err(FieldError::new(
                        format!("{key}.frequencies"),
                        "the two frequencies must differ",
                    ));
                }
                let w = f.map(|f| 2.0 * std::f64::consts::PI * f);
                // ζ1 = a0/(2ω1) + a1 ω1/2, ζ2 = a0/(2ω2) + a1 ω2/2
                let a1 = 2.0 * (z[1] * w[1] - z[0] * w[0]) / (w[1] * w[1] - w[0] * w[0]);
                let a0 = 2.0 * z[0] * w[0] - a1 * w[0] * w[0];
                if a0 < 0.0 || a1 < 0.0 {
                    return Err(FieldError::new(
                        format!("{key}.ratios"),
                        format!(
                            "these ratios at these frequencies need a negative coefficient (a0 = {a0:.4e}, \
                             a1 = {a1:.4e}); choose ratios that Rayleigh damping can give"
                        ),
                    ));
                }
                Ok((a0, a1))
            }
            (None, None) => {
                let a0 = self.mass.unwrap_or(0.0);
                let a1 = self.stiffness.unwrap_or(0.0);
                check::non_negative(&format!("{key}.mass"), a0)?;
                check::non_negative(&format!("{key}.stiffness"), a1)?;
                Ok((a0, a1))
            }
            _ => Err(FieldError::new(
                key,
                "frequencies and ratios go together: give both or neither",
            )),
        }
    }
}

/// `[structure.NAME.frame.contact]`: members and walls meet through particles along the members
/// (S2 §3(2)) pushed apart by a penalty spring and dashpot.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactConfig {
    /// Penalty stiffness per particle pair [N/m].
    pub stiffness: f64,
    /// Damping of the contact spring as a share of critical [–]. Range: [0, 1].
    #[serde(default)]
    pub damping_ratio: f64,
    /// Whether members touch each other (walls always touch members).
    #[serde(default = "yes")]
    pub members: bool,
}

fn yes() -> bool {
    true
}

/// `[[structure.NAME.frame.wall]]`: a rigid plane; members stay on the side its normal points to.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallConfig {
    /// A point of the plane [m].
    pub point: [f64; 3],
    /// Normal pointing to the side where the frame is [–] (any length but zero).
    pub normal: [f64; 3],
}

/// `[structure.NAME.frame.material]`: one elastic–perfectly-plastic material for every member.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialConfig {
    /// Young's modulus E [Pa].
    pub young_modulus: f64,
    /// Poisson's ratio ν [–]; G = E / (2 (1 + ν)).
    pub poisson: f64,
    /// Density [kg/m³].
    pub density: f64,
    /// Yield stress σ_y [Pa].
    pub yield_stress: f64,
    /// S2-17 critical curvatures about local y and z [1/m]; absent: that term is not checked.
    #[serde(default)]
    pub fracture_curvature: Option<[f64; 2]>,
    /// S2-17 critical axial strain [–]; absent: not checked.
    #[serde(default)]
    pub fracture_axial_strain: Option<f64>,
    /// S2-17 critical shear strains in local y and z [–]; absent: not checked.
    #[serde(default)]
    pub fracture_shear_strain: Option<[f64; 2]>,
}

/// `[[structure.NAME.frame.section]]`: a cross-section, by shape or by its properties.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SectionConfig {
    /// The section's name, unique in the frame; members name it.
    pub name: String,
    /// `"rectangle"` (from `width` and `depth`) or `"general"` (every property given).
    #[schemars(schema_with = "section_kinds")]
    pub kind: String,
    /// Extent along local y [m] (rectangle); projected width for drag (both kinds).
    #[serde(default)]
    pub width: Option<f64>,
    /// Extent along local z [m] (rectangle only).
    #[serde(default)]
    pub depth: Option<f64>,
    /// Area [m²] (general).
    #[serde(default)]
    pub area: Option<f64>,
    /// Second moment about local y [m⁴] (general).
    #[serde(default)]
    pub iy: Option<f64>,
    /// Second moment about local z [m⁴] (general).
    #[serde(default)]
    pub iz: Option<f64>,
    /// Torsion constant [m⁴] (general).
    #[serde(default)]
    pub j: Option<f64>,
    /// Shear area for shear along local y [m²] (general).
    #[serde(default)]
    pub shear_area_y: Option<f64>,
    /// Shear area for shear along local z [m²] (general).
    #[serde(default)]
    pub shear_area_z: Option<f64>,
    /// Plastic section modulus for bending about local y [m³] (general).
    #[serde(default)]
    pub plastic_modulus_y: Option<f64>,
    /// Plastic section modulus for bending about local z [m³] (general).
    #[serde(default)]
    pub plastic_modulus_z: Option<f64>,
    /// Full-plastic interaction of N, My, Mz (one of [`YIELD_FUNCTIONS`]; default `"rectangle"`):
    /// `"rectangle"`: the solid rectangle's exact `|M|/Mp + (N/Np)² = 1` about either axis, biaxial
    /// `(|my|^1.7 + |mz|^1.7)^(1/1.7) + n² = 1`; `"i_section"`: wide-flange I section with its web
    /// along local z, `My/Mpy ≤ 1.18 (1 − |n|)`, `Mz/Mpz ≤ 1.19 (1 − n²)`, biaxial with the
    /// exponents 2 and max(1, 5|n|) of EN 1993-1-1 §6.2.9.1; `"quadratic"`: `n² + my² + mz² = 1`.
    #[serde(default)]
    #[schemars(schema_with = "yield_functions")]
    pub yield_function: Option<String>,
}

/// The schema of `kind`: one of [`SECTION_KINDS`].
fn section_kinds(_: &mut SchemaGenerator) -> Schema {
    one_of(&SECTION_KINDS)
}

/// The schema of `yield_function`: one of [`YIELD_FUNCTIONS`].
fn yield_functions(_: &mut SchemaGenerator) -> Schema {
    one_of(&YIELD_FUNCTIONS)
}

/// The schema of `fixed`: any of [`DOF_NAMES`].
fn dof_names(_: &mut SchemaGenerator) -> Schema {
    schemars::json_schema!({ "type": "array", "items": one_of(&DOF_NAMES) })
}

/// The yield functions a section's `yield_function` may name.
pub const YIELD_FUNCTIONS: [&str; 3] = ["rectangle", "i_section", "quadratic"];

/// `[[structure.NAME.frame.node]]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NodeConfig {
    /// The node's id, unique in the frame; members, supports, loads and histories name it.
    pub id: u32,
    /// Position [m].
    pub position: [f64; 3],
}

/// `[[structure.NAME.frame.member]]`: one member, modelled as two ASI-Gauss elements.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MemberConfig {
    /// Ids of its end nodes.
    pub nodes: [u32; 2],
    /// Name of its section.
    pub section: String,
    /// Direction of the member's local y axis (projected normal to the member) [–]. Default:
    /// horizontal, global z × member axis; for a vertical member, global y.
    #[serde(default)]
    pub orientation: Option<[f64; 3]>,
}

/// `[[structure.NAME.frame.support]]`: fixed degrees of freedom of one node.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportConfig {
    /// The id of the node held.
    pub node: u32,
    /// Any of `"x"`, `"y"`, `"z"` (translations) and `"rx"`, `"ry"`, `"rz"` (rotations).
    #[schemars(schema_with = "dof_names")]
    pub fixed: Vec<String>,
}

/// The section kinds that `kind` may name.
pub const SECTION_KINDS: [&str; 2] = ["rectangle", "general"];

impl SectionConfig {
    /// Checks the keys its kind needs; `key` is the section's path, e.g. `structure.a.frame.section[0]`.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        if self.name.trim().is_empty() {
            return Err(FieldError::new(format!("{key}.name"), "must not be empty"));
        }
        if let Some(f) = &self.yield_function {
            if !YIELD_FUNCTIONS.contains(&f.as_str()) {
                return Err(FieldError::new(
                    format!("{key}.yield_function"),
                    format!(
                        "unknown yield function `{f}`; allowed: {}",
                        YIELD_FUNCTIONS.join(", ")
                    ),
                ));
            }
        }
        let general = [
            ("area", self.area),
            ("iy", self.iy),
            ("iz", self.iz),
            ("j", self.j),
            ("shear_area_y", self.shear_area_y),
            ("shear_area_z", self.shear_area_z),
            ("plastic_modulus_y", self.plastic_modulus_y),
            ("plastic_modulus_z", self.plastic_modulus_z),
        ];
        match self.kind.as_str() {
            "rectangle" => {
                for (name, value) in [("width", self.width), ("depth", self.depth)] {
                    let value = value.ok_or_else(|| {
                        FieldError::new(format!("{key}.{name}"), "is required for kind = \"rectangle\"")
                    })?;
                    check::positive(&format!("{key}.{name}"), value)?;
                }
                if let Some((name, _)) = general.iter().find(|(_, v)| v.is_some()) {
                    return Err(FieldError::new(
                        format!("{key}.{name}"),
                        "is not used by kind = \"rectangle\" (it is computed from width and depth); \
                         use kind = \"general\" to give it",
                    ));
                }
                Ok(())
            }
            "general" => {
                for (name, value) in general {
                    let value = value.ok_or_else(|| {
                        FieldError::new(format!("{key}.{name}"), "is required for kind = \"general\"")
                    })?;
                    check::positive(&format!("{key}.{name}"), value)?;
                }
                if let Some(width) = self.width {
                    check::positive(&format!("{key}.width"), width)?;
                }
                if self.depth.is_some() {
                    return Err(FieldError::new(
                        format!("{key}.depth"),
                        "is not used by kind = \"general\"; give iy, iz, … instead",
                    ));
                }
                Ok(())
            }
            other => Err(FieldError::new(
                format!("{key}.kind"),
                format!(
                    "unknown section kind `{other}`; allowed: {}",
                    SECTION_KINDS.join(", ")
                ),
            )),
        }
    }
}

impl MaterialConfig {
    /// Checks every material constant; `key` is the material's path.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        check::positive(&format!("{key}.young_modulus"), self.young_modulus)?;
        if !(self.poisson.is_finite() && self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(FieldError::new(
                format!("{key}.poisson"),
                format!("must be in (-1, 0.5), got {}", self.poisson),
            ));
        }
        check::positive(&format!("{key}.density"), self.density)?;
        check::positive(&format!("{key}.yield_stress"), self.yield_stress)?;
        if let Some(c) = self.fracture_curvature {
            for v in c {
                check::positive(&format!("{key}.fracture_curvature"), v)?;
            }
        }
        if let Some(v) = self.fracture_axial_strain {
            check::positive(&format!("{key}.fracture_axial_strain"), v)?;
        }
        if let Some(c) = self.fracture_shear_strain {
            for v in c {
                check::positive(&format!("{key}.fracture_shear_strain"), v)?;
            }
        }
        Ok(())
    }
}

impl FrameConfig {
    /// Checks every key and the topology; `key` is the table's path, e.g. `structure.bridge.frame`.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        check::positive(&format!("{key}.time_step"), self.time_step)?;
        check::finite(&format!("{key}.gravity"), &self.gravity)?;
        if let Some(d) = &self.damping {
            d.coefficients(&format!("{key}.damping"))?;
        }
        if let Some(tolerance) = self.equilibrium_tolerance {
            check::within(&format!("{key}.equilibrium_tolerance"), tolerance, 1e-14, 0.5)?;
        }
        self.material.validate(&format!("{key}.material"))?;

        let mut sections = BTreeSet::new();
        for (i, s) in self.section.iter().enumerate() {
            let skey = format!("{key}.section[{i}]");
            s.validate(&skey)?;
            if !sections.insert(s.name.as_str()) {
                return Err(FieldError::new(
                    format!("{skey}.name"),
                    format!("section name `{}` is used twice; names must be unique", s.name),
                ));
            }
        }

        if self.node.is_empty() {
            return Err(FieldError::new(
                format!("{key}.node"),
                "the frame has no node: add [[…frame.node]] tables",
            ));
        }
        let mut positions = BTreeMap::new();
        for (i, n) in self.node.iter().enumerate() {
            let nkey = format!("{key}.node[{i}]");
            check::finite(&format!("{nkey}.position"), &n.position)?;
            if positions.insert(n.id, n.position).is_some() {
                return Err(FieldError::new(
                    format!("{nkey}.id"),
                    format!("node id {} is used twice; ids must be unique", n.id),
                ));
            }
        }

        if self.member.is_empty() {
            return Err(FieldError::new(
                format!("{key}.member"),
                "the frame has no member: add [[…frame.member]] tables",
            ));
        }
        let mut used = BTreeSet::new();
        for (i, m) in self.member.iter().enumerate() {
            let mkey = format!("{key}.member[{i}]");
            let mut ends = [[0.0; 3]; 2];
            for (end, id) in m.nodes.iter().enumerate() {
                ends[end] = *positions.get(id).ok_or_else(|| {
                    FieldError::new(
                        format!("{mkey}.nodes"),
                        format!("node id {id} is not defined in {key}.node"),
                    )
                })?;
                used.insert(*id);
            }
            if !sections.contains(m.section.as_str()) {
                return Err(FieldError::new(
                    format!("{mkey}.section"),
                    format!(
                        "names no section; sections are: {}",
                        sections.iter().copied().collect::<Vec<_>>().join(", ")
                    ),
                ));
            }
            let axis = sub(ends[1], ends[0]);
            let length = norm(axis);
            if length <= 0.0 {
                return Err(FieldError::new(
                    format!("{mkey}.nodes"),
                    format!(
                        "member from node {} to node {} has zero length",
                        m.nodes[0], m.nodes[1]
                    ),
                ));
            }
            if let Some(o) = m.orientation {
                let okey = format!("{mkey}.orientation");
                check::finite(&okey, &o)?;
                let across = norm(cross(axis, o));
                if across <= 1e-6 * length * norm(o) {
                    return Err(FieldError::new(
                        okey,
                        "must be a nonzero vector not parallel to the member (it gives the local y axis)",
                    ));
                }
            }
        }
        if let Some(n) = self.node.iter().find(|n| !used.contains(&n.id)) {
            return Err(FieldError::new(
                format!("{key}.node"),
                format!("node id {} belongs to no member; remove it or connect it", n.id),
            ));
        }

        if let Some(c) = &self.contact {
            check::positive(&format!("{key}.contact.stiffness"), c.stiffness)?;
            check::within(&format!("{key}.contact.damping_ratio"), c.damping_ratio, 0.0, 1.0)?;
        }
        for (i, w) in self.wall.iter().enumerate() {
            let wkey = format!("{key}.wall[{i}]");
            if self.contact.is_none() {
                return Err(FieldError::new(
                    wkey,
                    format!("a wall needs a [{key}.contact] table (its penalty stiffness)"),
                ));
            }
            check::finite(&format!("{wkey}.point"), &w.point)?;
            check::finite(&format!("{wkey}.normal"), &w.normal)?;
            if norm(w.normal) == 0.0 {
                return Err(FieldError::new(
                    format!("{wkey}.normal"),
                    "must be a nonzero vector",
                ));
            }
        }
        for (i, s) in self.support.iter().enumerate() {
            let skey = format!("{key}.support[{i}]");
            if !positions.contains_key(&s.node) {
                return Err(FieldError::new(
                    format!("{skey}.node"),
                    format!("node id {} is not defined in {key}.node", s.node),
                ));
            }
            for d in &s.fixed {
                if !DOF_NAMES.contains(&d.as_str()) {
                    return Err(FieldError::new(
                        format!("{skey}.fixed"),
                        format!(
                            "unknown degree of freedom `{d}`; allowed: {}",
                            DOF_NAMES.join(", ")
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
