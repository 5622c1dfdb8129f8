//! The solver's step on the device: the GPU path of [`FluidSolver::step`]. The host keeps the
//! clock, the totals and the instability detector's thresholds; the particles stay on the device
//! and are copied back whole only when a frame ([`FluidSolver::frame_particles`]), a checkpoint
//! or a diagnostic ([`FluidSolver::sync_host`]) needs them; probes read them without a whole copy
//! ([`crate::sensors::view`]).

use super::device::{GpuDevice, NoAdapter};
use super::drag::{NOT_APPLIED, SPREAD_AT_CENTROID, SPREAD_AT_SAMPLE_POINT};
use super::frame::Frame;
use super::isph::IsphSetup;
use super::paddle::{PaddlePlacement, PaddleSites};
use super::solids::SolidBits;
use super::step::{GpuEmps, GpuSetup};
use crate::isph::step_length::pressure_step;
use crate::method::{ppe_failure, FluidMethod, MethodState, StepTotals};
use crate::particles::Particles;
use crate::solver::FluidSolver;
use crate::stability::Instability;
use schemas::case::fluid::{FluidBackend, FluidConfig};
use std::fmt;

/// Why a solver could not be put on the GPU.
#[derive(Debug, Clone, PartialEq)]
pub enum GpuStartError {
    /// No Vulkan adapter (bad usage: the message says how to get one).
    NoAdapter(NoAdapter),
    /// The case is beyond what the GPU path handles so far.
    Unsupported(String),
}

impl fmt::Display for GpuStartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GpuStartError::NoAdapter(e) => write!(f, "{e}"),
            GpuStartError::Unsupported(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for GpuStartError {}

/// Where a GPU run's steps spent their wall time so far [s]: the device step (its passes and
/// the wait for its reduction), the open boundaries (the device's pass with its counts and
/// appended rows, and the host's rule on its copy of the strip within it).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DeviceSeconds {
    pub steps: f64,
    pub open_boundaries: f64,
    pub strip_rule: f64,
}

/// Books the step's point reactions (6 each: centroid, force) by the states the device found
/// for them ([`crate::gpu::drag`]): the impulse of those it spread as handed to the fluid, of
/// those with no fluid near as not applied (as [`FluidSolver`]'s CPU step books them).
fn book_reactions(totals: &mut crate::solver::RunTotals, reactions: &[f64], states: &[u32], dt: f64) {
    for (r, &state) in reactions.chunks_exact(6).zip(states) {
        let booked = match state {
            SPREAD_AT_CENTROID | SPREAD_AT_SAMPLE_POINT => &mut totals.reaction_impulse,
            NOT_APPLIED => &mut totals.unapplied_impulse,
            _ => continue,
        };
        for c in 0..3 {
            booked[c] += r[3 + c] * dt;
        }
    }
}

impl FluidSolver {
    /// Builds the solver of a validated section on the backend it names (`backend = "gpu"`: the
    /// gates are removed on the host, then the particles go to the device).
    pub fn with_backend(cfg: &FluidConfig) -> Result<FluidSolver, GpuStartError> {
        let mut solver = FluidSolver::new(cfg);
        if cfg.backend == FluidBackend::Gpu {
            solver.to_device(cfg, GpuDevice::open().map_err(GpuStartError::NoAdapter)?)?;
        }
        Ok(solver)
    }

    /// Moves the particles to `dev`; from now on [`FluidSolver::step`] runs there.
    pub fn to_device(&mut self, cfg: &FluidConfig, dev: GpuDevice) -> Result<(), GpuStartError> {
        cfg.gpu_support("fluid")
            .map_err(|e| GpuStartError::Unsupported(format!("`{}`: {}", e.key, e.message)))?;
        self.start_device(cfg, dev, cfg.gpu_frame_origin(), cfg.gpu_quantum())
    }

    /// [`FluidSolver::to_device`] with the device measuring positions from `origin` instead of
    /// the tank's lower corner, in wide positions when the tank's far corners lie further from
    /// it than plain f32 keeps ([`schemas::case::fluid::gpu_wide_quantum`]): the device's
    /// numbers are then those of a tank as far from its frame's origin, which is how the wide
    /// positions are checked without a tank of 10⁵ spacings.
    pub fn to_device_from(
        &mut self,
        cfg: &FluidConfig,
        dev: GpuDevice,
        origin: [f64; 3],
    ) -> Result<(), GpuStartError> {
        cfg.gpu_support("fluid")
            .map_err(|e| GpuStartError::Unsupported(format!("`{}`: {}", e.key, e.message)))?;
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let far = schemas::validation::largest(
            (0..3).flat_map(|a| [(lo[a] - origin[a]).abs(), (hi[a] - origin[a]).abs()]),
            0.0,
        );
        let quantum = schemas::case::fluid::gpu_wide_quantum(far, cfg.spacing);
        let most = schemas::case::fluid::GPU_MAX_WIDE_ROUNDING * cfg.spacing;
        if let Some(q) = quantum.filter(|&q| 0.5 * q > most) {
            return Err(GpuStartError::Unsupported(format!(
                "{far} m from the device's frame origin wide positions would round by {:.2e} m, more than {most:.2e} m (0.02 Δs)",
                0.5 * q
            )));
        }
        self.start_device(cfg, dev, origin, quantum)
    }

    /// Moves the particles to `dev` with the device's frame at `origin` and wide positions of
    /// `quantum` (none: plain f32).
    fn start_device(
        &mut self,
        cfg: &FluidConfig,
        dev: GpuDevice,
        origin: [f64; 3],
        quantum: Option<f64>,
    ) -> Result<(), GpuStartError> {
        self.remove_gates();
        if let Some(q) = quantum {
            // wide positions test cells by their high part, within half a quantum: cells a
            // quantum wider keep every pair within the cells searched (gpu/frame.rs)
            let st = &mut self.state;
            st.grid = st.grid.widened(q);
            st.grid.sort(&mut st.particles, &mut Vec::new());
        }
        let setup = GpuSetup {
            kernel: self.kernel,
            physics: self.physics,
            domain: self.domain,
            open_top: self.open_top,
            tank: self.tank,
            walls: self.monitor.wall_boxes().to_vec(),
            bodies: self.monitor.body_interiors().to_vec(),
            members: self.bodies.members().to_vec(),
            body_pose: self.state.body_pose.clone(),
            body_velocity: self.state.body_velocity.clone(),
            solids: self
                .monitor
                .solid_sites()
                .solid()
                .map(|s| SolidBits::of(s, "the mesh solids' and terrains'"))
                .transpose()
                .map_err(GpuStartError::Unsupported)?,
            damping: cfg.damping.clone(),
            artificial_viscosity: cfg.artificial_viscosity,
            paddle: self.paddle.as_ref().map(PaddleSites::of),
            headroom: self.inflow_headroom(),
            frame: Frame { origin, quantum },
        };
        let mut step = GpuEmps::new(dev, &setup, &self.state.grid, &self.state.particles)
            .map_err(GpuStartError::Unsupported)?;
        if let FluidMethod::Isph(isph) = &self.method {
            let st = &self.state;
            let isph_setup = IsphSetup {
                kernel: isph.kernel,
                physics: isph.physics,
                settings: isph.settings,
                n0_mps: self.kernel.n0,
                particles: &st.particles,
                grid: &st.grid,
            };
            step.use_isph(&isph_setup).map_err(GpuStartError::Unsupported)?;
        }
        self.device_fastest = crate::isph::step_length::fastest_fluid(&self.state.particles);
        self.device = Some(Box::new(step));
        self.host_stale = false;
        Ok(())
    }

    /// Room the device's arrays keep for particles an inflow adds: a quarter of the start's
    /// count and at least 4096 (regrown by half when full).
    fn inflow_headroom(&self) -> usize {
        match self.state.open_boundaries.has_inflow() {
            true => (self.state.particles.len() / 4).max(4096),
            false => 0,
        }
    }

    /// The device step, when the solver runs on a GPU.
    pub fn device(&self) -> Option<&GpuEmps> {
        self.device.as_deref()
    }

    /// Mutable device step (e.g. to time its stages).
    pub fn device_mut(&mut self) -> Option<&mut GpuEmps> {
        self.device.as_deref_mut()
    }

    /// Copies the device's particles to the host when the device is ahead (checkpoints, the
    /// detector's findings, the end of a run), re-sorting the host's cell list for its point
    /// queries. Nothing on the CPU path.
    pub fn sync_host(&mut self) {
        if let (Some(dev), true) = (self.device.as_deref_mut(), self.host_stale) {
            let started = std::time::Instant::now();
            self.positions_version += 1;
            let st = &mut self.state;
            dev.download(&mut st.particles);
            st.grid.sort(&mut st.particles, &mut Vec::new());
            self.host_stale = false;
            self.host_copies.0 += 1;
            self.host_copies.1 += started.elapsed().as_secs_f64();
        }
    }

    /// The particles as they are now, for a frame: the host's own when they are current (the CPU
    /// path), else a whole copy from the device into a set of its own, in the device's order
    /// (counted with [`FluidSolver::host_copies`]); the host's copy stays behind the device, so
    /// no host cell sort follows, and no second copy is made when the frame is kept back.
    pub fn frame_particles(&mut self) -> std::borrow::Cow<'_, Particles> {
        match (self.device.as_deref_mut(), self.host_stale) {
            (Some(dev), true) => {
                let started = std::time::Instant::now();
                let mut copy = Particles::default();
                dev.download(&mut copy);
                self.host_copies.0 += 1;
                self.host_copies.1 += started.elapsed().as_secs_f64();
                std::borrow::Cow::Owned(copy)
            }
            _ => std::borrow::Cow::Borrowed(&self.state.particles),
        }
    }

    /// Whole copies of the particles from the device so far (frames through
    /// [`FluidSolver::frame_particles`]; checkpoints, the detector's findings and a run's end
    /// through [`FluidSolver::sync_host`]), and their wall seconds (with the host's cell sort
    /// after those of `sync_host`).
    pub fn host_copies(&self) -> (u64, f64) {
        self.host_copies
    }

    /// Where the device steps' wall time went so far (zeros on the CPU path).
    pub fn device_seconds(&self) -> DeviceSeconds {
        self.device_seconds
    }

    /// The device step when its particles are ahead of the host's copy (`None` on the CPU path
    /// and right after [`FluidSolver::sync_host`]).
    pub(crate) fn device_ahead(&self) -> Option<&GpuEmps> {
        self.device.as_deref().filter(|_| self.host_stale)
    }

    /// The particles in the box `lo`–`hi` (and some around it) when they are on the device ahead
    /// of the host's copy, gathered without copying the rest ([`super::gather`]); `None` when the
    /// host's particles are current (the CPU path, or right after [`FluidSolver::sync_host`]).
    pub fn device_particles_in(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<Particles> {
        self.device_ahead().map(|dev| dev.particles_in(lo, hi))
    }

    /// All the particles, light ([`GpuEmps::particles_all`]), when they are on the device ahead of
    /// the host's copy; `None` when the host's particles are current.
    pub fn device_particles_all(&self) -> Option<Particles> {
        self.device_ahead().map(|dev| dev.particles_all())
    }

    /// One step on the device (see the module doc): removals through the open top found by the
    /// last step happen on the device first, the detector's findings are explained by the host's
    /// detector on a copy.
    pub(crate) fn step_on_device(&mut self, dt: f64) -> Result<StepTotals, Instability> {
        // ISPH's advective limit from the device's fastest particle, and its PPE's tolerance
        let cut = self.advective_cut(dt);
        let tolerance = match &self.method {
            FluidMethod::Isph(s) => s.settings.ppe_tolerance,
            FluidMethod::Emps(_) => 0.0,
        };
        if !self.started {
            self.sync_host();
            self.monitor.start(&self.state.particles);
            self.started = true;
        }
        let device_error = |time: f64, steps: u64, quantity: &'static str, message: String| Instability {
            step: steps + 1,
            time,
            particle: None,
            quantity,
            message,
        };
        if let (Some(dev), true) = (self.device.as_deref_mut(), self.host_dirty) {
            dev.upload(&self.state.particles)
                .map_err(|m| device_error(self.state.time, self.state.steps, "GPU arrays", m))?;
            self.host_dirty = false;
        }
        // the fluid that left through the open top in the last step, removed on the device by
        // the rule its scan counted with (`gpu/escape.rs`)
        if let Some(fluid) = self.escape_pending.take() {
            let escaped = self.device.as_deref_mut().map_or(0, |dev| dev.remove_escaped());
            self.book_escaped(escaped, fluid.saturating_sub(escaped))?;
        }
        let Some(dev) = self.device.as_deref_mut() else {
            unreachable!("step_on_device is called with a device")
        };
        // the open boundaries before the step, as on the CPU: the host's copy of the strip runs
        // the CPU's rule, the device converts, moves and removes by it (`gpu/open_boundary.rs`)
        if self.state.open_boundaries.is_active() {
            let st = &mut self.state;
            let started = std::time::Instant::now();
            let plan = dev
                .strip
                .plan(&mut st.open_boundaries, st.time, dt)
                .map_err(|m| device_error(st.time, st.steps, "inflow strip", m))?;
            self.device_seconds.strip_rule += started.elapsed().as_secs_f64();
            let [entered, removed, withdrawn] = dev
                .open_boundaries(&plan.pass, &plan.rows)
                .map_err(|m| device_error(st.time, st.steps, "GPU arrays", m))?;
            if entered != plan.entered || withdrawn != plan.withdrawn {
                return Err(device_error(
                    st.time,
                    st.steps,
                    "inflow strip",
                    format!(
                        "the GPU's inflow strip parted from the host's: {entered} particles entered and {withdrawn} were withdrawn on the device, {} and {} on the host; use backend = \"cpu\"",
                        plan.entered, plan.withdrawn
                    ),
                ));
            }
            st.open_boundaries.add_removed(removed);
            self.device_seconds.open_boundaries += started.elapsed().as_secs_f64();
        }
        // the paddle where the CPU path places it before its step from t to t + dt
        if let Some(paddle) = &self.paddle {
            dev.set_paddle(&PaddlePlacement::of(paddle, self.state.time, dt));
        }
        // the drag coupling's reactions, spread by the device at the step's start
        let r = &self.point_reactions;
        if !r.reactions.is_empty() || dev.spreads_reactions() {
            dev.set_point_reactions(&r.reactions, &r.sample_points, &r.widths);
        }
        let started = std::time::Instant::now();
        let (step, time) = (self.state.steps + 1, self.state.time + dt);
        let (report, ppe) = match &mut self.state.method {
            MethodState::Isph(isph) => {
                let pressure_step = pressure_step(dt, self.time_step, cut, isph.last_pressure_step);
                let (report, ppe) = dev
                    .advance_isph(dt, pressure_step)
                    .map_err(|f| ppe_failure(f, tolerance, step, time))?;
                isph.last_pressure_step = Some(pressure_step);
                isph.ppe = ppe;
                (report, ppe.iterations)
            }
            MethodState::Emps => (dev.advance(dt), 0),
        };
        self.device_fastest = report.fastest;
        self.device_seconds.steps += started.elapsed().as_secs_f64();
        let n = dev.len() as u64;
        self.host_stale = true;
        let st = &mut self.state;
        book_reactions(&mut st.totals, &r.reactions, &dev.reaction_states(), dt);
        st.steps += 1;
        st.time += dt;
        for a in 0..3 {
            st.totals.wall_impulse[a] += report.force_from_walls[a] * dt;
        }
        st.totals.candidates += report.candidates;
        st.totals.particle_steps += n;
        st.totals.ppe_iterations += u64::from(ppe);
        // the bodies' loads and the fluid's reaction, two sums on the device (by body particle,
        // by fluid particle) that the coupler's ledger compares
        st.body_exchange.loads.clear();
        st.body_exchange.loads.extend_from_slice(dev.body_loads());
        st.body_exchange.reaction.clear();
        st.body_exchange.reaction.extend_from_slice(dev.body_reactions());
        self.escape_pending = (report.escaped > 0).then_some(report.fluid);
        let energy_over = self
            .monitor
            .energy_limit()
            .is_some_and(|limit| !report.energy.is_finite() || report.energy > limit);
        if report.finding.is_some() || energy_over {
            self.sync_host();
            let st = &self.state;
            self.monitor
                .check(&st.particles, st.steps, st.time, dt, &st.body_pose)?;
        }
        Ok(StepTotals {
            force_from_walls: report.force_from_walls,
            candidates: report.candidates,
            ppe_iterations: ppe,
            collisions: 0,
        })
    }
}
