//! `[fluid.NAME]`: a fluid participant solved by E-MPS (Saitoh & Akitomo, S1-3 … S1-16) or by
//! ISPH (Ohinata et al., S2-3 … S2-13), picked by `method`.
//!
//! ```toml
//! [fluid.tank]
//! method = "emps"           # or "isph" (then optionally [fluid.tank.isph], see IsphConfig)
//! backend = "cpu"           # or "gpu": a Vulkan GPU (see FluidConfig::gpu_support)
//! spacing = 0.01            # Δs [m]
//! time_step = 5e-4          # Δt [s], checked against the acoustic and viscous limits
//! sound_speed = 12.1        # c [m/s]; default u_max / 0.2 with u_max = √(2gH) (S1-16); E-MPS
//!                           # only: with "isph" it is left unused and the run says so
//! artificial_viscosity = 0.0 # α of Monaghan's artificial viscosity (E-MPS only, as sound_speed; default off)
//! viscosity_term = false    # switch ν⟨∇²u⟩ off when ν is far below the numerical dissipation
//! output_interval = 0.05
//! surface_mesh = true       # also a free-surface mesh (VTP) per frame; default false
//! ranks = 4                 # MPI ranks, each a slab along x (default 1; see FluidConfig::ranks)
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
//! [`InflowConfig`], [`OutflowConfig`]; an inflow's `series` file is read before the section is
//! checked, [`InflowConfig::read_series`]); with an inflow, u_max = √(u_in² + 2gH) in S1-16, with
//! the largest u_in and level of a series.
//!
//! Real scenes add solids from closed triangle meshes (`[[fluid.NAME.solid]]`, STL or OBJ),
//! terrains from height grids or planes (`[[fluid.NAME.terrain]]`; see [`SolidConfig`],
//! [`TerrainConfig`]), a piston or flap wave maker (`[fluid.NAME.wave_maker]`) and zones that absorb
//! waves (`[[fluid.NAME.damping]]`; see [`WaveMakerConfig`], [`DampingConfig`]). Their files are
//! read when the case is loaded ([`FluidConfig::load_files`], [`FluidConfig::build_wave_maker`]).

mod geometry;
mod gpu;
mod inflow_law;
mod inflow_series;
mod initial_wave;
mod isph;
mod mesh_bodies;
mod open_boundary;
mod probes;
mod ranks;
mod solids;
mod time_step;
mod wave_maker;

pub use geometry::{Aabb, BodyConfig, TankConfig};
pub use gpu::{gpu_wide_quantum, GPU_MAX_ROUNDING, GPU_MAX_WIDE_ROUNDING};
pub use inflow_law::InflowLaw;
pub use inflow_series::InflowSeries;
pub use initial_wave::InitialWaveConfig;
pub use isph::{
    IsphConfig, KernelCorrection, PpeSolver, PressureGradient, Shifting, WallSlip, MAX_SHIFTING_COEFFICIENT,
    SYMMETRIC_SUPPORT,
};
pub use open_boundary::{InflowConfig, OutflowConfig, MIN_INFLOW_STRIP_LAYERS};
pub use probes::{signed_axis, ProbeConfig, ProbeKind};
pub use ranks::{DEFAULT_LAUNCHER, RANKS_PLACEHOLDER};
pub use solids::{Loaded, PlaneConfig, SolidConfig, TerrainConfig, MAX_MESH_TO_TANK};
pub use time_step::{MACH, MAX_ACOUSTIC_COURANT, MAX_ADVECTIVE_COURANT, MAX_VISCOUS_NUMBER};
pub use wave_maker::{DampingConfig, PaddleKind, PaddleMotion, WaveMakerConfig};

/// Fewest spacings across a flume (along y, across the waves' x) below which ISPH's particle side
/// walls are warned to slow its waves ([`FluidConfig::warnings`]; docs/notes/standing-wave.md).
pub const FEWEST_SPACINGS_ACROSS_A_WAVE: f64 = 8.0;

use super::error::check;
use super::FieldError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Fewest wall layers: two pressure layers (a fluid particle half a spacing off the wall reaches
/// 2.1 Δs, i.e. wall centres 0.5 Δs and 1.5 Δs deep) plus dummy layers until the first wall
/// layer's number density (r_e = 3.1 Δs) is complete: centres down to 3.5 Δs, so four layers.
pub const MIN_WALL_LAYERS: u32 = 4;

/// Most particles a case may create (a guard against a spacing typo filling the memory).
pub const MAX_PARTICLES: f64 = 5.0e7;

/// Which fluid method steps a participant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FluidMethodName {
    /// Explicit MPS (seed 000): weakly compressible, Δt limited by the sound speed.
    #[default]
    Emps,
    /// Incompressible SPH (seed 003): a pressure Poisson equation every step, Δt free of c.
    Isph,
}

/// Where a fluid participant's step runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FluidBackend {
    /// The CPU (rayon threads): every feature.
    #[default]
    Cpu,
    /// A GPU through wgpu compute shaders (Vulkan): E-MPS, and ISPH with its default settings in
    /// tanks of walls, alone or coupled; see [`FluidConfig::gpu_support`] for what it refuses.
    Gpu,
}

/// Configuration of one fluid participant.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FluidConfig {
    /// The method that steps the particles.
    #[serde(default)]
    pub method: FluidMethodName,
    /// Where the step runs.
    #[serde(default)]
    pub backend: FluidBackend,
    /// ISPH only: the ISPH settings; defaults when absent, refused with `method = "emps"`.
    #[serde(default)]
    pub isph: Option<IsphConfig>,
    /// Particle spacing Δs [m]. Range: > 0, and at most 5e7 particles in the tank and its walls.
    pub spacing: f64,
    /// Time step Δt [s]: E-MPS's every step; ISPH's longest, a step being cut to
    /// u Δt/Δs ≤ 0.4 where the fluid at its start is faster than the check's u_max (down to
    /// Δt/8). Range: > 0, within the method's limits: E-MPS c Δt/Δs ≤ 1, ISPH
    /// u_max Δt/Δs ≤ 0.4, and ν Δt/Δs² ≤ 1/6 with the viscous term on.
    pub time_step: f64,
    /// Reference density ρ0 [kg/m³]. Range: > 0.
    #[serde(default = "default_density")]
    pub density: f64,
    /// Kinematic viscosity ν [m²/s]. Range: ≥ 0.
    #[serde(default = "default_viscosity")]
    pub viscosity: f64,
    /// Whether the viscous term ν⟨∇²u⟩ (S1-10) is computed; off when ν is far below the
    /// numerical dissipation.
    #[serde(default = "default_true")]
    pub viscosity_term: bool,
    /// Gravity g [m/s²].
    #[serde(default = "default_gravity")]
    pub gravity: [f64; 3],
    /// E-MPS only: sound speed c [m/s]; default `u_max / 0.2` (S1-16). ISPH has none: it
    /// leaves the key unused and says so. Range: > 0.
    #[serde(default)]
    pub sound_speed: Option<f64>,
    /// Predicted largest fluid speed u_max [m/s]: E-MPS's default sound speed (S1-16) and
    /// ISPH's advective time-step check use it. Default: √(u_in² + 2gH) for E-MPS, u_in + 2√(gH)
    /// for ISPH (the dam-break front), with H the highest block top or inflow level above the
    /// tank floor and u_in the inflow velocity (0 without one; a `series`' largest level and
    /// velocity). Range: > 0.
    #[serde(default)]
    pub max_velocity: Option<f64>,
    /// E-MPS only: α of Monaghan's artificial viscosity between fluid particles [–]
    /// (against pressure noise at wall sensors); 0 is off, WCSPH codes use 0.01 … 0.1. See
    /// `fluid-solver/src/emps/artificial_viscosity.rs`. Range: [0, 1].
    #[serde(default)]
    pub artificial_viscosity: f64,
    /// Wall particle layers: the two inner ones carry pressure, the others fill the number
    /// density. Range: 4 … 10.
    #[serde(default = "default_wall_layers")]
    pub wall_layers: u32,
    /// Interval between VTU frames [s]. Range: > 0.
    pub output_interval: f64,
    /// Also write a free-surface mesh of the water (`NAME_surface_*.vtp`, `NAME_surface.pvd`)
    /// with every VTU frame.
    #[serde(default)]
    pub surface_mesh: bool,
    /// Interval between probe rows [s]; default: every output interval. Range: > 0.
    #[serde(default)]
    pub probe_interval: Option<f64>,
    /// The tank: the inner faces of its walls.
    pub tank: TankConfig,
    /// Water blocks, filled on the lattice: at least one unless there is an `inflow`.
    #[serde(default)]
    pub block: Vec<Aabb>,
    /// Partition boards: present in the initial layout, removed at t = 0.
    #[serde(default)]
    pub gate: Vec<Aabb>,
    /// Rigid boxes made of particles: held fixed in a fluid-only run, moved by a structure
    /// participant through `[[coupling.body]]`.
    #[serde(default)]
    pub body: Vec<BodyConfig>,
    /// Fixed solid boxes inside the tank (piers, levees) made of wall particles.
    #[serde(default)]
    pub wall: Vec<Aabb>,
    /// Fixed solids from closed triangle meshes (STL, OBJ), made of wall particles.
    #[serde(default)]
    pub solid: Vec<SolidConfig>,
    /// Sea beds and beaches: the ground below a height grid or a plane, made of wall particles.
    #[serde(default)]
    pub terrain: Vec<TerrainConfig>,
    /// A piston or flap wave maker.
    #[serde(default)]
    pub wave_maker: Option<WaveMakerConfig>,
    /// A solitary wave in the tank at t = 0 (as NTHMP benchmark 1 starts), instead of a paddle
    /// that makes it.
    #[serde(default)]
    pub initial_wave: Option<InitialWaveConfig>,
    /// Zones that absorb waves (the fluid's velocity relaxed towards rest).
    #[serde(default)]
    pub damping: Vec<DampingConfig>,
    /// Probes, one column each of the probe CSV.
    #[serde(default)]
    pub probe: Vec<ProbeConfig>,
    /// An inflow boundary, water fed in along +x.
    #[serde(default)]
    pub inflow: Option<InflowConfig>,
    /// An outflow boundary, water beyond a plane is removed.
    #[serde(default)]
    pub outflow: Option<OutflowConfig>,
    // Run control (issue 15): particles leaving through the open top, progress lines.
    /// Largest fraction of the initial fluid particles that may leave through an open top
    /// (removed and counted) before the run stops [–]. Range: [0, 1].
    #[serde(default = "default_max_removed_fraction")]
    pub max_removed_fraction: f64,
    /// Wall-clock time between progress lines in the log [s]. Range: > 0.
    #[serde(default = "default_progress_interval")]
    pub progress_interval: f64,
    /// MPI ranks that step the fluid, each a slab along x balanced by fluid particles (the
    /// fluid solver built with its `mpi` feature; `coupler run` starts them through
    /// `launcher`). Default 1: one process. More than one runs E-MPS on CPU threads, without
    /// a wave maker or surface meshes (the drag coupling's members at most 2.1 Δs wide, 3.65 Δs
    /// with the viscous term). Range: ≥ 1.
    #[serde(default)]
    pub ranks: Option<usize>,
    /// The command that starts `ranks` processes, `{ranks}` where their number goes (e.g.
    /// `"srun -n {ranks}"` on a Slurm cluster, `"mpirun --oversubscribe -np {ranks}"` for more
    /// ranks than cores); the solver's command follows it. Default `"mpirun -np {ranks}"`;
    /// unused with one rank.
    #[serde(default)]
    pub launcher: Option<String>,
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
            match (b.box_bounds(), &b.mesh, b.min.is_some() || b.max.is_some()) {
                (Some(bb), None, _) => {
                    bb.validate(&bk)?;
                    named.push((bk, bb));
                }
                // a mesh body's box is known when its file is read (`load_files`)
                (None, Some(m), false) => m.validate(&format!("{bk}.mesh"))?,
                (_, Some(_), true) => {
                    return Err(FieldError::new(
                        format!("{bk}.mesh"),
                        format!(
                            "body `{}` gives both `mesh` and `min`/`max`: a body is a box (`min` and `max`) or a closed mesh (`mesh = {{ file = \"….stl\" }}`), not both",
                            b.name
                        ),
                    ))
                }
                _ => {
                    return Err(FieldError::new(
                        bk,
                        format!(
                            "body `{}` needs a shape: `min` and `max` (a box) or `mesh = {{ file = \"….stl\" }}` (a closed mesh)",
                            b.name
                        ),
                    ))
                }
            }
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
        self.validate_solids(key)?;
        self.validate_waves(key, &named)?;
        self.validate_initial_wave(key)?;
        self.validate_probes(key)?;
        self.validate_open_boundaries(key, &named)?;
        if self.backend == FluidBackend::Gpu {
            self.gpu_support(key)?;
        }
        self.validate_ranks(key)?;
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
    /// `method = "isph"` is its only change (one key selects the method), and says what
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
    /// `warning: ` line): the settings the method leaves unused ([`FluidConfig::unused_by_method`]),
    /// the ISPH settings known to misread a load in this case's geometry, and E-MPS or ISPH's
    /// symmetric gradients (the default included) asked to carry a wave
    /// (docs/notes/emps-gravity-waves.md, docs/notes/standing-wave.md).
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = self.unused_by_method();
        let isph = self.isph_settings();
        if self.method == FluidMethodName::Isph
            && isph.pressure_gradient == PressureGradient::Symmetric
            && !self.body.is_empty()
        {
            warnings.push(
                "`isph.pressure_gradient` = \"symmetric\" with a `body`: that gradient has no face normals at a body's convex edges (with them a held box read +9.6 % of ρgV), and the still water at a held box's corners moves (0.2 m/s at a 12 cm box, where the default's stays near 1e-3 m/s); without them, on the wall box of the MARIN dam break's CI twin (cases/dam-break-obstacle, Δs = 0.04 m), the sensor 2 cm under the box's top edge read a pull (−169 … −204 % of the measured mean over 0.6–0.8 s; −20 … −23 % with them); for loads near a body's edges use the default pressure_gradient = \"conservative\" (whose bodies complete the water's kernel sums: 0.0 % of ρgV, water still) or \"corrected-difference\"".into(),
            );
        }
        let carries_a_wave = self.wave_maker.is_some() || self.initial_wave.is_some();
        let isph_symmetric_wave =
            self.method == FluidMethodName::Isph && isph.pressure_gradient.is_symmetric() && carries_a_wave;
        if isph_symmetric_wave && isph.kernel_correction() == KernelCorrection::None {
            warnings.push(format!(
                "`isph.pressure_gradient` = \"{}\" with kernel_correction = \"none\" and a `wave_maker` or an `initial_wave`: the plain symmetric gradient reads the hydrostatic pressure sideways where the particles shear and so moves a gravity wave's energy out of the wave (a standing wave of a/d = 0.1 loses a quarter of its amplitude in the first quarter period at d/8, d/16 and d/32, one of a/d = 0.05 half of it; a solitary wave of H/d = 0.2 keeps 0.81 H after 10 depths at d/16), so read its height and loads only near where it starts; for waves use the defaults (pressure_gradient = \"conservative\" with kernel_correction = \"moment\") or isph = {{ shifting = \"lind\", pressure_gradient = \"corrected-difference\" }} (docs/notes/standing-wave.md)",
                match isph.pressure_gradient {
                    PressureGradient::Symmetric => "symmetric",
                    _ => "conservative",
                }
            ));
        } else if isph_symmetric_wave {
            warnings.push(
                "ISPH's exact projection with its kernel correction (the default) and a `wave_maker` or an `initial_wave`: in a flume eight particles wide it keeps 0.99 and 0.97 of a standing wave's amplitude at its first two swings (a/d = 0.1, d/16), and a piston's solitary wave (H/d = 0.2) reads 0.91–0.97 H after 10 depths within 1.5 % of √(g(d + H)) at d/16 and 0.98 H at 1.7 % below at d/24, but 0.92 H and 4.4 % slow at d/12 and 0.78 H at d/8; it runs up a 1:3 beach to 0.75 of Synolakis' law at d/16 (S2-8's gradient with Lind's shifting: 0.81, momentum not conserved), so read wave heights and run-up with their resolution, at 16 or more particles per depth (docs/notes/standing-wave.md, docs/notes/solitary-waves.md, docs/notes/solitary-runup.md)".into(),
            );
        }
        let across = (self.tank.max[1] - self.tank.min[1]) / self.spacing;
        if self.method == FluidMethodName::Isph
            && carries_a_wave
            && across < FEWEST_SPACINGS_ACROSS_A_WAVE - 1e-9
        {
            warnings.push(format!(
                "the tank is {across:.0} spacings wide across the wave (along y) with `method` = \"isph\" and a `wave_maker` or an `initial_wave`: particle side walls read the pressure as flat along them, so a narrow flume's walls hold its waves back by their share of the water (a standing wave's half periods ran 3.0 % long four spacings wide, 1.6 % eight wide and 1.05 % sixteen wide; a solitary wave of H/d = 0.2 at d/16, read on one gauge line, ran 2.5 % slow four wide and 0.4 % eight wide), so make the tank at least {FEWEST_SPACINGS_ACROSS_A_WAVE} spacings wide (docs/notes/standing-wave.md)"
            ));
        }
        if self.method == FluidMethodName::Emps && carries_a_wave {
            warnings.push(
                "`method` = \"emps\" with a `wave_maker` or an `initial_wave`: E-MPS damps gravity waves (a standing wave keeps 0.45 of its amplitude after one period at d/8, less at d/16; a solitary wave of H/d = 0.2 keeps 0.84 H after 10 depths at d/16 and travels about a quarter slow, and its run-up on a 1:3 beach reaches 0.30–0.33 of Synolakis' law), so read loads only where the wave has travelled a few depths; for waves use method = \"isph\" with its defaults (for run-up isph = { shifting = \"lind\", pressure_gradient = \"corrected-difference\" }, 0.81 of Synolakis' law at d/16 eight particles wide where the defaults reach 0.75) (docs/notes/emps-gravity-waves.md, docs/notes/solitary-waves.md)".into(),
            );
        }
        warnings
    }

    /// The ISPH settings: the `[isph]` table or its defaults.
    pub fn isph_settings(&self) -> IsphConfig {
        self.isph.unwrap_or_default()
    }

    /// True when the box holds at least one lattice site `tank.min + (k + ½) Δs` on every axis.
    fn holds_a_site(&self, b: &Aabb) -> bool {
        (0..3).all(|a| {
            let first = ((b.min[a] - self.tank.min[a]) / self.spacing - 0.5).ceil();
            self.tank.min[a] + (first + 0.5) * self.spacing <= b.max[a]
        })
    }

    /// |g| [m/s²].
    pub fn gravity_magnitude(&self) -> f64 {
        self.gravity.iter().map(|g| g * g).sum::<f64>().sqrt()
    }

    /// Names of the resolved rigid bodies this participant owns.
    pub fn body_names(&self) -> Vec<&str> {
        self.body.iter().map(|b| b.name.as_str()).collect()
    }
}
