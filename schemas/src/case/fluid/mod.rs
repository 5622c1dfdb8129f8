//! `[fluid.NAME]`: a fluid participant solved by E-MPS (Saitoh & Akitomo, S1-3 … S1-16) or by
//! ISPH (Ohinata et al., S2-3 … S2-13), picked by `method`.
//!
//! ```toml
//! [fluid.tank]
//! method = "emps"           # or "isph" (then optionally [fluid.tank.isph], see IsphConfig)
//! backend = "cpu"           # or "gpu": E-MPS on a Vulkan GPU (see FluidConfig::gpu_support)
//! spacing = 0.01            # Δs [m]
//! time_step = 5e-4          # Δt [s], checked against the acoustic and viscous limits
//! sound_speed = 12.1        # c [m/s]; default u_max / 0.2 with u_max = √(2gH) (S1-16); E-MPS
//!                           # only: with "isph" it is left unused and the run says so
//! artificial_viscosity = 0.0 # α of Monaghan's artificial viscosity (E-MPS only, as sound_speed; default off)
//! viscosity_term = false    # switch ν⟨∇²u⟩ off when ν is far below the numerical dissipation
//! output_interval = 0.05
//! surface_mesh = true       # also a free-surface mesh (VTP) per frame; default false
//! tank = { min = [0, 0, 0], max = [0.6, 0.45, 0.3] }
//! [[fluid.tank.block]]      # water, filled on the lattice
//! min = [0, 0, 0]
//! max = [0.3, 0.3, 0.3]
//! [[fluid.tank.gate]]       # partition board, removed at t = 0
//! min = [0.3, 0, 0]
//! max = [0.33, 0.3, 0.3]
//! [[fluid.tank.probe]]
//! name = "front"
//! kind = "surge-front"
//! [[fluid.tank.probe]]      # a pressure sensor on a wall or obstacle face
//! name = "P1"
//! kind = "wall-pressure"
//! position = [0.6, 0.15, 0.02]
//! normal = "-x"             # the face's outward normal, into the water
//! diameter = 0.02
//! window = 0.005            # box filter [s]; default none
//! ```
//!
//! Extents off the lattice (tank, blocks, gates, walls, bodies) are rounded to the nearest
//! lattice face with a message. Run control: `max_removed_fraction` (default 0.01) of the fluid
//! may leave over an open top before the run stops; `progress_interval` (default 10 s of wall
//! time) between progress lines.
//!
//! Open channels add fixed solid boxes (`[[fluid.NAME.wall]]`, `min`/`max`: piers, levees) and
//! inflow / outflow boundaries (`[fluid.NAME.inflow]`, `[fluid.NAME.outflow]`: see
//! [`InflowConfig`], [`OutflowConfig`]); with an inflow, u_max = √(u_in² + 2gH) in S1-16.

use super::error::check;
use super::FieldError;
use serde::Deserialize;

/// Mach number used for the default sound speed (S1-16: `c = u_max / 0.2`).
/// The largest f32 rounding of a position the GPU path accepts, in spacings: 1e-3 Δs is 5 % of
/// a step's largest move at c Δt/Δs ≈ 0.5 and u ≤ c/10 (S1-16), and allows tanks up to
/// 16 777 spacings from the origin (16.7 km at Δs = 1 m).
pub const GPU_MAX_ROUNDING: f64 = 1e-3;

pub const MACH: f64 = 0.2;

/// Largest acoustic Courant number `c Δt / Δs`. The E-MPS update is symplectic Euler on a
/// lattice whose equation of state makes it a spring chain with wave speed c; its highest
/// mode has ω = 2c/Δs and symplectic Euler is stable only for ωΔt < 2, i.e. cΔt/Δs < 1.
pub const MAX_ACOUSTIC_COURANT: f64 = 1.0;

/// Largest viscous number `ν Δt / Δs²`: explicit diffusion in d = 3 is stable for
/// `ν Δt / Δs² ≤ 1/(2d)`.
pub const MAX_VISCOUS_NUMBER: f64 = 1.0 / 6.0;

/// Fewest wall layers: two pressure layers (a fluid particle half a spacing off the wall reaches
/// 2.1 Δs, i.e. wall centres 0.5 Δs and 1.5 Δs deep) plus dummy layers until the first wall
/// layer's number density (r_e = 3.1 Δs) is complete: centres down to 3.5 Δs, so four layers.
pub const MIN_WALL_LAYERS: u32 = 4;

/// Most particles a case may create (a guard against a spacing typo filling the memory).
pub const MAX_PARTICLES: f64 = 5.0e7;

/// An axis-aligned box `[min, max]` [m].
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Aabb {
    pub min: [f64; 3],
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

/// `tank`: the inner faces of the walls; walls are `wall_layers` particle layers outside it.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TankConfig {
    pub min: [f64; 3],
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

/// `[[fluid.NAME.body]]`: a rigid box made of `Body` particles. In a fluid-only run it is held
/// fixed (an obstacle); coupled scenes move it with the structure's kinematics.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyConfig {
    pub name: String,
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// What a probe measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProbeKind {
    /// Height of the water surface above the tank floor at `position = [x, y]`: the top of the
    /// water column within Δs horizontally that stands on the floor (or on a wall block), plus
    /// Δs/2; spray and drops not connected to that column are left out.
    #[default]
    WaterHeight,
    /// Pressure at `position = [x, y, z]`: the mean over fluid, wall and body particles within
    /// r_e,grad = 2.1 Δs, weighted by w(r) of S1-6.
    Pressure,
    /// Surge front: how far the water reaches along `axis` ("x", "+x", "-x", …), plus Δs/2,
    /// measured from the tank face it starts at (`tank.min` for +, `tank.max` for −; spray
    /// excluded).
    SurgeFront,
    /// A pressure sensor mounted on a wall or obstacle face: a disc of `diameter` centred at
    /// `position` on the face whose outward normal (into the water) is `normal`; reads the
    /// normal force of the fluid on the wall particles behind the disc per unit area, optionally
    /// box-filtered over the last `window` seconds.
    WallPressure,
}

/// `[[fluid.NAME.probe]]`: one column of the probe CSV.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeConfig {
    pub name: String,
    pub kind: ProbeKind,
    /// `[x, y]` for water-height, `[x, y, z]` for pressure and wall-pressure, unused for
    /// surge-front.
    #[serde(default)]
    pub position: Vec<f64>,
    /// Axis and direction of a surge front: "x" or "+x" (default), "-x", "y", "+y", "-y", "z",
    /// "+z", "-z".
    #[serde(default)]
    pub axis: Option<String>,
    // Wall-pressure sensors (issue 15): face normal, disc diameter, filter window.
    /// Outward normal of the face the sensor is mounted on, pointing into the water: one of
    /// "+x", "-x", "+y", "-y", "+z", "-z" (walls and obstacles are axis-aligned boxes).
    #[serde(default)]
    pub normal: Option<String>,
    /// Diameter of the sensor's disc [m].
    #[serde(default)]
    pub diameter: Option<f64>,
    /// Box filter [s]: the reading is the mean over every step of the last `window` seconds
    /// (an experiment's sensor rate / anti-alias filter); default: the instantaneous reading.
    #[serde(default)]
    pub window: Option<f64>,
}

/// An axis and a sign, parsed from "x", "+x", "-x", … (`None` for anything else).
pub fn signed_axis(s: &str) -> Option<(usize, f64)> {
    let (sign, axis) = match s.as_bytes().first() {
        Some(b'+') => (1.0, &s[1..]),
        Some(b'-') => (-1.0, &s[1..]),
        _ => (1.0, s),
    };
    let a = ["x", "y", "z"].iter().position(|&n| n == axis)?;
    Some((a, sign))
}

impl ProbeConfig {
    /// The surge-front axis as an index (0 = x).
    pub fn axis_index(&self) -> usize {
        self.axis_direction().0
    }

    /// The surge-front axis and its direction (+1 towards `tank.max`, −1 towards `tank.min`).
    pub fn axis_direction(&self) -> (usize, f64) {
        self.axis.as_deref().and_then(signed_axis).unwrap_or((0, 1.0))
    }

    /// A wall-pressure sensor's normal as axis and sign (validated: always present there).
    pub fn normal_direction(&self) -> (usize, f64) {
        self.normal.as_deref().and_then(signed_axis).unwrap_or((2, 1.0))
    }
}

/// Which fluid method steps a participant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FluidMethodName {
    /// Explicit MPS (seed 000): weakly compressible, Δt limited by the sound speed.
    #[default]
    Emps,
    /// Incompressible SPH (seed 003): a pressure Poisson equation every step, Δt free of c.
    Isph,
}

/// Where a fluid participant's step runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FluidBackend {
    /// The CPU (rayon threads): every feature.
    #[default]
    Cpu,
    /// A GPU through wgpu compute shaders (Vulkan): E-MPS of a fluid-only case; see
    /// [`FluidConfig::gpu_support`] for what it refuses.
    Gpu,
}

/// Largest advective Courant number `u_max Δt / Δs` of ISPH: a particle at u_max moves at most
/// 0.4 Δs per step, so a step's neighbour lists stay valid for its whole length and the
/// instability detector's 0.5 Δs per step is not reached by the predicted flow itself.
pub const MAX_ADVECTIVE_COURANT: f64 = 0.4;

/// How ISPH walls act on the velocity tangential to them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WallSlip {
    /// Slip rate 1.0 (S2, Table 1): walls take no part in the viscous term.
    #[default]
    FreeSlip,
    /// Walls and bodies enter the viscous term with their own velocity.
    NoSlip,
}

/// Which solver the ISPH pressure Poisson equation uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PpeSolver {
    /// Jacobi-preconditioned conjugate gradient on the neighbour list, warm-started from the last
    /// pressure (the default until the two-level one was measured faster, see the README).
    JacobiPcg,
    /// faer's sparse Cholesky factorisation of the assembled matrix, every step.
    FaerCholesky,
    /// Conjugate gradient preconditioned by symmetric Gauss–Seidel within fixed blocks of rows
    /// (block Jacobi between them), warm-started from the last pressure.
    SgsPcg,
    /// Conjugate gradient preconditioned by a two-level V(1,1) cycle: damped Jacobi smoothing and
    /// an exact coarse correction on aggregates of neighbour-search cells, warm-started from the
    /// last pressure (the default until the additive form was measured faster).
    TwoLevelPcg,
    /// Conjugate gradient preconditioned by Jacobi plus the same coarse correction, added
    /// (`D⁻¹ + P A_c⁻¹ Pᵀ`), warm-started from the last pressure: more iterations than the cycle,
    /// a third of its products with the matrix each (the fastest measured, before and after a dam
    /// break's impact: README section "ISPH: a two-level preconditioner for the PPE").
    #[default]
    AdditiveTwoLevelPcg,
}

/// The pressure gradient of ISPH's momentum equation (issue 12; see
/// `fluid_solver::isph::operators::pressure_gradient` for both equations and the measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PressureGradient {
    /// S2-8's difference form `Σ_j V (p_j − p_i) ∇W_ij` corrected by the moment matrix (Bonet &
    /// Lok 1999); bodies loaded by the face law of `fluid_solver::isph::pair_laws::body_faces`.
    #[default]
    CorrectedDifference,
    /// The uncorrected symmetric form `Σ_j V (p_i + p_j) ∇W_ij` (walls `V (2p_i + Δp_ij) ∇W_ij`),
    /// whose pair term is also the walls' load; with a body neighbour the pair term is the body's
    /// face-law share: momentum closes pair by pair. Accepted only with `influence_radius` in
    /// [`SYMMETRIC_SUPPORT`]; measured to hold the hydrostatic tank at 2.0 (README).
    Symmetric,
}

/// Particle shifting of ISPH (issue 12; `fluid_solver::isph::shifting` has the equation, the
/// free-surface and wall treatment and the measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shifting {
    /// Particles move with their velocity only.
    #[default]
    Off,
    /// Lind, Xu, Stansby & Rogers (2012): `δr = −D Σ_j V ∇W_ij` after each position update, with
    /// `D = A h |u|_max Δt` after Skillen et al. (2013) (A = `shifting_coefficient`); the water
    /// in a resolved body's support is not shifted. Smoothest with `pressure_gradient =
    /// "symmetric"` at `influence_radius = 2.0` (README).
    Lind,
}

/// `[fluid.NAME.isph]`: settings of the ISPH method (all optional).
///
/// ```toml
/// [fluid.tank.isph]
/// alpha_d = 5e-3            # α_d of S2-5 (density relaxation)
/// influence_radius = 2.4    # kernel support in spacings (S2, Table 1)
/// ppe_tolerance = 1e-6      # relative residual |r|/|b| the PPE must reach every step
/// ppe_max_iterations = 1000 # beyond this the run stops with the residual
/// ppe_solver = "additive-two-level-pcg" # or "two-level-pcg", "jacobi-pcg", "faer-cholesky", "sgs-pcg"
/// wall_slip = "free-slip"   # or "no-slip"
/// pressure_gradient = "corrected-difference" # or "symmetric" (with influence_radius = 2.0)
/// shifting = "off"          # or "lind" (particle shifting)
/// shifting_coefficient = 0.5 # A of D = A h |u|_max Δt (Skillen et al. 2013), with "lind"
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IsphConfig {
    #[serde(default = "default_alpha_d")]
    pub alpha_d: f64,
    #[serde(default = "default_influence_radius")]
    pub influence_radius: f64,
    #[serde(default = "default_ppe_tolerance")]
    pub ppe_tolerance: f64,
    #[serde(default = "default_ppe_max_iterations")]
    pub ppe_max_iterations: u32,
    #[serde(default)]
    pub ppe_solver: PpeSolver,
    #[serde(default)]
    pub wall_slip: WallSlip,
    #[serde(default)]
    pub pressure_gradient: PressureGradient,
    #[serde(default)]
    pub shifting: Shifting,
    #[serde(default = "default_shifting_coefficient")]
    pub shifting_coefficient: f64,
}

/// The kernel supports (spacings) at which `pressure_gradient = "symmetric"` is accepted: where
/// a column or a plane of the particle lattice sliding along itself is pushed back by the
/// symmetric form's zero-order term (both lattice sums κ ≥ 0.02 /Δs²,
/// `fluid-solver/tests/isph_lattice_modes.rs`; the tank held at 2.0, failed at 2.4 and 3.0).
pub const SYMMETRIC_SUPPORT: (f64, f64) = (1.95, 2.15);

impl Default for IsphConfig {
    fn default() -> IsphConfig {
        IsphConfig {
            alpha_d: default_alpha_d(),
            influence_radius: default_influence_radius(),
            ppe_tolerance: default_ppe_tolerance(),
            ppe_max_iterations: default_ppe_max_iterations(),
            ppe_solver: PpeSolver::default(),
            wall_slip: WallSlip::default(),
            pressure_gradient: PressureGradient::default(),
            shifting: Shifting::default(),
            shifting_coefficient: default_shifting_coefficient(),
        }
    }
}

fn default_alpha_d() -> f64 {
    5.0e-3
}
fn default_influence_radius() -> f64 {
    2.4
}
fn default_ppe_tolerance() -> f64 {
    1.0e-6
}
fn default_ppe_max_iterations() -> u32 {
    1000
}
/// A in `D = A h |u|_max Δt` (Skillen, Lind, Stansby & Rogers 2013, Comput. Methods Appl. Mech.
/// Engrg. 265, 163–173, who used A = 2 with each particle's own |u|): measured on the L/20 dam
/// break with the symmetric gradient at 2.0 Δs (README, "ISPH: shifting with the symmetric
/// gradient"), A = 2 and 6 were stopped by the detector (at 0.29 and 0.06 s), 1 and 0.5 ran to
/// 0.6 s with the same probe roughness; 0.5 keeps a margin of 4 from the first failure.
fn default_shifting_coefficient() -> f64 {
    0.5
}

/// Largest `shifting_coefficient`: the top of the range 1 … 6 Skillen et al. (2013) tried.
pub const MAX_SHIFTING_COEFFICIENT: f64 = 6.0;

impl IsphConfig {
    /// Checks every key; `key` is the section's dotted path.
    pub fn validate(&self, key: &str, wall_layers: u32) -> Result<(), FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        check::non_negative(&k("alpha_d"), self.alpha_d)?;
        if self.alpha_d > 1.0 {
            return Err(FieldError::new(
                k("alpha_d"),
                format!("must be in [0, 1], got {}", self.alpha_d),
            ));
        }
        let layers = f64::from(wall_layers);
        if !(self.influence_radius >= 1.5 && self.influence_radius <= layers - 0.5) {
            return Err(FieldError::new(
                k("influence_radius"),
                format!(
                    "must be in [1.5, wall_layers − 0.5 = {}] spacings (a fluid particle half a spacing off a wall must see only wall particles behind it), got {}",
                    layers - 0.5,
                    self.influence_radius
                ),
            ));
        }
        let (lo, hi) = SYMMETRIC_SUPPORT;
        if self.pressure_gradient == PressureGradient::Symmetric
            && !(self.influence_radius >= lo && self.influence_radius <= hi)
        {
            return Err(FieldError::new(
                k("influence_radius"),
                format!(
                    "must be in [{lo}, {hi}] spacings with pressure_gradient = \"symmetric\" (outside it a sliding column or plane of particles is not pushed back and a tank at rest comes apart: at S2's 2.4 the 1 s tank's edge columns rose at 0.12 m/s), got {}; set influence_radius = 2.0 or use pressure_gradient = \"corrected-difference\"",
                    self.influence_radius
                ),
            ));
        }
        if !(self.ppe_tolerance > 0.0 && self.ppe_tolerance < 1.0) {
            return Err(FieldError::new(
                k("ppe_tolerance"),
                format!("must be in (0, 1), got {}", self.ppe_tolerance),
            ));
        }
        if self.ppe_max_iterations == 0 {
            return Err(FieldError::new(k("ppe_max_iterations"), "must be at least 1"));
        }
        if !(self.shifting_coefficient > 0.0 && self.shifting_coefficient <= MAX_SHIFTING_COEFFICIENT) {
            return Err(FieldError::new(
                k("shifting_coefficient"),
                format!(
                    "must be in (0, {MAX_SHIFTING_COEFFICIENT}] (A of D = A h |u|_max Δt, Skillen et al. 2013), got {}",
                    self.shifting_coefficient
                ),
            ));
        }
        Ok(())
    }
}

/// Configuration of one fluid participant.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FluidConfig {
    /// The method: "emps" (default) or "isph".
    #[serde(default)]
    pub method: FluidMethodName,
    /// Where the step runs: "cpu" (default) or "gpu".
    #[serde(default)]
    pub backend: FluidBackend,
    /// ISPH settings (`[fluid.NAME.isph]`, only with `method = "isph"`; defaults when absent).
    #[serde(default)]
    pub isph: Option<IsphConfig>,
    /// Particle spacing Δs [m].
    pub spacing: f64,
    /// Fixed time step Δt [s].
    pub time_step: f64,
    /// Reference density ρ0 [kg/m³].
    #[serde(default = "default_density")]
    pub density: f64,
    /// Kinematic viscosity ν [m²/s].
    #[serde(default = "default_viscosity")]
    pub viscosity: f64,
    /// Whether the viscous term ν⟨∇²u⟩ (S1-10) is computed.
    #[serde(default = "default_true")]
    pub viscosity_term: bool,
    /// Gravity g [m/s²].
    #[serde(default = "default_gravity")]
    pub gravity: [f64; 3],
    /// Sound speed c [m/s]; default `u_max / 0.2` (S1-16). E-MPS only.
    #[serde(default)]
    pub sound_speed: Option<f64>,
    /// Predicted largest fluid speed u_max [m/s] for S1-16; default `√(2 g H)` with H the height
    /// of the highest water block's top above the tank floor.
    #[serde(default)]
    pub max_velocity: Option<f64>,
    /// E-MPS only: α of Monaghan's artificial viscosity between fluid particles (issue 15:
    /// pressure noise at wall sensors); 0 (default) is off, WCSPH codes use 0.01 … 0.1. See
    /// `fluid-solver/src/emps/artificial_viscosity.rs`.
    #[serde(default)]
    pub artificial_viscosity: f64,
    /// Wall particle layers (≥ 4): the two inner ones carry pressure, the others fill the number density.
    #[serde(default = "default_wall_layers")]
    pub wall_layers: u32,
    /// Interval between VTU frames [s].
    pub output_interval: f64,
    /// Also write a free-surface mesh of the water (`NAME_surface_*.vtp`, `NAME_surface.pvd`)
    /// with every VTU frame.
    #[serde(default)]
    pub surface_mesh: bool,
    /// Interval between probe rows [s]; default: every output interval.
    #[serde(default)]
    pub probe_interval: Option<f64>,
    pub tank: TankConfig,
    /// Water blocks.
    #[serde(default)]
    pub block: Vec<Aabb>,
    /// Partition boards: present in the initial layout, removed at t = 0.
    #[serde(default)]
    pub gate: Vec<Aabb>,
    /// Rigid bodies made of particles.
    #[serde(default)]
    pub body: Vec<BodyConfig>,
    /// Fixed solid boxes inside the tank (piers, levees) made of wall particles.
    #[serde(default)]
    pub wall: Vec<Aabb>,
    #[serde(default)]
    pub probe: Vec<ProbeConfig>,
    /// Inflow boundary (`[fluid.NAME.inflow]`): water fed in along +x.
    #[serde(default)]
    pub inflow: Option<InflowConfig>,
    /// Outflow boundary (`[fluid.NAME.outflow]`): water beyond a plane is removed.
    #[serde(default)]
    pub outflow: Option<OutflowConfig>,
    // Run control (issue 15): particles leaving through the open top, progress lines.
    /// Largest fraction of the initial fluid particles that may leave through an open top
    /// (removed and counted) before the run stops; default 0.01.
    #[serde(default = "default_max_removed_fraction")]
    pub max_removed_fraction: f64,
    /// Wall-clock seconds between progress lines in the log; default 10.
    #[serde(default = "default_progress_interval")]
    pub progress_interval: f64,
}

fn default_max_removed_fraction() -> f64 {
    0.01
}
fn default_progress_interval() -> f64 {
    10.0
}

fn default_density() -> f64 {
    1000.0
}
fn default_viscosity() -> f64 {
    1.0e-6
}
fn default_true() -> bool {
    true
}
fn default_gravity() -> [f64; 3] {
    [0.0, 0.0, -9.8]
}
fn default_wall_layers() -> u32 {
    MIN_WALL_LAYERS
}

impl FluidConfig {
    /// Checks every key; `key` is the section's dotted path, e.g. `fluid.tank`.
    pub fn validate(&self, key: &str) -> Result<(), FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        check::positive(&k("spacing"), self.spacing)?;
        check::positive(&k("time_step"), self.time_step)?;
        check::positive(&k("density"), self.density)?;
        check::non_negative(&k("viscosity"), self.viscosity)?;
        check::within(&k("artificial_viscosity"), self.artificial_viscosity, 0.0, 1.0)?;
        check::finite(&k("gravity"), &self.gravity)?;
        check::positive(&k("output_interval"), self.output_interval)?;
        if let Some(p) = self.probe_interval {
            check::positive(&k("probe_interval"), p)?;
        }
        if let Some(c) = self.sound_speed {
            check::positive(&k("sound_speed"), c)?;
        }
        if let Some(u) = self.max_velocity {
            check::positive(&k("max_velocity"), u)?;
        }
        if !(MIN_WALL_LAYERS..=10).contains(&self.wall_layers) {
            return Err(FieldError::new(
                k("wall_layers"),
                format!(
                    "must be {MIN_WALL_LAYERS} … 10 (fewer leave the first wall layer's number density incomplete), got {}",
                    self.wall_layers
                ),
            ));
        }
        if !(self.max_removed_fraction.is_finite() && (0.0..=1.0).contains(&self.max_removed_fraction)) {
            return Err(FieldError::new(
                k("max_removed_fraction"),
                format!("must be in [0, 1], got {}", self.max_removed_fraction),
            ));
        }
        check::positive(&k("progress_interval"), self.progress_interval)?;
        let tank = self.tank.inner();
        tank.validate(&k("tank"))?;
        for a in 0..3 {
            // Extents that are not whole spacings are rounded to the nearest layer when the
            // lattice is built (with a message); at least one layer is needed.
            let cells = (tank.max[a] - tank.min[a]) / self.spacing;
            if cells.round() < 1.0 {
                return Err(FieldError::new(
                    k("tank"),
                    format!(
                        "the tank's {} extent {} m must hold at least one spacing ({} m); it is {cells:.4} spacings",
                        ["x", "y", "z"][a],
                        tank.max[a] - tank.min[a],
                        self.spacing
                    ),
                ));
            }
        }
        let l = f64::from(self.wall_layers);
        let outer: f64 = (0..3)
            .map(|a| (tank.max[a] - tank.min[a]) / self.spacing + 2.0 * l)
            .product();
        if outer > MAX_PARTICLES {
            return Err(FieldError::new(
                k("spacing"),
                format!(
                    "spacing {} m would make about {outer:.3e} particles; at most {MAX_PARTICLES:.0e} are allowed",
                    self.spacing
                ),
            ));
        }
        if self.block.is_empty() && self.inflow.is_none() {
            return Err(FieldError::new(
                k("block"),
                "a fluid participant needs at least one [[block]] of water or an [inflow]",
            ));
        }
        let mut named: Vec<(String, Aabb)> = Vec::new();
        for (i, b) in self.block.iter().enumerate() {
            let bk = format!("{key}.block[{i}]");
            b.validate(&bk)?;
            named.push((bk, *b));
        }
        for (i, g) in self.gate.iter().enumerate() {
            let gk = format!("{key}.gate[{i}]");
            g.validate(&gk)?;
            named.push((gk, *g));
        }
        for (i, w) in self.wall.iter().enumerate() {
            let wk = format!("{key}.wall[{i}]");
            w.validate(&wk)?;
            named.push((wk, *w));
        }
        for (i, b) in self.body.iter().enumerate() {
            let bk = format!("{key}.body[{i}]");
            if b.name.trim().is_empty() {
                return Err(FieldError::new(format!("{bk}.name"), "must not be empty"));
            }
            if self.body[..i].iter().any(|o| o.name == b.name) {
                return Err(FieldError::new(
                    format!("{bk}.name"),
                    format!("body name `{}` is used twice; names must be unique", b.name),
                ));
            }
            let bb = Aabb {
                min: b.min,
                max: b.max,
            };
            bb.validate(&bk)?;
            named.push((bk, bb));
        }
        for (i, (ka, a)) in named.iter().enumerate() {
            if !tank.contains(a) {
                return Err(FieldError::new(
                    ka.clone(),
                    format!(
                        "the box {:?} … {:?} is outside the domain: it must lie inside the tank {:?} … {:?}",
                        a.min, a.max, tank.min, tank.max
                    ),
                ));
            }
            if !self.holds_a_site(a) {
                return Err(FieldError::new(
                    ka.clone(),
                    format!(
                        "the box {:?} … {:?} holds no particle: particles sit at tank.min + (k + ½)·spacing ({} m)",
                        a.min, a.max, self.spacing
                    ),
                ));
            }
            for (kb, b) in &named[..i] {
                if a.overlaps(b) {
                    return Err(FieldError::new(
                        ka.clone(),
                        format!(
                            "overlaps `{kb}`; water blocks, gates, walls and bodies must not share volume"
                        ),
                    ));
                }
            }
        }
        self.validate_probes(key)?;
        self.validate_open_boundaries(key, &named)?;
        if self.backend == FluidBackend::Gpu {
            self.gpu_support(key)?;
        }
        match self.method {
            FluidMethodName::Emps => {
                if self.isph.is_some() {
                    return Err(FieldError::new(
                        k("isph"),
                        "an [isph] table needs method = \"isph\" (the method is \"emps\")",
                    ));
                }
                self.validate_time_step(key)
            }
            FluidMethodName::Isph => {
                self.isph_settings().validate(&k("isph"), self.wall_layers)?;
                self.validate_isph_time_step(key)
            }
        }
    }

    /// The section's E-MPS settings that ISPH does not use, one sentence each naming its key
    /// (runs print each as a `warning: ` line): a case written for E-MPS runs with ISPH when
    /// `method = "isph"` is its only change (issue 12: one key selects the method), and says what
    /// it leaves unused. Empty for E-MPS.
    pub fn unused_by_method(&self) -> Vec<String> {
        let mut unused = Vec::new();
        if self.method == FluidMethodName::Isph {
            if let Some(c) = self.sound_speed {
                let limit = self.isph_time_step_limit();
                unused.push(format!(
                    "`sound_speed` = {c} m/s is not used: ISPH has no sound speed (the PPE makes the flow incompressible), and its time step is checked against the advective and viscous limits instead: here they allow time_step up to {limit:.3e} s, {:.1}× the case's {} s (fewer, longer steps: raise `time_step`, and the coupling window with it)",
                    limit / self.time_step,
                    self.time_step
                ));
            }
            if self.artificial_viscosity != 0.0 {
                unused.push(format!(
                    "`artificial_viscosity` = {} is not used: it is an E-MPS option, scaled by the sound speed ISPH has not",
                    self.artificial_viscosity
                ));
            }
        }
        unused
    }

    /// What a run tells the user before it starts, one sentence each (runs print each as a
    /// `warning: ` line): the settings the method leaves unused ([`FluidConfig::unused_by_method`])
    /// and the ISPH settings known to misread a load in this case's geometry.
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = self.unused_by_method();
        let isph = self.isph_settings();
        if self.method == FluidMethodName::Isph
            && isph.pressure_gradient == PressureGradient::Symmetric
            && !self.body.is_empty()
        {
            warnings.push(
                "`isph.pressure_gradient` = \"symmetric\" with a `body`: that gradient has no face normals at a body's convex edges (with them a held box read +9.6 % of ρgV); without them, on the wall box of the MARIN dam break's CI twin (cases/dam-break-obstacle, Δs = 0.04 m), the sensor 2 cm under the box's top edge read a pull (−169 … −204 % of the measured mean over 0.6–0.8 s; −20 … −23 % with them); for loads near a body's edges use the default pressure_gradient = \"corrected-difference\"".into(),
            );
        }
        warnings
    }

    /// Refuses what the GPU path (`backend = "gpu"`) does not run yet, naming the feature: a run
    /// never goes on with a mix that silently differs from the CPU's. `key` is the section's
    /// dotted path; the error is at its `backend` key.
    pub fn gpu_support(&self, key: &str) -> Result<(), FieldError> {
        let refuse = |feature: &str| {
            Err(FieldError::new(
                format!("{key}.backend"),
                format!("the GPU path does not run {feature} yet; use backend = \"cpu\" (the default) for this case"),
            ))
        };
        if self.method != FluidMethodName::Emps {
            return refuse("method = \"isph\" (only E-MPS is on the GPU)");
        }
        if self.artificial_viscosity != 0.0 {
            return refuse("the E-MPS artificial viscosity (artificial_viscosity > 0)");
        }
        if self.inflow.is_some() || self.outflow.is_some() {
            return refuse("inflow or outflow boundaries");
        }
        if let Some(p) = self.probe.iter().find(|p| p.window.is_some()) {
            return refuse(&format!(
                "filtered probes (probe `{}` has a window; probes are read from a copy at each probe row, not every step)",
                p.name
            ));
        }
        self.gpu_position_rounding(key)
    }

    /// The GPU path keeps absolute positions in f32 (24-bit significand): a coordinate x rounds
    /// by up to |x|·2⁻²⁴. Refused when that exceeds [`GPU_MAX_ROUNDING`] Δs anywhere in the
    /// tank or its headroom above an open top (one tank height): a slow particle far from the
    /// origin would then move by steps of the rounding instead of its velocity (cell index +
    /// f32 offset positions are not on the GPU yet).
    fn gpu_position_rounding(&self, key: &str) -> Result<(), FieldError> {
        let t = &self.tank;
        let headroom = if t.lid { 0.0 } else { t.max[2] - t.min[2] };
        let far = (0..3)
            .map(|a| {
                t.min[a]
                    .abs()
                    .max(t.max[a].abs() + if a == 2 { headroom } else { 0.0 })
            })
            .fold(0.0, f64::max);
        let rounding = far * f64::from(f32::EPSILON) / 2.0;
        if rounding > GPU_MAX_ROUNDING * self.spacing {
            return Err(FieldError::new(
                format!("{key}.backend"),
                format!(
                    "the GPU path keeps positions in f32: {far} m from the origin they round by {rounding:.2e} m = {:.1e} Δs, more than the {GPU_MAX_ROUNDING:e} Δs it allows; move the tank next to the origin (coordinates are free: shift every position of the case) or use backend = \"cpu\"",
                    rounding / self.spacing
                ),
            ));
        }
        Ok(())
    }

    /// The ISPH settings: the `[isph]` table or its defaults.
    pub fn isph_settings(&self) -> IsphConfig {
        self.isph.unwrap_or_default()
    }

    /// The largest Δt ISPH accepts for this section: the advective limit `0.4 Δs / u` (u of
    /// [`FluidConfig::advective_velocity`]) and, with the viscous term on, the viscous limit
    /// `Δs² / (6ν)`, whichever is shorter.
    pub fn isph_time_step_limit(&self) -> f64 {
        let advective = self.advective_time_step_limit();
        if self.viscosity_term {
            advective.min(self.viscous_time_step_limit())
        } else {
            advective
        }
    }

    /// ISPH's advective limit on Δt: `0.4 Δs / u`, u of [`FluidConfig::advective_velocity`].
    fn advective_time_step_limit(&self) -> f64 {
        MAX_ADVECTIVE_COURANT * self.spacing / self.advective_velocity()
    }

    /// The viscous limit on Δt: `Δs² / (6ν)` (viscous number ν Δt/Δs² ≤ 1/6).
    fn viscous_time_step_limit(&self) -> f64 {
        MAX_VISCOUS_NUMBER * self.spacing * self.spacing / self.viscosity
    }

    /// ISPH: refuses a Δt above the advective (u Δt/Δs ≤ 0.4, u of
    /// [`FluidConfig::advective_velocity`]) or viscous (ν Δt/Δs² ≤ 1/6)
    /// limit; there is no acoustic limit.
    fn validate_isph_time_step(&self, key: &str) -> Result<(), FieldError> {
        let u = self.advective_velocity();
        let courant = u * self.time_step / self.spacing;
        if courant > MAX_ADVECTIVE_COURANT || courant.is_nan() {
            return Err(FieldError::new(
                format!("{key}.time_step"),
                format!(
                    "Δt = {} s is too long for ISPH: the advective Courant number u·Δt/Δs = {courant:.3} (u = {u:.3} m/s, the case's max_velocity or u_in + 2√(gH)) must be ≤ {MAX_ADVECTIVE_COURANT}; use time_step ≤ {:.3e} s",
                    self.time_step,
                    self.advective_time_step_limit()
                ),
            ));
        }
        self.validate_viscous_number(key)
    }

    /// Checks `inflow` and `outflow`: planes inside the tank, u_in > 0, the level inside the
    /// tank, and the inflow strip clear of blocks, gates and bodies.
    fn validate_open_boundaries(&self, key: &str, named: &[(String, Aabb)]) -> Result<(), FieldError> {
        let tank = self.tank.inner();
        let ds = self.spacing;
        let mut inflow_plane = None;
        if let Some(inflow) = &self.inflow {
            let strip = inflow.validate(&format!("{key}.inflow"), &tank, ds)?;
            for (kb, b) in named {
                if strip.overlaps(b) {
                    return Err(FieldError::new(
                        format!("{key}.inflow"),
                        format!(
                            "the inflow strip {:?} … {:?} overlaps `{kb}`; the strip must be free of water blocks, gates and bodies",
                            strip.min, strip.max
                        ),
                    ));
                }
            }
            inflow_plane = Some(inflow.plane);
        }
        if let Some(outflow) = &self.outflow {
            let k = format!("{key}.outflow.plane");
            let (lo, hi) = (inflow_plane.unwrap_or(tank.min[0]), tank.max[0] - ds);
            if !(outflow.plane.is_finite() && outflow.plane > lo && outflow.plane <= hi) {
                return Err(FieldError::new(
                    k,
                    format!(
                        "the outflow plane x = {} is outside the domain: it must lie after the {} (x > {lo}) and at least one spacing before the tank's end (x ≤ {hi})",
                        outflow.plane,
                        if inflow_plane.is_some() { "inflow plane" } else { "tank's start" }
                    ),
                ));
            }
        }
        Ok(())
    }

    fn validate_probes(&self, key: &str) -> Result<(), FieldError> {
        for (i, p) in self.probe.iter().enumerate() {
            let pk = format!("{key}.probe[{i}]");
            if p.name.trim().is_empty() || p.name.contains(',') {
                return Err(FieldError::new(
                    format!("{pk}.name"),
                    "must be a non-empty name without commas",
                ));
            }
            if self.probe[..i].iter().any(|o| o.name == p.name) {
                return Err(FieldError::new(
                    format!("{pk}.name"),
                    format!("probe name `{}` is used twice", p.name),
                ));
            }
            let (want, kind) = match p.kind {
                ProbeKind::WaterHeight => (2, "water-height"),
                ProbeKind::Pressure => (3, "pressure"),
                ProbeKind::SurgeFront => (0, "surge-front"),
                ProbeKind::WallPressure => (3, "wall-pressure"),
            };
            Self::validate_sensor_keys(p, &pk, self.spacing)?;
            if p.position.len() != want {
                return Err(FieldError::new(
                    format!("{pk}.position"),
                    format!(
                        "a {kind} probe needs {want} coordinates, got {}",
                        p.position.len()
                    ),
                ));
            }
            check::finite(&format!("{pk}.position"), &p.position)?;
            let t = self.tank;
            if (0..want).any(|a| p.position[a] < t.min[a] || p.position[a] > t.max[a]) {
                return Err(FieldError::new(
                    format!("{pk}.position"),
                    format!("{:?} is outside the tank {:?} … {:?}", p.position, t.min, t.max),
                ));
            }
            if let Some(axis) = &p.axis {
                if signed_axis(axis).is_none() || p.kind != ProbeKind::SurgeFront {
                    return Err(FieldError::new(
                        format!("{pk}.axis"),
                        format!(
                            "only a surge-front probe has an axis, one of \"x\", \"+x\", \"-x\", \"y\", \"+y\", \"-y\", \"z\", \"+z\", \"-z\"; got `{axis}`"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// `normal`, `diameter` and `window`: required (the first two) on a wall-pressure sensor,
    /// refused on the other probes.
    fn validate_sensor_keys(p: &ProbeConfig, pk: &str, spacing: f64) -> Result<(), FieldError> {
        let sensor = p.kind == ProbeKind::WallPressure;
        let keys = [
            ("normal", p.normal.is_some()),
            ("diameter", p.diameter.is_some()),
            ("window", p.window.is_some()),
        ];
        if let Some((key, _)) = keys.iter().find(|(_, set)| *set && !sensor) {
            return Err(FieldError::new(
                format!("{pk}.{key}"),
                "only a wall-pressure probe has `normal`, `diameter` and `window`",
            ));
        }
        if !sensor {
            return Ok(());
        }
        match p.normal.as_deref() {
            Some(n) if n.starts_with(['+', '-']) && signed_axis(n).is_some() => {}
            other => {
                return Err(FieldError::new(
                    format!("{pk}.normal"),
                    format!(
                        "a wall-pressure sensor needs the face's outward normal (into the water), one of \"+x\", \"-x\", \"+y\", \"-y\", \"+z\", \"-z\"; got {other:?}"
                    ),
                ))
            }
        }
        match p.diameter {
            Some(d) if d.is_finite() && d >= spacing => {}
            other => {
                return Err(FieldError::new(
                    format!("{pk}.diameter"),
                    format!(
                        "a wall-pressure sensor needs a disc diameter of at least one spacing ({spacing} m); got {other:?}"
                    ),
                ))
            }
        }
        if let Some(w) = p.window {
            check::positive(&format!("{pk}.window"), w)?;
        }
        Ok(())
    }

    /// True when the box holds at least one lattice site `tank.min + (k + ½) Δs` on every axis.
    fn holds_a_site(&self, b: &Aabb) -> bool {
        (0..3).all(|a| {
            let first = ((b.min[a] - self.tank.min[a]) / self.spacing - 0.5).ceil();
            self.tank.min[a] + (first + 0.5) * self.spacing <= b.max[a]
        })
    }

    /// Refuses a Δt above the acoustic (c Δt/Δs ≤ 1) or viscous (ν Δt/Δs² ≤ 1/6) limit.
    fn validate_time_step(&self, key: &str) -> Result<(), FieldError> {
        let c = self.sound_speed();
        if !(c.is_finite() && c > 0.0) {
            return Err(FieldError::new(
                format!("{key}.sound_speed"),
                format!(
                    "the default c = u_max/0.2 is {c} (no gravity or no water height): set sound_speed > 0"
                ),
            ));
        }
        let courant = c * self.time_step / self.spacing;
        if courant > MAX_ACOUSTIC_COURANT {
            return Err(FieldError::new(
                format!("{key}.time_step"),
                format!(
                    "Δt = {} s is unstable: the acoustic Courant number c·Δt/Δs = {courant:.3} (c = {c:.3} m/s) must be ≤ {MAX_ACOUSTIC_COURANT}; use time_step ≤ {:.3e} s",
                    self.time_step,
                    MAX_ACOUSTIC_COURANT * self.spacing / c
                ),
            ));
        }
        self.validate_viscous_number(key)
    }

    /// Refuses a Δt above the viscous limit ν Δt/Δs² ≤ 1/6 (when the viscous term is on).
    fn validate_viscous_number(&self, key: &str) -> Result<(), FieldError> {
        if self.viscosity_term {
            let vn = self.viscosity * self.time_step / (self.spacing * self.spacing);
            if vn > MAX_VISCOUS_NUMBER {
                return Err(FieldError::new(
                    format!("{key}.time_step"),
                    format!(
                        "Δt = {} s is unstable: the viscous number ν·Δt/Δs² = {vn:.3} must be ≤ 1/6; use time_step ≤ {:.3e} s",
                        self.time_step,
                        self.viscous_time_step_limit()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// |g| [m/s²].
    pub fn gravity_magnitude(&self) -> f64 {
        self.gravity.iter().map(|g| g * g).sum::<f64>().sqrt()
    }

    /// u_max of S1-16: the case's `max_velocity`, else √(u_in² + 2gH) with H the highest block
    /// top or inflow level above the floor (u_in = 0 without an inflow).
    pub fn max_velocity(&self) -> f64 {
        self.max_velocity.unwrap_or_else(|| {
            let (u_in, inflow_top) = self.inflow.as_ref().map_or((0.0, self.tank.min[2]), |i| {
                (i.velocity, self.tank.min[2] + i.level)
            });
            let top = self.block.iter().map(|b| b.max[2]).fold(inflow_top, f64::max);
            (u_in * u_in + 2.0 * self.gravity_magnitude() * (top - self.tank.min[2])).sqrt()
        })
    }

    /// The velocity scale of ISPH's advective Courant check: the case's `max_velocity`, else
    /// `u_in + 2√(gH)` with H as in [`FluidConfig::max_velocity`]: the front of a dam break on a
    /// dry bed runs at 2√(gH) (Ritter 1892), √2 times the free-fall speed √(2gH) of S1-16 (an
    /// ISPH dam break checked against √(2gH) at Courant 0.4 moved its front 0.57 Δs a step and
    /// tripped the instability detector's 0.5 Δs).
    pub fn advective_velocity(&self) -> f64 {
        self.max_velocity.unwrap_or_else(|| {
            let (u_in, inflow_top) = self.inflow.as_ref().map_or((0.0, self.tank.min[2]), |i| {
                (i.velocity, self.tank.min[2] + i.level)
            });
            let top = self.block.iter().map(|b| b.max[2]).fold(inflow_top, f64::max);
            u_in + 2.0 * (self.gravity_magnitude() * (top - self.tank.min[2])).sqrt()
        })
    }

    /// c of S1-16: the case's `sound_speed`, else `u_max / 0.2`.
    pub fn sound_speed(&self) -> f64 {
        self.sound_speed.unwrap_or_else(|| self.max_velocity() / MACH)
    }

    /// Names of the resolved rigid bodies this participant owns.
    pub fn body_names(&self) -> Vec<&str> {
        self.body.iter().map(|b| b.name.as_str()).collect()
    }
}

/// Fewest strip layers of an inflow: the fluid at the plane must see a full r_e = 3.1 Δs of
/// strip behind it while the back layer lags up to 1.5 Δs behind the strip's back (see
/// `fluid_solver::open_boundary`), so 3.1 + 1.5 rounded up.
pub const MIN_INFLOW_STRIP_LAYERS: f64 = 5.0;

/// `[fluid.NAME.inflow]`: an inflow boundary for run-up (Saitoh & Akitomo, Fig. 5): a strip of
/// particles upstream of the plane x = `plane` moves with u_in along +x and feeds water up to the
/// level h(t), which rises linearly from `initial_level` to `level` over `rise_time`.
///
/// ```toml
/// [fluid.river.inflow]
/// plane = 40.0          # x of the inflow plane [m]
/// velocity = 10.0       # u_in [m/s], along +x
/// strip_length = 40.0   # strip depth upstream of the plane [m]
/// level = 20.0          # h_max above the tank floor [m]
/// initial_level = 0.0   # h(0) [m]
/// rise_time = 4.0       # h reaches h_max at this time [s]
/// span = [0.0, 100.0]   # y range fed [m]; default: the tank's width
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct InflowConfig {
    /// x of the inflow plane [m].
    pub plane: f64,
    /// u_in [m/s] along +x.
    pub velocity: f64,
    /// Depth of the strip upstream of the plane [m], a whole number of spacings.
    pub strip_length: f64,
    /// Largest water level h_max above the tank floor [m].
    pub level: f64,
    /// Water level at t = 0 [m].
    #[serde(default)]
    pub initial_level: f64,
    /// Time over which the level rises linearly to `level` [s]; 0 means at once.
    #[serde(default)]
    pub rise_time: f64,
    /// `[y_min, y_max]` fed with water [m]; default: the tank's width.
    #[serde(default)]
    pub span: Option<[f64; 2]>,
}

impl InflowConfig {
    /// The water level h(t) above the tank floor [m].
    pub fn level_at(&self, t: f64) -> f64 {
        if self.rise_time > 0.0 && t < self.rise_time {
            self.initial_level + (self.level - self.initial_level) * (t.max(0.0) / self.rise_time)
        } else {
            self.level
        }
    }

    /// The fed y range: `span`, or the tank's width.
    pub fn span_or(&self, tank: &Aabb) -> [f64; 2] {
        self.span.unwrap_or([tank.min[1], tank.max[1]])
    }

    /// Checks every key against the tank and the spacing; returns the strip's box at full level.
    pub fn validate(&self, key: &str, tank: &Aabb, spacing: f64) -> Result<Aabb, FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        check::positive(&k("velocity"), self.velocity)?;
        check::positive(&k("strip_length"), self.strip_length)?;
        check::positive(&k("level"), self.level)?;
        check::non_negative(&k("rise_time"), self.rise_time)?;
        let layers = self.strip_length / spacing;
        if (layers - layers.round()).abs() > 1e-6 * layers || layers.round() < MIN_INFLOW_STRIP_LAYERS {
            return Err(FieldError::new(
                k("strip_length"),
                format!(
                    "must be a whole number of spacings ({spacing} m), at least {MIN_INFLOW_STRIP_LAYERS}; got {} m = {layers:.4} spacings",
                    self.strip_length
                ),
            ));
        }
        let (back, front) = (tank.min[0] + self.strip_length, tank.max[0] - spacing);
        if !(self.plane.is_finite() && self.plane >= back - 1e-9 * spacing && self.plane <= front) {
            return Err(FieldError::new(
                k("plane"),
                format!(
                    "the inflow plane x = {} is outside the domain: with strip_length = {} m the strip must fit inside the tank, so the plane must be in [{back}, {front}] (tank x from {} to {})",
                    self.plane, self.strip_length, tank.min[0], tank.max[0]
                ),
            ));
        }
        let offset = (self.plane - tank.min[0]) / spacing;
        if (offset - offset.round()).abs() > 1e-6 * offset.max(1.0) {
            return Err(FieldError::new(
                k("plane"),
                format!(
                    "the inflow plane x = {} must lie on a lattice face, tank.min.x + a whole number of spacings ({spacing} m); it is {offset:.4} spacings in",
                    self.plane
                ),
            ));
        }
        let height = tank.max[2] - tank.min[2];
        if self.level > height || self.level < spacing {
            return Err(FieldError::new(
                k("level"),
                format!(
                    "the level {} m must be at least one spacing ({spacing} m) and must not be above the domain: at most the tank height {height} m",
                    self.level
                ),
            ));
        }
        if !(self.initial_level.is_finite() && (0.0..=self.level).contains(&self.initial_level)) {
            return Err(FieldError::new(
                k("initial_level"),
                format!(
                    "must be in [0, level = {}], got {}",
                    self.level, self.initial_level
                ),
            ));
        }
        let span = self.span_or(tank);
        let sites = ((span[1] - tank.min[1]) / spacing - 0.5).floor()
            - ((span[0] - tank.min[1]) / spacing - 0.5).ceil();
        if !(span[0].is_finite() && span[1].is_finite())
            || span[0] < tank.min[1]
            || span[1] > tank.max[1]
            || sites < 0.0
        {
            return Err(FieldError::new(
                k("span"),
                format!(
                    "{span:?} must be an increasing y range inside the tank [{}, {}] that holds a lattice site tank.min.y + (j + ½)·{spacing} m",
                    tank.min[1], tank.max[1]
                ),
            ));
        }
        Ok(Aabb {
            min: [self.plane - self.strip_length, span[0], tank.min[2]],
            max: [self.plane, span[1], tank.min[2] + self.level],
        })
    }
}

/// `[fluid.NAME.outflow]`: fluid particles beyond the plane x = `plane` are removed.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutflowConfig {
    /// x of the outflow plane [m].
    pub plane: f64,
}
