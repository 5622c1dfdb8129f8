//! The ISPH step on the device (`method = "isph"` with `backend = "gpu"`): the stages of
//! [`crate::isph::step`] in the same order, with the default discretisation (the exact projection
//! of [`crate::isph::exact_projection`], pairs corrected by the moment matrices of
//! [`crate::isph::kernel_correction`] or plain): cell sort at r^n, S2-7 and the free-surface flags
//! (S2-10 … S2-13), the Dirichlet values, corrections and the walls' completion of surface water,
//! the viscous term and S2-3, the PPE's rows and right-hand side, its solve by Jacobi-
//! preconditioned conjugate gradient (the CPU's default preconditioner is the two-level one; both
//! stop at the case's relative tolerance), no tension, Adami's wall pressure, the symmetric
//! gradient and S2-4, then the collision stage and the detector's reduction the E-MPS step shares
//! (`shaders/isph.wgsl`).
//!
//! The solver's vectors live on the device by particle (0 off the unknowns), its scalars too
//! (α and β are formed by one workgroup from per-workgroup partials), so an iteration is six
//! dispatches and nothing crosses to the host but the eight scalars after each
//! [`ITERATIONS_PER_READ`] iterations.
//!
//! The walls' normals, depths and convexity flags are computed once on the host (the walls are
//! fixed: [`crate::isph::walls`] keeps them by id for the same reason) and kept by particle id.

use super::buffers::map_read;
use super::device::GpuDevice;
use super::kernels::{dispatch, grid_of, Kernels, WG, WIDE_WG};
use super::reduce::StepReport;
use super::step::{GpuEmps, Recorder};
use crate::isph::kernel::Wendland;
use crate::isph::neighbour_list::NeighbourList;
use crate::isph::ppe::{PpeFailure, PpeReport};
use crate::isph::walls;
use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use crate::physics::Physics;
use bytemuck::{Pod, Zeroable};
use schemas::case::fluid::{IsphConfig, KernelCorrection, WallSlip};

/// Conjugate-gradient iterations recorded between two reads of the solver's scalars.
pub const ITERATIONS_PER_READ: u32 = 8;

/// ε of the exact projection's blend ([`crate::isph::exact_projection::CHECKERBOARD_SHARE`]).
const EPSILON: f64 = crate::isph::exact_projection::CHECKERBOARD_SHARE;

/// Storage buffers of the ISPH group (binding 1 … 18 of group 1; 0 is its uniform block).
const STORAGE: usize = 18;

/// The bindings of group 0 the ISPH kernels read (`shaders/common.wgsl`): the uniform block, the
/// particles, the step's sums and the cell list. The ISPH pipelines bind only these, so that
/// with the ISPH group they stay within the 32 storage buffers per shader a software device
/// (lavapipe) allows.
const PARTICLE_BINDINGS: [u32; 12] = [0, 1, 2, 3, 4, 5, 6, 7, 10, 11, 13, 23];

/// Mirror of `IsphParams` in `shaders/isph.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct IsphParams {
    w_factor: f32,
    dw_factor: f32,
    inv_radius: f32,
    volume: f32,
    lattice_density: f32,
    lattice_moment: f32,
    radius: f32,
    reach: u32,
    rho: f32,
    alpha_d: f32,
    eps: f32,
    dt_p: f32,
    dt: f32,
    share: f32,
    n0_mps: f32,
    nu: f32,
    gravity: [f32; 3],
    tol2: f32,
    corrected: u32,
    no_slip: u32,
    viscous: u32,
    groups: u32,
    max_iterations: u32,
    spacing: f32,
    short: u32,
    pad: u32,
}

/// What the device's ISPH step is built from.
pub struct IsphSetup<'a> {
    pub kernel: Wendland,
    pub physics: Physics,
    pub settings: IsphConfig,
    /// n0 of the MPS lattice: the fluid's number density is written as n0 ρ̂/ρ0.
    pub n0_mps: f64,
    /// The host's particles (sorted by `grid`) from which the walls' geometry is taken.
    pub particles: &'a Particles,
    pub grid: &'a CellGrid,
}

/// The ISPH kernels, their arrays and the solver's state between steps.
pub struct GpuIsph {
    params: IsphParams,
    /// Group 0 of the ISPH pipelines ([`PARTICLE_BINDINGS`]) and the particles' capacity it was
    /// bound at.
    particles_layout: wgpu::BindGroupLayout,
    particles: wgpu::BindGroup,
    bound_capacity: usize,
    uniform: wgpu::Buffer,
    storage: Vec<wgpu::Buffer>,
    layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
    pipelines: Pipelines,
    /// Particles the per-particle arrays hold room for.
    capacity: usize,
    /// Each solid's normal and depth (4 f32) and convexity flag by particle id.
    geometry: Vec<[f32; 4]>,
    convex: Vec<u32>,
    staging: wgpu::Buffer,
}

/// One pipeline per ISPH kernel.
struct Pipelines {
    density: wgpu::ComputePipeline,
    surface: wgpu::ComputePipeline,
    fields: wgpu::ComputePipeline,
    laplacian: wgpu::ComputePipeline,
    predict: wgpu::ComputePipeline,
    assemble: wgpu::ComputePipeline,
    known: wgpu::ComputePipeline,
    rhs: wgpu::ComputePipeline,
    cg_gradient: wgpu::ComputePipeline,
    cg_start: wgpu::ComputePipeline,
    cg_start_residual: wgpu::ComputePipeline,
    cg_start_scalars: wgpu::ComputePipeline,
    cg_apply: wgpu::ComputePipeline,
    cg_step_length: wgpu::ComputePipeline,
    cg_update: wgpu::ComputePipeline,
    cg_iteration_end: wgpu::ComputePipeline,
    cg_direction: wgpu::ComputePipeline,
    pressure: wgpu::ComputePipeline,
    wall_pressure: wgpu::ComputePipeline,
    gradient: wgpu::ComputePipeline,
    correct: wgpu::ComputePipeline,
}

/// The solver's scalars as the device keeps them (`CG_*` in `shaders/isph.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct CgScalars {
    b2: f32,
    r2: f32,
    rz: f32,
    alpha: f32,
    beta: f32,
    done: f32,
    iterations: f32,
    target: f32,
    unknowns: f32,
    pad: [f32; 3],
}

/// Each solid particle's normal into the fluid, depth behind its wall's face and convexity flag
/// ([`walls::fixed_geometry`]) by particle id, from the host's particles sorted by `grid`.
fn solid_geometry(k: &Wendland, grid: &CellGrid, p: &Particles) -> (Vec<[f32; 4]>, Vec<u32>) {
    let ids = p.id.iter().max().map_or(0, |&m| m as usize + 1);
    let mut list = NeighbourList::default();
    list.build_every(grid, p, k);
    let mut geometry = vec![[0.0f32; 4]; ids];
    let mut convex = vec![0u32; ids];
    for w in 0..p.len() {
        if p.kind[w] == FLUID {
            continue;
        }
        let (n, depth, c) = walls::fixed_geometry(k, &list, p, w);
        let id = p.id[w] as usize;
        geometry[id] = [n[0] as f32, n[1] as f32, n[2] as f32, depth as f32];
        convex[id] = u32::from(c);
    }
    (geometry, convex)
}

impl GpuIsph {
    /// The ISPH kernels for the step `emps` (whose group 0 they share), with room for its
    /// arrays' particles; an error when the device binds too few storage buffers.
    pub fn new(emps: &GpuEmps, setup: &IsphSetup) -> Result<GpuIsph, String> {
        let dev = &emps.dev;
        let have = dev.device.limits().max_storage_buffers_per_shader_stage;
        let need = (PARTICLE_BINDINGS.len() - 1 + STORAGE) as u32;
        if have < need {
            return Err(format!(
                "the GPU binds {have} storage buffers per shader, ISPH on the device needs {need}; use backend = \"cpu\""
            ));
        }
        let k = &setup.kernel;
        let s = &setup.settings;
        let ph = &setup.physics;
        let reach = setup.grid.reach(k.radius) as u32;
        let params = IsphParams {
            w_factor: k.w_at(0.0) as f32,
            dw_factor: k.dw_over_r_at(0.0) as f32,
            inv_radius: (1.0 / k.radius) as f32,
            volume: k.volume as f32,
            lattice_density: k.lattice_density as f32,
            lattice_moment: k.lattice_moment as f32,
            radius: k.radius as f32,
            reach,
            rho: ph.density as f32,
            alpha_d: s.alpha_d as f32,
            eps: EPSILON as f32,
            dt_p: 0.0,
            dt: 0.0,
            share: 1.0,
            n0_mps: setup.n0_mps as f32,
            nu: if ph.viscous() { ph.viscosity as f32 } else { 0.0 },
            gravity: ph.gravity.map(|g| g as f32),
            tol2: (s.ppe_tolerance * s.ppe_tolerance) as f32,
            corrected: u32::from(s.kernel_correction() == KernelCorrection::Moment),
            no_slip: u32::from(s.wall_slip == WallSlip::NoSlip),
            viscous: u32::from(ph.viscous()),
            groups: 0,
            max_iterations: s.ppe_max_iterations,
            spacing: k.spacing as f32,
            short: 0,
            pad: 0,
        };
        let (geometry, convex) = solid_geometry(k, setup.grid, setup.particles);
        let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let mut entries = vec![entry(0, wgpu::BufferBindingType::Uniform)];
        for b in 1..=STORAGE as u32 {
            entries.push(entry(b, wgpu::BufferBindingType::Storage { read_only: false }));
        }
        let layout = dev
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("isph"),
                entries: &entries,
            });
        let uniform = dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("isph params"),
            size: std::mem::size_of::<IsphParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let staging = dev.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("isph scalars"),
            size: std::mem::size_of::<CgScalars>() as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let particle_entries: Vec<_> = PARTICLE_BINDINGS
            .iter()
            .map(|&b| match b {
                0 => entry(0, wgpu::BufferBindingType::Uniform),
                b => entry(b, wgpu::BufferBindingType::Storage { read_only: false }),
            })
            .collect();
        let particles_layout = dev
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("isph particles"),
                entries: &particle_entries,
            });
        let particles = bind_particles(dev, &particles_layout, emps);
        let pipelines = Pipelines::new(dev, &particles_layout, &layout, emps.buffers.wide);
        let capacity = emps.buffers.capacity;
        let (storage, bind_group) = arrays(dev, &layout, &uniform, capacity, geometry.len());
        let isph = GpuIsph {
            params,
            particles_layout,
            particles,
            bound_capacity: capacity,
            uniform,
            storage,
            layout,
            bind_group,
            pipelines,
            capacity,
            geometry,
            convex,
            staging,
        };
        isph.write_geometry(dev);
        Ok(isph)
    }

    /// Uploads the solids' geometry by id.
    fn write_geometry(&self, dev: &GpuDevice) {
        dev.queue.write_buffer(
            &self.storage[GEOMETRY - 1],
            0,
            bytemuck::cast_slice(&self.geometry),
        );
        dev.queue
            .write_buffer(&self.storage[CONVEX - 1], 0, bytemuck::cast_slice(&self.convex));
    }

    /// Makes the per-particle arrays hold room for the particles of `emps`, and binds its
    /// arrays afresh where they were regrown.
    fn ensure_capacity(&mut self, emps: &GpuEmps) {
        let (dev, n) = (&emps.dev, emps.buffers.capacity);
        if n != self.bound_capacity {
            self.particles = bind_particles(dev, &self.particles_layout, emps);
            self.bound_capacity = n;
        }
        if n <= self.capacity {
            return;
        }
        let (storage, bind_group) = arrays(dev, &self.layout, &self.uniform, n, self.geometry.len());
        (self.storage, self.bind_group, self.capacity) = (storage, bind_group, n);
        self.write_geometry(dev);
    }

    /// Records `pipeline` over `items` threads of `group` per workgroup, with the particles'
    /// group 0 and the ISPH group 1.
    fn run(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        k: &Kernels,
        pipeline: &wgpu::ComputePipeline,
        items: u32,
        group: u32,
    ) {
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.particles, &[]);
        pass.set_bind_group(1, &self.bind_group, &[]);
        let (x, y) = grid_of(items.div_ceil(group).max(1), k.row);
        pass.dispatch_workgroups(x, y, 1);
    }

    /// Records one conjugate-gradient iteration ([`crate::isph::ppe`]'s `pcg`).
    fn iteration(&self, p: &mut wgpu::ComputePass<'_>, k: &Kernels, n: u32) {
        let q = &self.pipelines;
        self.run(p, k, &q.cg_gradient, n, WG);
        self.run(p, k, &q.cg_apply, n, WIDE_WG);
        self.run(p, k, &q.cg_step_length, 1, WIDE_WG);
        self.run(p, k, &q.cg_update, n, WIDE_WG);
        self.run(p, k, &q.cg_iteration_end, 1, WIDE_WG);
        self.run(p, k, &q.cg_direction, n, WG);
    }
}

/// Group 0 of the ISPH pipelines over the arrays of `emps` ([`PARTICLE_BINDINGS`]).
fn bind_particles(dev: &GpuDevice, layout: &wgpu::BindGroupLayout, emps: &GpuEmps) -> wgpu::BindGroup {
    let b = &emps.buffers;
    let entries: Vec<wgpu::BindGroupEntry> = PARTICLE_BINDINGS
        .iter()
        .map(|&k| wgpu::BindGroupEntry {
            binding: k,
            resource: match k {
                0 => b.params.as_entire_binding(),
                k => b.storage[k as usize - 1].as_entire_binding(),
            },
        })
        .collect();
    dev.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("isph particles"),
        layout,
        entries: &entries,
    })
}

/// Binding numbers of the ISPH group (see `shaders/isph.wgsl`).
const GEOMETRY: usize = 6;
const CONVEX: usize = 7;
const SCALARS: usize = 18;

/// The ISPH group's arrays for `n` particles and `ids` particle ids, and their bind group.
fn arrays(
    dev: &GpuDevice,
    layout: &wgpu::BindGroupLayout,
    uniform: &wgpu::Buffer,
    n: usize,
    ids: usize,
) -> (Vec<wgpu::Buffer>, wgpu::BindGroup) {
    let n = n.max(1) as u64;
    let groups = n.div_ceil(u64::from(WIDE_WG));
    let ids = ids.max(1) as u64;
    let sizes: [u64; STORAGE] = [
        4 * n,                                   // 1 ratio
        4 * n,                                   // 2 part
        4 * n,                                   // 3 surf
        48 * n,                                  // 4 lmat
        48 * n,                                  // 5 smat
        16 * ids,                                // 6 geom
        4 * ids,                                 // 7 convex
        4 * n,                                   // 8 dirich
        16 * n,                                  // 9 yv
        4 * n,                                   // 10 xs
        4 * n,                                   // 11 rs
        4 * n,                                   // 12 ds
        4 * n,                                   // 13 qs
        4 * n,                                   // 14 dg
        4 * n,                                   // 15 bs
        16 * n,                                  // 16 vstart
        16 * groups,                             // 17 cgp
        std::mem::size_of::<CgScalars>() as u64, // 18 cgs
    ];
    let storage: Vec<wgpu::Buffer> = sizes
        .iter()
        .map(|&size| {
            dev.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("isph"),
                size,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        })
        .collect();
    let mut bindings = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: uniform.as_entire_binding(),
    }];
    for (k, b) in storage.iter().enumerate() {
        bindings.push(wgpu::BindGroupEntry {
            binding: k as u32 + 1,
            resource: b.as_entire_binding(),
        });
    }
    let bind_group = dev.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("isph"),
        layout,
        entries: &bindings,
    });
    (storage, bind_group)
}

impl Pipelines {
    /// Compiles `shaders/isph.wgsl` with `common.wgsl` (with wide positions when `wide`).
    fn new(
        dev: &GpuDevice,
        particles: &wgpu::BindGroupLayout,
        layout: &wgpu::BindGroupLayout,
        wide: bool,
    ) -> Pipelines {
        let device = &dev.device;
        let source = [
            include_str!("shaders/common.wgsl"),
            include_str!("shaders/isph.wgsl"),
        ]
        .join("\n");
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("isph"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("isph"),
            bind_group_layouts: &[Some(particles), Some(layout)],
            immediate_size: 0,
        });
        let constants = [("WIDE", if wide { 1.0 } else { 0.0 })];
        let make = |name: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(name),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        Pipelines {
            density: make("isph_density"),
            surface: make("isph_surface"),
            fields: make("isph_fields"),
            laplacian: make("isph_laplacian"),
            predict: make("isph_predict"),
            assemble: make("isph_assemble"),
            known: make("isph_known"),
            rhs: make("isph_rhs"),
            cg_gradient: make("cg_gradient"),
            cg_start: make("cg_start"),
            cg_start_residual: make("cg_start_residual"),
            cg_start_scalars: make("cg_start_scalars"),
            cg_apply: make("cg_apply"),
            cg_step_length: make("cg_step_length"),
            cg_update: make("cg_update"),
            cg_iteration_end: make("cg_iteration_end"),
            cg_direction: make("cg_direction"),
            pressure: make("isph_pressure"),
            wall_pressure: make("isph_wall_pressure"),
            gradient: make("isph_gradient"),
            correct: make("isph_correct"),
        }
    }
}

impl GpuEmps {
    /// Moves the device's step to ISPH ([`GpuIsph`]).
    pub fn use_isph(&mut self, setup: &IsphSetup) -> Result<(), String> {
        let isph = GpuIsph::new(self, setup)?;
        // the pair passes' reach (`apart_near`'s test) and the collision's grid are ISPH's
        self.params.re = setup.kernel.radius as f32;
        self.isph = Some(Box::new(isph));
        Ok(())
    }

    /// Whether the device steps ISPH.
    pub fn is_isph(&self) -> bool {
        self.isph.is_some()
    }

    /// Advances the device's particles by `dt` with ISPH, its pressure taken from a step of
    /// `pressure_step` (Δt_p ≥ dt, [`crate::isph::step_length::pressure_step`]); returns the
    /// device's reduction and how the PPE went, or the PPE's failure.
    pub fn advance_isph(
        &mut self,
        dt: f64,
        pressure_step: f64,
    ) -> Result<(StepReport, PpeReport), PpeFailure> {
        let Some(mut isph) = self.isph.take() else {
            unreachable!("advance_isph is called on an ISPH device step")
        };
        let result = self.advance_isph_with(&mut isph, dt, pressure_step);
        self.isph = Some(isph);
        result
    }

    fn advance_isph_with(
        &mut self,
        isph: &mut GpuIsph,
        dt: f64,
        pressure_step: f64,
    ) -> Result<(StepReport, PpeReport), PpeFailure> {
        let t0 = self.times.start();
        self.params.dt = dt as f32;
        self.buffers.write_params(&self.dev, &self.params);
        isph.ensure_capacity(self);
        let n = self.n as u32;
        let cells = self.params.cells;
        let ip = &mut isph.params;
        ip.dt = dt as f32;
        ip.dt_p = pressure_step as f32;
        let short = pressure_step > dt;
        ip.short = u32::from(short);
        ip.share = if short { (dt / pressure_step) as f32 } else { 1.0 };
        ip.groups = self.n.div_ceil(WIDE_WG as usize).max(1) as u32;
        self.dev
            .queue
            .write_buffer(&isph.uniform, 0, bytemuck::bytes_of(&isph.params));
        let (viscous, damped) = (
            isph.params.viscous != 0 || isph.params.no_slip != 0,
            self.params.n_damping > 0,
        );
        let spreads = self.spreads_reactions();
        let q = &isph.pipelines;
        let mut rec = Recorder::new(self);
        rec.passes("clear", |p, k| dispatch(p, k, &k.clear_sums, n, WG));
        rec.sort("neighbour search", n, cells);
        if spreads {
            rec.spread();
        }
        rec.passes("density and free surface", |p, k| {
            isph.run(p, k, &q.density, n, WG);
            isph.run(p, k, &q.surface, n, WG);
            isph.run(p, k, &q.fields, n, WG);
        });
        rec.passes("viscous and prediction", |p, k| {
            if viscous {
                isph.run(p, k, &q.laplacian, n, WG);
            }
            isph.run(p, k, &q.predict, n, WG);
        });
        rec.passes("PPE assembly", |p, k| {
            isph.run(p, k, &q.assemble, n, WG);
            isph.run(p, k, &q.known, n, WG);
            isph.run(p, k, &q.rhs, n, WG);
            isph.run(p, k, &q.cg_gradient, n, WG);
            isph.run(p, k, &q.cg_start, n, WG);
            isph.run(p, k, &q.cg_start_residual, n, WIDE_WG);
            isph.run(p, k, &q.cg_start_scalars, 1, WIDE_WG);
        });
        let bytes = std::mem::size_of::<CgScalars>() as u64;
        let scalars = loop {
            rec.passes("PPE solve", |p, k| {
                for _ in 0..ITERATIONS_PER_READ {
                    isph.iteration(p, k, n);
                }
            });
            rec.enc
                .copy_buffer_to_buffer(&isph.storage[SCALARS - 1], 0, &isph.staging, 0, bytes);
            rec.submit();
            let read: Vec<CgScalars> = map_read(&rec.step.dev, &isph.staging.slice(..));
            rec.step.buffers.downloaded += bytes;
            if read[0].done != 0.0 {
                break read[0];
            }
        };
        let residual = if scalars.b2 > 0.0 {
            f64::from(scalars.r2 / scalars.b2).sqrt()
        } else {
            0.0
        };
        let ppe = PpeReport {
            iterations: scalars.iterations as u32,
            residual,
            unknowns: scalars.unknowns as usize,
        };
        if scalars.done == 2.0 {
            rec.finish("PPE solve");
            return Err(PpeFailure {
                iterations: ppe.iterations,
                residual,
                unknowns: ppe.unknowns,
            });
        }
        rec.passes("wall pressure", |p, k| {
            isph.run(p, k, &q.pressure, n, WG);
            isph.run(p, k, &q.wall_pressure, n, WG);
        });
        rec.passes("pressure gradient and correction", |p, k| {
            isph.run(p, k, &q.gradient, n, WG);
            isph.run(p, k, &q.correct, n, WG);
        });
        rec.passes("collision", |p, k| {
            dispatch(p, k, &k.collide, n, WG);
            dispatch(p, k, &k.apply_collisions, n, WG);
        });
        if damped {
            rec.passes("damping", |p, k| dispatch(p, k, &k.relax_damping, n, WG));
        }
        let report = rec.report(spreads);
        if !self.profile {
            self.times.lap(t0, "step");
        }
        Ok((report, ppe))
    }
}
