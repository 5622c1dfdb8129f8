//! The fluid solver of one `[fluid.NAME]` participant: the particles, the step, the clock and
//! the stability monitor; advances to a given time and saves/restores its state in memory.

use crate::bodies::pair_law::{Exchange, PairLaw};
use crate::bodies::RigidBodies;
use crate::boundaries::damping::{self, DampingZone};
use crate::boundaries::escape::OpenTop;
use crate::boundaries::open_boundary::OpenBoundaries;
use crate::boundaries::paddle::Paddle;
use crate::emps::kernel::Kernel;
use crate::emps::step::EmpsStep;
use crate::isph::neighbour_list;
use crate::isph::step::{IsphState, IsphStep};
use crate::isph::step_length::AdvectiveLimit;
use crate::method::{FluidMethod, MethodState, StepTotals};
use crate::neighbours::neighbour_search::{CellGrid, CELL_IN_SPACINGS};
use crate::particles::kind::Kind;
use crate::particles::layout::{self, Domain};
use crate::particles::Particles;
use crate::physics::Physics;
use crate::stability::{Instability, StabilityMonitor};
use crate::stage_timer::StageTimes;
use crate::state::{BodyExchange, FluidState, PointReactions, RunState};
use crate::unresolved;
use crate::unresolved::spreading::{Share, Spread};
use schemas::case::fluid::{Aabb, FluidConfig, FluidMethodName};
use std::sync::Mutex;

/// Landing on a time: a remainder below this fraction of Δt is rounding, not a step; a step up to
/// (1 + this) Δt is taken whole.
const LANDING_SLACK: f64 = 1e-9;

/// Running totals since the solver was made.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunTotals {
    /// Σ force_from_walls·Δt: impulse of walls and bodies on the fluid [N s].
    pub wall_impulse: [f64; 3],
    /// Neighbour candidates examined.
    pub candidates: u64,
    /// Particle-steps done.
    pub particle_steps: u64,
    /// Iterations of the pressure Poisson equation's solver (ISPH).
    pub ppe_iterations: u64,
    /// Fluid particles kicked by the collision stage, summed over the steps
    /// ([`crate::method::StepTotals::collisions`]).
    pub collisions: u64,
    /// Σ (point reactions spread on the fluid)·Δt: impulse of the drag coupling [N s].
    pub reaction_impulse: [f64; 3],
    /// Σ (point reactions no fluid was near)·Δt: impulse that could not be applied [N s].
    pub unapplied_impulse: [f64; 3],
    /// ISPH's steps cut short because the fluid outran the case's Δt ([`AdvectiveLimit`]).
    pub advective_cuts: u64,
    /// The fastest fluid speed that cut a step [m/s] (0 when none did).
    pub fastest_cut: f64,
}

/// Shares of point reactions found while sampling, for the particles at `version`.
#[derive(Debug)]
struct ReactionShares {
    version: u64,
    points: Vec<f64>,
    centroids: Vec<f64>,
    widths: Vec<f64>,
    shares: Vec<Option<Share>>,
}

/// A particle fluid with walls, stepped by the case's method.
#[derive(Debug)]
pub struct FluidSolver {
    /// Everything a step changes (a checkpoint is a clone of it).
    pub(crate) state: FluidState,
    pub(crate) method: FluidMethod,
    /// The MPS lattice constants the shared services read (probes: radii, n0).
    pub(crate) kernel: Kernel,
    pub(crate) physics: Physics,
    pub(crate) monitor: StabilityMonitor,
    pub(crate) time_step: f64,
    /// ISPH's limit on each step's length from the fluid's speed (`None` for E-MPS, whose
    /// limit is acoustic and set by the case's sound speed).
    advective: Option<AdvectiveLimit>,
    pub(crate) started: bool,
    pub(crate) domain: Domain,
    pub(crate) tank: Aabb,
    pub(crate) bodies: RigidBodies,
    /// Where fluid may leave (removed and counted), and the most that may leave.
    pub(crate) open_top: OpenTop,
    /// The wave maker's paddle, placed before every step (on the GPU path by the device).
    pub(crate) paddle: Option<Paddle>,
    /// Zones whose fluid velocity is relaxed after every step.
    damping: Vec<DampingZone>,
    max_removed_fraction: f64,
    /// What the lattice moved (see [`crate::particles::lattice`]).
    layout_notes: Vec<String>,
    /// [`FluidSolver::warnings`].
    warnings: Vec<String>,
    /// Reactions of the unresolved coupling, applied at every step until replaced.
    pub(crate) point_reactions: PointReactions,
    /// Bumped whenever the particles may have moved, been added or removed, or been replaced
    /// ([`FluidSolver::moved`]): the shares below are used only at the version they were found at.
    pub(crate) positions_version: u64,
    /// The shares of the point reactions found while sampling ([`FluidSolver::sample_points_for`]).
    reaction_shares: Mutex<Option<ReactionShares>>,
    /// The GPU path ([`crate::gpu`]): the step on the device, when the case asks for it.
    pub(crate) device: Option<Box<crate::gpu::GpuEmps>>,
    /// The device's particles are ahead of the host's / the host's of the device's; the fluid
    /// particles when the last step saw fluid leave through the open top (removed on the device
    /// before the next step).
    pub(crate) host_stale: bool,
    pub(crate) host_dirty: bool,
    pub(crate) escape_pending: Option<u64>,
    /// Whole copies from the device to the host so far, and their wall seconds.
    pub(crate) host_copies: (u64, f64),
    /// Where the device steps' wall time went.
    pub(crate) device_seconds: crate::gpu::DeviceSeconds,
    /// The fastest fluid particle's speed at the device's last step's end [m/s].
    pub(crate) device_fastest: f64,
}

impl FluidSolver {
    /// Builds the initial layout of a validated section (gates still in place).
    pub fn new(cfg: &FluidConfig) -> FluidSolver {
        let layout = layout::build(cfg);
        let on_lattice = layout.config.clone();
        let cfg = &on_lattice;
        let open_top = OpenTop {
            domain: layout.domain,
            wall_top: layout.tank.max[2],
            spacing: cfg.spacing,
            open: !cfg.tank.lid,
        };
        let kernel = Kernel::new(cfg.spacing);
        let physics = Physics {
            density: cfg.density,
            viscosity: cfg.viscosity,
            viscosity_term: cfg.viscosity_term,
            gravity: cfg.gravity,
            sound_speed: cfg.sound_speed(),
        };
        let cell = match cfg.method {
            FluidMethodName::Emps => CELL_IN_SPACINGS * cfg.spacing,
            FluidMethodName::Isph => neighbour_list::cell_edge(cfg.spacing, cfg.isph_settings().support()),
        };
        let grid = CellGrid::with_cell(layout.grid_box.lo, layout.grid_box.hi, cell);
        let centres: Vec<[f64; 3]> = cfg.body.iter().map(|b| b.centre()).collect();
        let bodies = RigidBodies::new(&layout.bodies, &centres, &layout.particles);
        let body_pose: Vec<f64> = (0..centres.len())
            .flat_map(|b| {
                let c = bodies.initial_centre(b);
                [c[0], c[1], c[2], 1.0, 0.0, 0.0, 0.0]
            })
            .collect();
        let mut monitor = StabilityMonitor::new(
            layout.domain,
            open_top,
            layout.tank,
            &cfg.wall,
            layout.body_sites.interiors(&centres, cfg.spacing),
            cfg.spacing,
            cfg.gravity,
        )
        .with_solid_sites(std::sync::Arc::new(layout.solid_sites));
        let mut particles = layout.particles;
        let open_boundaries = OpenBoundaries::new(cfg, &mut particles);
        if open_boundaries.has_inflow() {
            monitor.set_driven(); // the inflow feeds energy in
        }
        let paddle = layout.paddle.zip(cfg.wave_maker.as_ref()).map(|(pp, w)| {
            let motion = w.built.clone().expect(
                "the wave maker's motion is built when the case is loaded (FluidConfig::build_wave_maker)",
            );
            // the paddle's front face on the lattice: a flap's hinge lies on it
            Paddle::new(motion, pp, w.max[0])
        });
        if paddle.is_some() {
            monitor.set_driven(); // the paddle does work on the water
        }
        let mut grid = grid;
        let (mut method, mut method_state) = match cfg.method {
            FluidMethodName::Emps => (
                FluidMethod::Emps(Box::new(
                    EmpsStep::new(kernel, physics).with_artificial_viscosity(cfg.artificial_viscosity),
                )),
                MethodState::Emps,
            ),
            FluidMethodName::Isph => {
                let step = IsphStep::new(
                    cfg.spacing,
                    physics,
                    cfg.isph_settings(),
                    kernel.n0,
                    cfg.time_step,
                );
                (
                    FluidMethod::Isph(Box::new(step)),
                    MethodState::Isph(IsphState::default()),
                )
            }
        };
        if let Some(paddle) = &paddle {
            method.turn_solids(Some(paddle.turned_solids(None))); // at rest
        }
        method.refresh_pressure(&mut particles, &mut grid, &mut method_state);
        let mut solver = FluidSolver {
            state: FluidState {
                particles,
                grid,
                method: method_state,
                body_velocity: vec![0.0; 6 * centres.len()],
                body_exchange: BodyExchange::default(),
                body_pose,
                time: 0.0,
                steps: 0,
                gates_removed: false,
                open_boundaries,
                escaped: 0,
                totals: RunTotals::default(),
            },
            method,
            kernel,
            physics,
            monitor,
            time_step: cfg.time_step,
            advective: (cfg.method == FluidMethodName::Isph)
                .then(|| AdvectiveLimit::new(cfg.spacing, cfg.time_step)),
            started: false,
            domain: layout.domain,
            tank: layout.tank,
            bodies,
            open_top,
            paddle,
            damping: cfg.damping.iter().filter_map(DampingZone::of).collect(),
            max_removed_fraction: cfg.max_removed_fraction,
            layout_notes: layout.notes,
            warnings: cfg.warnings(),
            point_reactions: Default::default(),
            positions_version: 0,
            reaction_shares: Mutex::default(),
            device: None,
            host_stale: false,
            host_dirty: false,
            escape_pending: None,
            host_copies: (0, 0.0),
            device_seconds: Default::default(),
            device_fastest: 0.0,
        };
        solver.refresh_body_exchange();
        solver
    }

    /// Sets the body loads to the pressure pair forces of the present state (no collisions):
    /// what the bodies feel before the first step.
    fn refresh_body_exchange(&mut self) {
        let st = &mut self.state;
        let law = self.method.pressure_law(&st.particles, &st.method);
        let (loads, reaction) = self.bodies.exchange(&st.grid, &st.particles, &st.body_pose, &law);
        st.body_exchange = BodyExchange { loads, reaction };
    }

    /// What the lattice moved to build the case (one message per box; empty when all was on it).
    pub fn layout_notes(&self) -> &[String] {
        &self.layout_notes
    }

    /// What the run tells the user before it starts, each as a `warning: ` line (the coupler
    /// passes those on): [`FluidConfig::warnings`].
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Fluid particles removed after leaving through the open top ([`crate::boundaries::escape`]).
    pub fn escaped(&self) -> u64 {
        self.state.escaped
    }

    /// Fluid particles removed in all: through the open top and behind an outflow plane.
    pub fn removed(&self) -> u64 {
        self.state.escaped + self.state.open_boundaries.balance().removed
    }

    /// The method's pressure pair law on the present state (force on a solid particle from a
    /// fluid one): what wall-pressure sensors read.
    pub fn pressure_law(&self) -> PairLaw<'_> {
        self.method.pressure_law(self.particles(), &self.state.method)
    }

    /// The inflow and outflow boundaries and their particle balance.
    pub fn open_boundaries(&self) -> &OpenBoundaries {
        &self.state.open_boundaries
    }

    /// The particles (in cell order; use `id` for identity). On the GPU path, call
    /// [`FluidSolver::sync_host`] after stepping first.
    pub fn particles(&self) -> &Particles {
        assert!(
            !self.host_stale,
            "the particles are on the GPU: call FluidSolver::sync_host before reading them"
        );
        &self.state.particles
    }

    /// Number of particles (also on the GPU path without a copy).
    pub fn particle_count(&self) -> usize {
        self.device
            .as_ref()
            .map_or(self.state.particles.len(), |d| d.len())
    }

    /// The cell list of the particles, sorted for their present order (point queries).
    pub fn cell_grid(&self) -> &CellGrid {
        &self.state.grid
    }

    /// Mutable particles, e.g. to set initial velocities or body kinematics (on the GPU path
    /// they are copied back first and go to the device before the next step).
    pub fn particles_mut(&mut self) -> &mut Particles {
        self.moved();
        self.sync_host();
        self.host_dirty = self.device.is_some();
        &mut self.state.particles
    }

    /// Simulated time [s].
    pub fn time(&self) -> f64 {
        self.state.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.state.steps
    }

    /// Δt of the case [s].
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    /// The operators' radii and lattice constants.
    pub fn kernel(&self) -> &Kernel {
        &self.kernel
    }

    /// The physical parameters.
    pub fn physics(&self) -> &Physics {
        &self.physics
    }

    /// The box particles must stay in.
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The tank's inner faces.
    pub fn tank(&self) -> Aabb {
        self.tank
    }

    /// Names of the rigid bodies, in interface order.
    pub fn body_names(&self) -> &[String] {
        self.bodies.names()
    }

    /// Gives the bodies' particles the rigid velocity of `velocity` (6 per body: V, ω) and places
    /// them so that a step of length `lead` ends with them at `pose` (7 per body: centre,
    /// quaternion w x y z relative to the initial placement; see
    /// [`crate::bodies::RigidBodies::set_kinematics`]); `lead` = 0 places them at `pose`. The
    /// pose is the one the bodies' loads and the detector's inside-a-body check refer to; held
    /// until the next call.
    pub fn set_body_motion(&mut self, pose: &[f64], velocity: &[f64], lead: f64) -> Result<(), String> {
        let n = self.bodies.names().len();
        if pose.len() != 7 * n || velocity.len() != 6 * n {
            return Err(format!(
                "body motion for {n} bodies needs 7 pose and 6 velocity values per body, got {} and {}",
                pose.len(),
                velocity.len()
            ));
        }
        if pose.iter().chain(velocity).any(|v| !v.is_finite()) {
            return Err("body motion holds a value that is not finite".into());
        }
        if velocity.iter().any(|&v| v != 0.0) {
            self.monitor.set_driven();
        }
        self.moved();
        self.state.body_pose.copy_from_slice(pose);
        self.state.body_velocity.copy_from_slice(velocity);
        match self.device.as_deref_mut() {
            // placed on the device at the next step's start, from the same pose
            Some(dev) => dev.set_body_motion(pose, velocity, lead),
            None => self
                .bodies
                .set_kinematics(&mut self.state.particles, pose, velocity, lead),
        }
        Ok(())
    }

    /// Force and moment the bodies exerted on the fluid and the walls in the last step (6 per
    /// body), the fluid's share evaluated from the fluid's side; minus [`FluidSolver::body_loads`]
    /// up to round-off.
    pub fn body_reactions(&self) -> Vec<f64> {
        self.state.body_exchange.reaction.clone()
    }

    /// Force and moment of the fluid on each body in the last step, about the centre of the pose
    /// last set by [`FluidSolver::set_body_motion`], the step's end (6 per body): S1-4's viscous
    /// pair forces (when the term is on), S1-3's pressure pair forces at r* and the fluid–body collision impulses / Δt (see
    /// [`crate::bodies`]), exactly the momentum the fluid gave up to the bodies, plus the walls'
    /// contact ([`crate::bodies::body_wall_contact`]). No gravity: the body's weight is the structure
    /// solver's.
    pub fn body_loads(&self) -> Vec<f64> {
        self.state.body_exchange.loads.clone()
    }

    /// Totals since the start.
    pub fn totals(&self) -> RunTotals {
        self.state.totals
    }

    /// Bytes held by the particle arrays, the step's buffers and the cell grid.
    pub fn memory_bytes(&self) -> usize {
        let n = self.state.particles.x.capacity();
        n * (crate::particles::STATE_BYTES_PER_PARTICLE + 3 * 8 + 8) + self.state.grid.memory_bytes()
    }

    /// Removes the partition boards (done automatically before the first step, i.e. at t = 0).
    /// Returns how many particles were removed.
    pub fn remove_gates(&mut self) -> usize {
        self.moved();
        self.state.gates_removed = true;
        let removed = self.state.particles.remove_kind(Kind::Gate);
        if removed > 0 {
            let st = &mut self.state;
            self.method
                .refresh_pressure(&mut st.particles, &mut st.grid, &mut st.method);
            self.refresh_body_exchange();
        }
        removed
    }

    /// One step of length `dt` (≤ Δt); stops with a diagnostic if the state became unstable.
    pub fn step(&mut self, dt: f64) -> Result<StepTotals, Instability> {
        if self.device.is_some() {
            self.moved();
            return self.step_on_device(dt);
        }
        if !self.state.gates_removed {
            self.remove_gates();
        }
        let cut = self.advective_cut(dt);
        let st = &mut self.state;
        if !self.started {
            self.monitor.start(&st.particles);
            self.started = true;
        }
        if let Some(paddle) = &self.paddle {
            paddle.place(&mut st.particles, st.time, dt);
            self.method
                .turn_solids(Some(paddle.turned_solids(Some(st.time + dt))));
        }
        let balance = st.open_boundaries.balance();
        let open = st.open_boundaries.is_active() || self.paddle.is_some();
        st.open_boundaries.apply(&mut st.particles, st.time, dt);
        let escaped = self.remove_escaped()?;
        // particles added or removed: the cell list no longer matches their order
        let reordered = escaped > 0 || self.state.open_boundaries.balance() != balance;
        if open || escaped > 0 {
            self.moved();
        }
        self.apply_point_reactions(dt, reordered);
        let totals = self.step_on_host(dt, cut);
        self.moved();
        totals
    }

    /// Whether a step of `dt` is ISPH's advective limit cutting Δt short
    /// ([`FluidSolver::next_step_towards`]); counts it.
    pub(crate) fn advective_cut(&mut self, dt: f64) -> bool {
        let Some(limit) = &self.advective else {
            return false;
        };
        if let (longest, Some(fastest)) = limit.longest_step_at(self.fastest_fluid()) {
            if (dt - longest).abs() <= self.time_step * LANDING_SLACK {
                let totals = &mut self.state.totals;
                totals.advective_cuts += 1;
                totals.fastest_cut = totals.fastest_cut.max(fastest);
                return true;
            }
        }
        false
    }

    /// The fastest fluid particle's speed now [m/s]: the device's, reduced at its last step's
    /// end, while it is ahead of the host's copy.
    fn fastest_fluid(&self) -> f64 {
        match self.device_ahead() {
            Some(_) => self.device_fastest,
            None => crate::isph::step_length::fastest_fluid(&self.state.particles),
        }
    }

    /// The particles may have changed: shares found before are not used again.
    pub(crate) fn moved(&mut self) {
        self.positions_version += 1;
    }

    /// Removes the fluid that left through the open top ([`crate::boundaries::escape`]) and returns how many
    /// particles left; stops when more than `max_removed_fraction` of the fluid has left.
    pub(crate) fn remove_escaped(&mut self) -> Result<u64, Instability> {
        let escaped = self.open_top.remove_escaped(&mut self.state.particles);
        if escaped > 0 {
            let fluid = self.state.particles.count(Kind::Fluid) as u64;
            self.book_escaped(escaped, fluid)?;
        }
        Ok(escaped)
    }

    /// Counts `escaped` fluid particles removed through the open top, `fluid` being left; stops
    /// when more than `max_removed_fraction` of the fluid has left.
    pub(crate) fn book_escaped(&mut self, escaped: u64, fluid: u64) -> Result<(), Instability> {
        {
            let st = &mut self.state;
            st.escaped += escaped;
            let removed = st.escaped + st.open_boundaries.balance().removed;
            let fluid = fluid + removed;
            let fraction = st.escaped as f64 / fluid.max(1) as f64;
            if fraction > self.max_removed_fraction {
                return Err(Instability {
                    step: st.steps,
                    time: st.time,
                    particle: None,
                    quantity: "removed particles",
                    message: format!(
                        "{} fluid particles ({:.2} % of the fluid) have left through the open top, more than max_removed_fraction = {} %: the water is splashing out of the tank (raise its walls, add a lid) or the run is unstable; raise max_removed_fraction only if this loss is expected",
                        st.escaped,
                        100.0 * fraction,
                        100.0 * self.max_removed_fraction
                    ),
                });
            }
        }
        Ok(())
    }

    /// The rest of [`FluidSolver::step`] on the CPU (`cut`: ISPH's advective limit cut the step).
    fn step_on_host(&mut self, dt: f64, cut: bool) -> Result<StepTotals, Instability> {
        let st = &mut self.state;
        let scales = self.method.scales(dt);
        let (bodies, pose, exchange) = (&self.bodies, &st.body_pose, &mut st.body_exchange);
        let zeros = vec![0.0; 6 * bodies.names().len()];
        exchange.loads.clone_from(&zeros);
        exchange.reaction.clone_from(&zeros);
        let clock = (dt, cut, st.steps + 1, st.time + dt);
        let totals = self.method.advance(
            &mut st.particles,
            &mut st.grid,
            &mut st.method,
            clock,
            |stage, law, grid, p| {
                if bodies.names().is_empty() {
                    return;
                }
                let (mut loads, mut reaction) = bodies.exchange(grid, p, pose, law);
                if stage == Exchange::Collision {
                    // the walls' contact on the bodies; the walls take its reaction (see
                    // `body_wall_contact.rs`)
                    let walls = bodies.wall_contact_loads(grid, p, pose, &scales);
                    add_to(&mut loads, &walls);
                    reaction.iter_mut().zip(&walls).for_each(|(r, w)| *r -= w);
                }
                add_to(&mut exchange.loads, &loads);
                add_to(&mut exchange.reaction, &reaction);
            },
        )?;
        damping::relax(&self.damping, &mut st.particles, dt);
        st.steps += 1;
        st.time += dt;
        for a in 0..3 {
            st.totals.wall_impulse[a] += totals.force_from_walls[a] * dt;
        }
        st.totals.candidates += totals.candidates;
        st.totals.ppe_iterations += u64::from(totals.ppe_iterations);
        st.totals.collisions += totals.collisions;
        st.totals.particle_steps += st.particles.len() as u64;
        self.monitor
            .check(&st.particles, st.steps, st.time, dt, &st.body_pose)?;
        Ok(totals)
    }

    /// Sets the point reactions of the unresolved coupling (6 per reaction: point, force) with
    /// their paired sample points (3 per reaction, or none) and their members' widths (1 per
    /// reaction, or none: all points), applied from the next step on.
    pub fn set_point_reactions(&mut self, reactions: &[f64], sample_points: &[f64], widths: &[f64]) {
        let r = &mut self.point_reactions;
        r.reactions.clear();
        r.reactions.extend_from_slice(reactions);
        r.sample_points.clear();
        r.sample_points.extend_from_slice(sample_points);
        r.widths.clear();
        r.widths.extend_from_slice(widths);
    }

    /// The point reactions as accelerations over a step of `dt`: each fluid particle's velocity
    /// changes by its share of the reactions (S2-24 over the members' footprints) / its mass × dt.
    /// `reordered`: particles were added or removed since the cell list was sorted (it is sorted
    /// again first).
    fn apply_point_reactions(&mut self, dt: f64, reordered: bool) {
        if self.point_reactions.reactions.is_empty() {
            return;
        }
        let st = &mut self.state;
        if reordered {
            st.grid.sort(&mut st.particles, &mut Vec::new());
        }
        let r = &self.point_reactions;
        let spread = self.spread_point_reactions(&r.reactions, &r.sample_points, &r.widths);
        let scale = dt / self.particle_mass();
        let p = &mut self.state.particles;
        for (i, f) in spread.force.chunks_exact(3).enumerate() {
            p.vx[i] += f[0] * scale;
            p.vy[i] += f[1] * scale;
            p.vz[i] += f[2] * scale;
        }
        for c in 0..3 {
            self.state.totals.reaction_impulse[c] += spread.total[c] * dt;
            self.state.totals.unapplied_impulse[c] += spread.unapplied_force[c] * dt;
        }
    }

    /// The point reactions `reactions` (6 each: point, force) spread over the fluid particles
    /// (S2-24 over the footprints of members `widths` wide, 1 each or none) with their paired
    /// sample points (3 each, or none), by the shares found while sampling at these particles'
    /// positions, these centroids, sample points and widths where there are (the same to the
    /// last bit), else by searching the cell list.
    pub fn spread_point_reactions(&self, reactions: &[f64], sample_points: &[f64], widths: &[f64]) -> Spread {
        let st = &self.state;
        let cache = self.reaction_shares.lock();
        let known = match cache.as_deref() {
            Ok(Some(c))
                if c.version == self.positions_version
                    && c.points == sample_points
                    && c.widths == widths
                    && c.centroids.len() == reactions.len() / 2
                    && reactions
                        .chunks_exact(6)
                        .zip(c.centroids.chunks_exact(3))
                        .all(|(r, c)| r[..3] == *c) =>
            {
                &c.shares[..]
            }
            _ => &[],
        };
        unresolved::spreading::spread_reusing(
            &st.particles,
            &st.grid,
            self.kernel.spacing,
            reactions,
            sample_points,
            widths,
            known,
        )
    }

    /// As [`FluidSolver::sample_points`], finding too the shares of the point reactions
    /// `reactions` (6 each: centroid, force; paired with `points`; their members `widths` wide, 1
    /// each or none) for the next step's spreading ([`FluidSolver::spread_point_reactions`]; see
    /// [`unresolved::sampling::sample_with_shares`]).
    pub fn sample_points_for(
        &self,
        points: &[f64],
        reactions: &[f64],
        widths: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        if let Some(dev) = self.device_ahead() {
            return dev.sample_points(points);
        }
        let (samples, shares) = unresolved::sampling::sample_with_shares(
            self.particles(),
            &self.state.grid,
            self.kernel.spacing,
            points,
            reactions,
            widths,
        );
        if let Ok(mut cache) = self.reaction_shares.lock() {
            *cache = (!shares.is_empty()).then(|| ReactionShares {
                version: self.positions_version,
                points: points.to_vec(),
                centroids: reactions
                    .chunks_exact(6)
                    .flat_map(|r| r[..3].iter().copied())
                    .collect(),
                widths: widths.to_vec(),
                shares,
            });
        }
        (
            samples.iter().flat_map(|s| s.velocity).collect(),
            samples.iter().map(|s| s.lambda_min).collect(),
        )
    }

    /// Velocity and λ_min at `points` (3 per point) for the unresolved coupling (3 and 1 per point).
    pub fn sample_points(&self, points: &[f64]) -> (Vec<f64>, Vec<f64>) {
        if let Some(dev) = self.device_ahead() {
            return dev.sample_points(points);
        }
        let samples =
            unresolved::sampling::sample(self.particles(), &self.state.grid, self.kernel.spacing, points);
        (
            samples.iter().flat_map(|s| s.velocity).collect(),
            samples.iter().map(|s| s.lambda_min).collect(),
        )
    }

    /// The next step's length towards `t_end`: the longest step (Δt, or with ISPH shorter
    /// where the fluid outruns it, [`AdvectiveLimit`]), or the remainder when it is at most that
    /// (the last step lands exactly); `None` when `t_end` is reached (up to rounding).
    pub fn next_step_towards(&self, t_end: f64) -> Option<f64> {
        let left = t_end - self.state.time;
        let longest = match &self.advective {
            Some(limit) => limit.longest_step_at(self.fastest_fluid()).0,
            None => self.time_step,
        };
        if left <= self.time_step * LANDING_SLACK {
            None
        } else if left <= longest * (1.0 + LANDING_SLACK) {
            Some(left)
        } else {
            Some(longest)
        }
    }

    /// Steps with Δt until `t_end`, shortening the last step to land exactly on it.
    pub fn advance_to(&mut self, t_end: f64) -> Result<(), Instability> {
        while let Some(dt) = self.next_step_towards(t_end) {
            self.step(dt)?;
        }
        self.land_on(t_end);
        Ok(())
    }

    /// Sets the clock to `t_end` when the steps have reached it up to rounding.
    pub fn land_on(&mut self, t_end: f64) {
        if (self.state.time - t_end).abs() <= self.time_step * LANDING_SLACK {
            self.state.time = t_end;
        }
    }

    /// A copy of the state (particles, cell list, the method's own state, bodies, clock,
    /// open boundaries) for implicit coupling (on the GPU path, after [`FluidSolver::sync_host`]).
    pub fn save_state(&self) -> FluidState {
        assert!(
            !self.host_stale,
            "the particles are on the GPU: call FluidSolver::sync_host before saving the state"
        );
        self.state.clone()
    }

    /// Puts back a state saved by [`FluidSolver::save_state`].
    pub fn restore_state(&mut self, s: &FluidState) {
        self.moved();
        self.state.clone_from(s);
        self.host_stale = false;
        self.host_dirty = self.device.is_some();
    }

    /// What a resumed run needs besides [`FluidState`] (not part of it because implicit coupling's
    /// restores must not touch it).
    pub fn run_state(&self) -> RunState {
        RunState {
            started: self.started,
            energy_reference: self.monitor.energy_reference(),
            point_reactions: self.point_reactions.clone(),
        }
    }

    /// Puts back a [`FluidSolver::run_state`].
    pub fn restore_run_state(&mut self, r: RunState) {
        self.started = r.started;
        self.monitor.set_energy_reference(r.energy_reference);
        self.point_reactions = r.point_reactions;
    }

    /// The method's own state (ISPH: surface flags, last PPE record).
    pub fn method_state(&self) -> &MethodState {
        &self.state.method
    }

    /// Wall time per stage of the method's step since the start.
    pub fn stage_times(&self) -> &StageTimes {
        if let Some(d) = &self.device {
            return d.stage_times();
        }
        self.method.stage_times()
    }

    /// Total momentum of the fluid [kg m/s].
    pub fn fluid_momentum(&self) -> [f64; 3] {
        let m = self.physics.density * self.kernel.spacing.powi(3);
        let p = self.particles();
        let mut sum = [0.0; 3];
        for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
            sum[0] += m * p.vx[i];
            sum[1] += m * p.vy[i];
            sum[2] += m * p.vz[i];
        }
        sum
    }

    /// Mass of one particle ρ0 Δs³ [kg].
    pub fn particle_mass(&self) -> f64 {
        self.physics.density * self.kernel.spacing.powi(3)
    }
}

/// `a += b`, element-wise.
fn add_to(a: &mut [f64], b: &[f64]) {
    a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
}
