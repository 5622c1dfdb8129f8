//! One E-MPS step on the device, the stages of [`crate::emps::step`] in the same order, after the
//! wave maker's paddle and the bodies are placed (as [`crate::solver`] places them before the
//! method's step; [`super::paddle`], [`super::bodies`]): (when the viscous term is on or the drag
//! coupling's reactions are spread) cell sort at r^k, the reactions spread ([`super::drag`]) and
//! (viscous) S1-4, then S1-10/S1-11, cell sort at r*, S1-15 with S1-14, S1-3 (with the artificial
//! viscosity when on), S1-12/S1-13, the collision pass and its update, the damping zones (as
//! [`crate::solver`] relaxes them after the method's step), and the device reduction of the
//! detector and the totals. Only the 48 B per 256 particles of that reduction come back per step,
//! and with resolved bodies 96 B per body (their loads, the fluid's reaction summed from the
//! fluid's side and the walls' contact, each a force and a moment reduced on the device after each
//! exchange: [`super::bodies`]).

use super::bodies::{self, BodyLoad};
use super::body_inside;
use super::buffers::{
    map_read, Buffers, BODY_KIN, BODY_LOADS, BOXES, CELL_COUNT, DAMPING, MEMBERS, OPEN_COUNTERS, PARTIALS,
    SOLID_BITS, SUMS,
};
use super::cell_sort;
use super::damping;
use super::device::GpuDevice;
use super::drag::DragState;
use super::frame::Frame;
use super::isph::GpuIsph;
use super::kernels::{dispatch, dispatch_layers, Kernels, WG, WIDE_WG};
use super::open_boundary::{OpenPass, StripCopy};
use super::paddle::{PaddlePlacement, PaddleSites};
use super::params::{f32x3, Params};
use super::reduce::{self, Partial, StepReport};
use super::solids::SolidBits;
use crate::bodies::body_wall_contact::CONTACT_PERIOD_STEPS;
use crate::boundaries::escape::OpenTop;
use crate::emps::kernel::Kernel;
use crate::neighbours::collision::{COLLISION_DISTANCE, RESTITUTION};
use crate::neighbours::neighbour_search::{CellGrid, PAD};
use crate::particles::body_interior::BodyInterior;
use crate::particles::layout::Domain;
use crate::particles::Particles;
use crate::physics::Physics;
use crate::stage_timer::StageTimes;
use schemas::case::fluid::{Aabb, DampingConfig};
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// What the device step needs to know of the case: the operators, the physics, the grid and the
/// detector's geometry.
#[derive(Debug, Clone)]
pub struct GpuSetup {
    pub kernel: Kernel,
    pub physics: Physics,
    pub domain: Domain,
    pub open_top: OpenTop,
    pub tank: Aabb,
    /// The detector's wall blocks: the case's on the lattice less half a spacing, those of the
    /// CPU's detector ([`crate::stability::StabilityMonitor::wall_boxes`]).
    pub walls: Vec<Aabb>,
    /// The detector's bodies ([`crate::stability::StabilityMonitor::body_interiors`]).
    pub bodies: Vec<BodyInterior>,
    /// The bodies' particles: (id, body, offset from the body's initial centre), sorted by id.
    pub members: Vec<(u32, usize, [f64; 3])>,
    /// Each body's pose (7) and velocity (6) at the start.
    pub body_pose: Vec<f64>,
    pub body_velocity: Vec<f64>,
    /// The mesh solids' and terrains' sites the detector checks against (`None` without any).
    pub solids: Option<SolidBits>,
    /// The damping zones, relaxed after each step.
    pub damping: Vec<DampingConfig>,
    /// α of the E-MPS artificial viscosity (0: off).
    pub artificial_viscosity: f64,
    /// The wave maker's paddle (`None` without one), placed before each step by
    /// [`GpuEmps::set_paddle`]'s placement.
    pub paddle: Option<PaddleSites>,
    /// Room for this many particles more than the start's (an inflow adds particles; the
    /// arrays are regrown when they are full: [`GpuEmps::open_boundaries`]).
    pub headroom: usize,
    /// Where the device measures positions from ([`super::frame`]).
    pub frame: Frame,
}

/// What the buffers were made for, besides the particles (to regrow them).
#[derive(Debug, Clone, Copy)]
struct Shape {
    cells: usize,
    boxes: usize,
    bodies: (usize, usize),
    scene: (usize, usize),
    /// The largest binding the device allows [B].
    largest: u64,
}

/// The E-MPS step on a GPU: the device, its buffers and kernels.
pub struct GpuEmps {
    pub dev: GpuDevice,
    pub(super) buffers: Buffers,
    pub(super) kernels: Kernels,
    pub(super) params: Params,
    pub(super) n: usize,
    viscous: bool,
    /// Where the reduction's partials and the bodies' loads are read back (reused every step).
    staging: wgpu::Buffer,
    /// Bodies on the device; their loads and the fluid's reaction of the last step (6 per body
    /// each); a pose handed over and not yet applied to the body particles.
    pub(super) bodies: usize,
    body_loads: Vec<f64>,
    body_reactions: Vec<f64>,
    place_pending: bool,
    /// Submit and wait after each stage to time it (the benchmark); off in runs.
    pub(super) profile: bool,
    pub(super) times: StageTimes,
    shape: Shape,
    /// Where the open boundaries' counts are read back.
    open_staging: wgpu::Buffer,
    /// The host's copy of the inflow strip (empty without an inflow).
    pub strip: StripCopy,
    /// Bytes the filtered sensors' gathers copied back ([`super::gather`]).
    pub(super) gathered: AtomicU64,
    /// The drag coupling's buffers, made when it is first used ([`super::drag`]).
    pub(super) drag: Mutex<Option<DragState>>,
    /// Where the device measures positions from ([`super::frame`]).
    pub(super) frame: Frame,
    /// The ISPH step, when the case's method is ISPH ([`super::isph`]).
    pub(super) isph: Option<Box<GpuIsph>>,
}

impl fmt::Debug for GpuEmps {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "GpuEmps({} particles on {:?})", self.n, self.dev)
    }
}

impl GpuEmps {
    /// Uploads `p` (sorted by `grid`, whose geometry the device copies) to `dev`.
    pub fn new(dev: GpuDevice, setup: &GpuSetup, grid: &CellGrid, p: &Particles) -> Result<GpuEmps, String> {
        let n = p.len();
        let capacity = n + setup.headroom;
        let (origin, cell, dims) = grid.geometry();
        let cells = dims[0] * dims[1] * dims[2];
        let limits = dev.device.limits();
        let largest = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if 16 * capacity as u64 > largest {
            return Err(format!(
                "the GPU binds at most {largest} B per array, {capacity} particles need {} B; use backend = \"cpu\"",
                16 * capacity as u64
            ));
        }
        let starts = 4 * (cells as u64 + 1);
        if starts > largest || cells >= u32::MAX as usize {
            return Err(format!(
                "the GPU binds at most {largest} B per array, the case's cell grid of {} × {} × {} = {cells} cells (cells of {cell:.3e} m over the tank and its headroom) needs {starts} B for its cell starts; use a coarser spacing or backend = \"cpu\"",
                dims[0], dims[1], dims[2]
            ));
        }
        let k = &setup.kernel;
        let ph = &setup.physics;
        let frame = setup.frame;
        let mass = ph.density * k.spacing.powi(3);
        let boxes: Vec<[f32; 4]> = setup
            .walls
            .iter()
            .flat_map(|b| {
                let (lo, hi) = (frame.point(b.min), frame.point(b.max));
                [[lo[0], lo[1], lo[2], 0.0], [hi[0], hi[1], hi[2], 0.0]]
            })
            .collect();
        // the solids' sites, then the bodies' table and sites (`body_inside`)
        let mut site_words = setup.solids.as_ref().map_or(Vec::new(), |s| s.words.clone());
        let body_table = site_words.len();
        site_words.extend(body_inside::words(&setup.bodies, body_table)?);
        if 4 * site_words.len() as u64 > largest {
            return Err(format!(
                "the GPU binds at most {largest} B per array, the mesh solids', terrains' and bodies' sites need {} B (one bit per site of the tank's lattice with solids, and of each mesh body's block of sites); use a coarser spacing or backend = \"cpu\"",
                4 * site_words.len() as u64
            ));
        }
        let zones = damping::zones(&setup.damping, &frame);
        let viscous = ph.viscous();
        let n_bodies = setup.body_pose.len() / 7;
        // the paddle's rest positions follow the bodies' members in their buffer
        let mut member_rows = bodies::members(&setup.members);
        let paddle_row = member_rows.len();
        let paddle = setup.paddle.as_ref();
        member_rows.extend(paddle.map_or(Vec::new(), |p| p.rows(&frame)));
        let paddle_count = member_rows.len() - paddle_row;
        // artificial_viscosity.rs: q_ij = −α ρ0 c h (u_ij · r_ij) / (r² + 0.01 h²), h = r_e,grad / 2
        let h_av = 0.5 * k.re_grad;
        let hinge_x = paddle.map_or((0.0, 0.0), |p| frame.split_along(0, p.hinge[0]));
        let hinge_z = paddle.map_or((0.0, 0.0), |p| frame.split_along(2, p.hinge[1]));
        let params = Params {
            origin: frame.point(origin),
            inv_cell: (1.0 / cell) as f32,
            dims: dims.map(|d| d as u32),
            n: n as u32,
            gravity: f32x3(ph.gravity),
            dt: 0.0,
            re: k.re as f32,
            re_grad: k.re_grad as f32,
            inv_n0: (1.0 / k.n0) as f32,
            grad_factor: k.gradient_factor() as f32,
            lap_factor: k.laplacian_factor() as f32,
            nu: if viscous { ph.viscosity as f32 } else { 0.0 },
            rho: ph.density as f32,
            c2: (ph.sound_speed * ph.sound_speed) as f32,
            coll_dist: (COLLISION_DISTANCE * k.spacing) as f32,
            restitution: RESTITUTION as f32,
            reach: grid.reach(k.re) as u32,
            reach_grad: grid.reach(k.re_grad) as u32,
            reach_coll: grid.reach(COLLISION_DISTANCE * k.spacing) as u32,
            cells: cells as u32,
            pad: PAD as u32,
            viscous: u32::from(viscous),
            domain_lo: frame.point(setup.domain.lo),
            spacing: k.spacing as f32,
            domain_hi: frame.point(setup.domain.hi),
            wall_top: frame.along(2, setup.open_top.wall_top),
            tank_lo: frame.point(setup.tank.min),
            open_top: u32::from(setup.open_top.open),
            tank_hi: frame.point(setup.tank.max),
            n_boxes: (boxes.len() / 2) as u32,
            mass: mass as f32,
            volume: (mass / ph.density) as f32,
            scan_blocks: cell_sort::scan_blocks(cells as u32),
            n_bodies: n_bodies as u32,
            n_members: setup.members.len() as u32,
            reach_contact: grid.reach(k.spacing) as u32,
            contact_k: 0.0,
            contact_c: 0.0,
            solid_lo: frame.point(setup.solids.as_ref().map_or(frame.origin, |s| s.origin)),
            solid_inv_ds: setup.solids.as_ref().map_or(0.0, |s| (1.0 / s.spacing) as f32),
            solid_n: setup.solids.as_ref().map_or([0; 3], |s| s.n),
            solids: u32::from(setup.solids.is_some()),
            n_damping: zones.len() as u32,
            av_scale: (-setup.artificial_viscosity * ph.density * ph.sound_speed * h_av) as f32,
            av_eta2: (0.01 * h_av * h_av) as f32,
            // below 2²⁷: the solids' lattice numbers at most 2³² sites (`SolidBits::of`)
            body_table: body_table as u32,
            paddle_first: paddle.map_or(0, |p| p.first),
            paddle_count: paddle_count as u32,
            paddle_row: paddle_row as u32,
            paddle_shift: 0.0,
            paddle_speed: 0.0,
            paddle_cos_m1: 0.0,
            paddle_sin: 0.0,
            paddle_dcos: 0.0,
            paddle_dsin: 0.0,
            hinge_x: hinge_x.0,
            hinge_z: hinge_z.0,
            quantum: frame.quantum.map_or(0.0, |q| q as f32),
            inflow_u: 0.0,
            inflow_dx: 0.0,
            inflow_enter: f32::INFINITY,
            inflow_cut: f32::INFINITY,
            outflow_x: f32::INFINITY,
            outflow_low: 0.0,
            hinge_low_x: hinge_x.1,
            hinge_low_z: hinge_z.1,
        };
        let groups = capacity.div_ceil(WIDE_WG as usize);
        let sizes = (n_bodies, member_rows.len());
        let scene = (zones.len(), site_words.len());
        let shape = Shape {
            cells,
            boxes: boxes.len() / 2,
            bodies: sizes,
            scene,
            largest,
        };
        let mut buffers = Buffers::new(
            &dev,
            (capacity, frame.wide()),
            cells,
            shape.boxes,
            groups,
            sizes,
            scene,
        );
        let kernels = Kernels::new(&dev, &buffers);
        buffers.write(&dev, BOXES, &boxes);
        buffers.write(&dev, DAMPING, &zones);
        buffers.write(&dev, SOLID_BITS, &site_words);
        buffers.write(&dev, MEMBERS, &member_rows);
        let kin = bodies::kinematics(&setup.body_pose, &setup.body_velocity, 0.0, &frame);
        buffers.write(&dev, BODY_KIN, &kin);
        let staging = staging_buffer(&dev, "partials", groups, n_bodies);
        let open_staging = staging_buffer(&dev, "open boundaries", 0, 0);
        let mut step = GpuEmps {
            staging,
            bodies: n_bodies,
            body_loads: vec![0.0; 6 * n_bodies],
            body_reactions: vec![0.0; 6 * n_bodies],
            place_pending: false,
            dev,
            buffers,
            kernels,
            params,
            n,
            viscous,
            profile: false,
            times: StageTimes::default(),
            shape,
            open_staging,
            strip: StripCopy::of(p, k.spacing),
            gathered: AtomicU64::new(0),
            drag: Mutex::new(None),
            frame,
            isph: None,
        };
        step.upload(p)?;
        Ok(step)
    }

    /// Where the device measures positions from, and whether they are wide.
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// Particles on the device.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True when no particle is on the device.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Replaces the device's particles by `p` (the arrays regrown when they hold fewer); an error
    /// when the device cannot hold them.
    pub fn upload(&mut self, p: &Particles) -> Result<(), String> {
        if p.len() > self.buffers.capacity {
            self.regrow(p.len())?;
        }
        self.n = p.len();
        self.params.n = self.n as u32;
        self.buffers.upload(&self.dev, p, &self.frame);
        Ok(())
    }

    /// Copies the device's particles into `p` (in the device's cell order).
    pub fn download(&mut self, p: &mut Particles) {
        self.buffers.download(&self.dev, self.n, p, &self.frame);
    }

    /// The open boundaries' part of the step about to run ([`super::open_boundary`]): the pass
    /// over the device's particles, the sort that drops those it removed (when any), then the
    /// strip's new `rows` appended (the arrays regrown when full). Returns the device's counts:
    /// strip particles entered, fluid removed, strip particles withdrawn; an error when the
    /// device cannot hold the particles.
    pub fn open_boundaries(&mut self, pass: &OpenPass, rows: &Particles) -> Result<[u64; 3], String> {
        let f = |x: f64| x as f32;
        let frame = self.frame;
        let prm = &mut self.params;
        (prm.inflow_u, prm.inflow_dx) = (f(pass.u), f(pass.dx));
        // planes (±∞ where there is none) in the device's frame
        (prm.inflow_enter, prm.inflow_cut) = (frame.along(0, pass.enter), frame.along(2, pass.cut));
        (prm.outflow_x, prm.outflow_low) = frame.split_along(0, pass.outflow);
        prm.n = self.n as u32;
        let (n, cells) = (prm.n, prm.cells);
        self.buffers.write_params(&self.dev, &self.params);
        let counters = 4 * u64::from(cells);
        let zeros = [0u32; OPEN_COUNTERS as usize];
        self.buffers
            .write_at(&self.dev, CELL_COUNT, cells as usize, &zeros);
        let mut enc = self.encoder("open boundaries");
        {
            let mut p = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("open boundaries"),
                timestamp_writes: None,
            });
            dispatch(&mut p, &self.kernels, &self.kernels.open_boundaries, n, WG);
        }
        let cell_count = self.buffers.at(CELL_COUNT);
        enc.copy_buffer_to_buffer(cell_count, counters + 4, &self.open_staging, 0, 12);
        self.dev.queue.submit([enc.finish()]);
        let read: Vec<u32> = map_read(&self.dev, &self.open_staging.slice(..12));
        self.buffers.downloaded += 12;
        let [entered, removed, withdrawn] = [0, 1, 2].map(|k| u64::from(read[k]));
        let gone = (removed + withdrawn) as usize;
        if gone > 0 {
            // the sort with the count before the pass drops the removed particles past the rest
            let mut enc = self.encoder("compaction");
            cell_sort::encode(&mut enc, &self.kernels, &self.buffers, n, cells);
            self.dev.queue.submit([enc.finish()]);
            self.n -= gone;
        }
        if !rows.is_empty() {
            let need = self.n + rows.len();
            if need > self.buffers.capacity {
                let most = (self.shape.largest / 16) as usize;
                self.regrow((need + need / 2).min(most).max(need))?;
            }
            self.buffers.upload_at(&self.dev, rows, self.n, &self.frame);
            self.n = need;
        }
        self.params.n = self.n as u32;
        Ok([entered, removed, withdrawn])
    }

    /// Drops the last `removed` particles (those a compaction sort put past the rest).
    pub(super) fn shrink_by(&mut self, removed: usize) {
        self.n -= removed;
        self.params.n = self.n as u32;
    }

    /// Particles the arrays hold room for.
    pub fn capacity(&self) -> usize {
        self.buffers.capacity
    }

    /// Makes the arrays hold room for `capacity` particles (no fewer than the device has),
    /// keeping every buffer's contents; an error when that is more than the device's largest
    /// binding allows.
    pub fn regrow(&mut self, capacity: usize) -> Result<(), String> {
        let sh = self.shape;
        let capacity = capacity.max(self.n);
        if 16 * capacity as u64 > sh.largest {
            return Err(format!(
                "the GPU binds at most {} B per array, {capacity} particles need {} B (the inflow has added too many for this device); use backend = \"cpu\"",
                sh.largest,
                16 * capacity as u64
            ));
        }
        let groups = capacity.div_ceil(WIDE_WG as usize);
        let mut fresh = Buffers::new(
            &self.dev,
            (capacity, self.frame.wide()),
            sh.cells,
            sh.boxes,
            groups,
            sh.bodies,
            sh.scene,
        );
        let mut enc = self.encoder("regrow");
        for (old, new) in self.buffers.storage.iter().zip(&fresh.storage) {
            enc.copy_buffer_to_buffer(old, 0, new, 0, old.size().min(new.size()));
        }
        self.dev.queue.submit([enc.finish()]);
        (fresh.uploaded, fresh.downloaded) = (self.buffers.uploaded, self.buffers.downloaded);
        self.buffers = fresh;
        let row = self.kernels.row;
        self.kernels = Kernels::new(&self.dev, &self.buffers);
        self.kernels.row = row;
        self.rebind_drag();
        self.staging = staging_buffer(&self.dev, "partials", groups, self.bodies);
        Ok(())
    }

    fn encoder(&self, label: &str) -> wgpu::CommandEncoder {
        self.dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) })
    }

    /// Hands over each body's pose (7 per body: centre, quaternion w x y z), velocity (6 per
    /// body: V, ω) and lead; the next step first places the body particles by them (as
    /// [`crate::bodies::RigidBodies::set_kinematics`]) and takes moments about these centres.
    pub fn set_body_motion(&mut self, pose: &[f64], velocity: &[f64], lead: f64) {
        let kin = bodies::kinematics(pose, velocity, lead, &self.frame);
        self.buffers.write(&self.dev, BODY_KIN, &kin);
        self.place_pending = true;
    }

    /// Hands over the wave maker's paddle's placement for the next step (from t to t + Δt, as
    /// [`crate::boundaries::paddle::Paddle::place`] places it on the CPU); the step places the
    /// paddle particles by it first. Call it before every step of a case with a paddle.
    pub fn set_paddle(&mut self, p: &PaddlePlacement) {
        let f = |x: f64| x as f32;
        let prm = &mut self.params;
        prm.paddle_shift = f(p.shift);
        prm.paddle_speed = f(p.speed);
        prm.paddle_cos_m1 = f(p.cos_m1);
        prm.paddle_sin = f(p.sin);
        prm.paddle_dcos = f(p.dcos);
        prm.paddle_dsin = f(p.dsin);
    }

    /// Force and moment of the fluid's pair terms and the walls' contact on each body in the
    /// last step (6 per body, about the centres handed over for it).
    pub fn body_loads(&self) -> &[f64] {
        &self.body_loads
    }

    /// Bytes of device memory the step's buffers hold (the module doc of [`super::buffers`]).
    pub fn device_bytes(&self) -> u64 {
        self.buffers.device_bytes()
    }

    /// Force and moment the bodies exerted on the fluid and the walls in the last step (6 per
    /// body): the fluid's share summed on the device from the fluid particles' side
    /// (`shaders/reaction.wgsl`), minus the walls' contact; minus [`GpuEmps::body_loads`] up to
    /// f32 rounding.
    pub fn body_reactions(&self) -> &[f64] {
        &self.body_reactions
    }

    /// Bytes copied host → device and device → host since the start.
    pub fn bytes_moved(&self) -> (u64, u64) {
        let gathered = self.gathered.load(Ordering::Relaxed);
        let (drag_up, drag_down) = self.drag_bytes();
        (
            self.buffers.uploaded + drag_up,
            self.buffers.downloaded + gathered + drag_down,
        )
    }

    /// Dispatches in rows of at most `groups` workgroups (the device's limit per dimension by
    /// default): a smaller row runs the 2-D dispatch path of large runs at a small size (tests).
    pub fn set_dispatch_row(&mut self, groups: u32) {
        let limit = self.dev.device.limits().max_compute_workgroups_per_dimension;
        self.kernels.row = groups.clamp(1, limit);
    }

    /// Times every stage by waiting after it (slower; for the benchmark).
    pub fn set_profile(&mut self, on: bool) {
        self.profile = on;
    }

    /// Wall time per stage since the start (only with [`GpuEmps::set_profile`]; otherwise the
    /// whole step is one stage "step").
    pub fn stage_times(&self) -> &StageTimes {
        &self.times
    }

    /// Advances the device's particles by `dt` and returns the device's reduction.
    pub fn advance(&mut self, dt: f64) -> StepReport {
        let t0 = self.times.start();
        self.params.dt = dt as f32;
        // body_wall_contact.rs: k = m ω², c = 2 m ω, ω = 2π / (CONTACT_PERIOD_STEPS Δt)
        let mass = f64::from(self.params.mass);
        let omega = 2.0 * std::f64::consts::PI / (CONTACT_PERIOD_STEPS * dt);
        self.params.contact_k = (mass * omega * omega) as f32;
        self.params.contact_c = (2.0 * mass * omega) as f32;
        self.buffers.write_params(&self.dev, &self.params);
        let (n, cells) = (self.n as u32, self.params.cells);
        let (bodies, place) = (self.bodies as u32, self.place_pending);
        let (av, damped) = (self.params.av_scale != 0.0, self.params.n_damping > 0);
        let paddle = self.params.paddle_count > 0;
        let spreads = self.spreads_reactions();
        self.place_pending = false;
        // after an exchange's pass: each body particle's force summed per body, and the reaction
        // summed from the fluid particles' side (`react`), on the device
        let reduce_bodies = |p: &mut wgpu::ComputePass<'_>, k: &Kernels, react: &wgpu::ComputePipeline| {
            dispatch(p, k, &k.reduce_bodies, n, WIDE_WG);
            dispatch_layers(p, k, react, n, WIDE_WG, bodies);
            dispatch(p, k, &k.sum_bodies, 1, WIDE_WG);
        };
        let mut rec = Recorder::new(self);
        rec.passes("clear", |p, k| {
            dispatch(p, k, &k.clear_sums, n, WG);
            if bodies > 0 {
                dispatch(p, k, &k.clear_body_loads, bodies * SUMS as u32, WG);
            }
            if place {
                dispatch(p, k, &k.place_bodies, n, WG);
            }
            if paddle {
                dispatch(p, k, &k.place_paddle, n, WG);
            }
        });
        // the drag's reactions spread at the step's start positions with a cell list sorted
        // for them, before the viscous term (where the CPU kicks the velocities)
        if rec.step.viscous || spreads {
            rec.sort("neighbour search", n, cells);
        }
        if spreads {
            rec.spread();
        }
        if rec.step.viscous {
            rec.passes("viscous", |p, k| {
                dispatch(p, k, &k.laplacian, n, WG);
                if bodies > 0 {
                    dispatch(p, k, &k.body_viscous, n, WG);
                    reduce_bodies(p, k, &k.react_viscous);
                }
            });
        }
        rec.passes("predict", |p, k| dispatch(p, k, &k.predict, n, WG));
        rec.sort("neighbour search", n, cells);
        rec.passes("density and pressure", |p, k| dispatch(p, k, &k.density, n, WG));
        rec.passes("pressure gradient", |p, k| {
            dispatch(p, k, &k.gradient, n, WG);
            if av {
                dispatch(p, k, &k.artificial_viscosity, n, WG);
            }
            if bodies > 0 {
                dispatch(p, k, &k.body_pressure, n, WG);
                reduce_bodies(p, k, &k.react_pressure);
            }
            dispatch(p, k, &k.correct, n, WG);
        });
        rec.passes("collision", |p, k| {
            dispatch(p, k, &k.collide, n, WG);
            if bodies > 0 {
                dispatch(p, k, &k.body_collision, n, WG);
                reduce_bodies(p, k, &k.react_collision);
            }
            dispatch(p, k, &k.apply_collisions, n, WG);
        });
        if damped {
            rec.passes("damping", |p, k| dispatch(p, k, &k.relax_damping, n, WG));
        }
        let report = rec.report(spreads);
        if !self.profile {
            self.times.lap(t0, "step");
        }
        report
    }
}

/// A buffer the host maps to read `groups` reduction partials and the sums of `bodies` bodies
/// (at least 16 B).
fn staging_buffer(dev: &GpuDevice, label: &str, groups: usize, bodies: usize) -> wgpu::Buffer {
    let size = groups.max(1) * std::mem::size_of::<Partial>()
        + SUMS as usize * bodies * std::mem::size_of::<BodyLoad>();
    dev.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Records the step's passes into one command encoder, or (profiling) submits and times each.
pub(super) struct Recorder<'a> {
    pub(super) step: &'a mut GpuEmps,
    pub(super) enc: wgpu::CommandEncoder,
    clock: std::time::Instant,
}

impl<'a> Recorder<'a> {
    pub(super) fn new(step: &'a mut GpuEmps) -> Recorder<'a> {
        let enc = step
            .dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("emps step"),
            });
        Recorder {
            step,
            enc,
            clock: std::time::Instant::now(),
        }
    }

    /// Records one compute pass filled by `f`, as stage `name`.
    pub(super) fn passes(
        &mut self,
        name: &'static str,
        f: impl FnOnce(&mut wgpu::ComputePass<'_>, &Kernels),
    ) {
        {
            let mut pass = self.enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(name),
                timestamp_writes: None,
            });
            f(&mut pass, &self.step.kernels);
        }
        self.lap(name);
    }

    /// Records the drag's spreading ([`GpuEmps::encode_spreading`]), as stage "drag spreading".
    pub(super) fn spread(&mut self) {
        self.step.encode_spreading(&mut self.enc);
        self.lap("drag spreading");
    }

    /// Records a cell sort, as stage `name`.
    pub(super) fn sort(&mut self, name: &'static str, n: u32, cells: u32) {
        cell_sort::encode(&mut self.enc, &self.step.kernels, &self.step.buffers, n, cells);
        self.lap(name);
    }

    /// Profiling: submits what was recorded, waits, and adds the time to stage `name`.
    fn lap(&mut self, name: &'static str) {
        if self.step.profile {
            self.submit();
            self.clock = self.step.times.lap(self.clock, name);
        }
    }

    /// Submits what was recorded and waits.
    pub(super) fn submit(&mut self) {
        let dev = &self.step.dev;
        let fresh = dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("emps step"),
            });
        let enc = std::mem::replace(&mut self.enc, fresh);
        dev.queue.submit([enc.finish()]);
        dev.wait();
    }

    /// Records the detector's scan and the step's totals (reduced on the device), submits the
    /// rest and reads back the partials and the bodies' sums (`spreads`: the drag's reactions
    /// were spread this step, whose states the host then takes): the step's report.
    pub(super) fn report(mut self, spreads: bool) -> StepReport {
        let n = self.step.n as u32;
        let groups = self.step.n.div_ceil(WIDE_WG as usize).max(1);
        let bodies = self.step.bodies;
        self.passes("detector and totals", |p, k| {
            dispatch(p, k, &k.reduce_step, n, WIDE_WG)
        });
        let bytes = (groups * std::mem::size_of::<Partial>()) as u64;
        let body_bytes = (SUMS as usize * bodies * std::mem::size_of::<BodyLoad>()) as u64;
        let (partials_buffer, staging) = (self.step.buffers.at(PARTIALS), &self.step.staging);
        self.enc
            .copy_buffer_to_buffer(partials_buffer, 0, staging, 0, bytes);
        if body_bytes > 0 {
            let loads = self.step.buffers.at(BODY_LOADS);
            self.enc
                .copy_buffer_to_buffer(loads, 0, staging, bytes, body_bytes);
        }
        let clock = self.clock;
        self.submit();
        let step = self.step;
        if step.profile {
            step.times.lap(clock, "detector and totals");
        }
        let read: Vec<u8> = map_read(&step.dev, &step.staging.slice(..bytes + body_bytes));
        step.buffers.downloaded += bytes + body_bytes;
        let (head, tail) = read.split_at(bytes as usize);
        let partials: Vec<Partial> = bytemuck::pod_collect_to_vec(head);
        let sums = bytemuck::pod_collect_to_vec::<u8, BodyLoad>(tail);
        (step.body_loads, step.body_reactions) = bodies::loads_and_reactions(&sums);
        step.take_reaction_states(spreads);
        let mut report = reduce::sum(&partials);
        // Σ (½|u|² − g·(r − origin)) on the device: the potential back from the case's origin
        let g = step.params.gravity.map(f64::from);
        let lift: f64 = (0..3).map(|a| g[a] * step.frame.origin[a]).sum();
        report.energy -= report.fluid as f64 * lift;
        report
    }

    /// Submits the rest; with profiling on, its time goes to stage `name`.
    pub(super) fn finish(mut self, name: &'static str) {
        self.submit();
        if self.step.profile {
            self.step.times.lap(self.clock, name);
        }
    }
}
