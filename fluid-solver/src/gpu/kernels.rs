//! The WGSL kernels (`shaders/`) as compute pipelines sharing one bind group layout: binding 0
//! the uniform block, 1 … 23 the storage buffers of [`super::buffers`] (the drag coupling's
//! kernels bind a second group, [`super::drag`]); and their dispatch, in rows when a dispatch
//! has more workgroups than the device allows per dimension.

use super::buffers::Buffers;
use super::device::GpuDevice;

/// The WGSL sources, joined into one module (the bindings are declared once in `common.wgsl`).
const SOURCES: [&str; 15] = [
    include_str!("shaders/common.wgsl"),
    include_str!("shaders/cell_sort.wgsl"),
    include_str!("shaders/emps.wgsl"),
    include_str!("shaders/artificial_viscosity.wgsl"),
    include_str!("shaders/damping.wgsl"),
    include_str!("shaders/solids.wgsl"),
    include_str!("shaders/reduce.wgsl"),
    include_str!("shaders/bodies.wgsl"),
    include_str!("shaders/body_inside.wgsl"),
    include_str!("shaders/reaction.wgsl"),
    include_str!("shaders/paddle.wgsl"),
    include_str!("shaders/open_boundary.wgsl"),
    include_str!("shaders/probe_reductions.wgsl"),
    include_str!("shaders/escape.wgsl"),
    include_str!("shaders/drag.wgsl"),
];

/// One pipeline per kernel, and the bind group over the step's buffers.
pub struct Kernels {
    pub clear_cells: wgpu::ComputePipeline,
    pub count_cells: wgpu::ComputePipeline,
    pub scan_cells: wgpu::ComputePipeline,
    pub scan_block_sums: wgpu::ComputePipeline,
    pub scan_tops: wgpu::ComputePipeline,
    pub add_tops: wgpu::ComputePipeline,
    pub add_blocks: wgpu::ComputePipeline,
    pub scatter: wgpu::ComputePipeline,
    pub order_cells: wgpu::ComputePipeline,
    pub gather_positions: wgpu::ComputePipeline,
    pub gather_lows: wgpu::ComputePipeline,
    pub gather_velocities: wgpu::ComputePipeline,
    pub gather_ids: wgpu::ComputePipeline,
    pub clear_sums: wgpu::ComputePipeline,
    pub laplacian: wgpu::ComputePipeline,
    pub predict: wgpu::ComputePipeline,
    pub density: wgpu::ComputePipeline,
    pub gradient: wgpu::ComputePipeline,
    pub artificial_viscosity: wgpu::ComputePipeline,
    pub correct: wgpu::ComputePipeline,
    pub collide: wgpu::ComputePipeline,
    pub apply_collisions: wgpu::ComputePipeline,
    pub relax_damping: wgpu::ComputePipeline,
    pub reduce_step: wgpu::ComputePipeline,
    pub place_bodies: wgpu::ComputePipeline,
    pub clear_body_loads: wgpu::ComputePipeline,
    pub body_viscous: wgpu::ComputePipeline,
    pub body_pressure: wgpu::ComputePipeline,
    pub body_collision: wgpu::ComputePipeline,
    pub reduce_bodies: wgpu::ComputePipeline,
    pub sum_bodies: wgpu::ComputePipeline,
    pub react_viscous: wgpu::ComputePipeline,
    pub react_pressure: wgpu::ComputePipeline,
    pub react_collision: wgpu::ComputePipeline,
    pub place_paddle: wgpu::ComputePipeline,
    pub open_boundaries: wgpu::ComputePipeline,
    pub water_extent: wgpu::ComputePipeline,
    pub run_up: wgpu::ComputePipeline,
    pub remove_escaped: wgpu::ComputePipeline,
    pub sample_flow: wgpu::ComputePipeline,
    pub reaction_sums: wgpu::ComputePipeline,
    pub spread_reactions: wgpu::ComputePipeline,
    pub bind_group: wgpu::BindGroup,
    /// The layout of the drag coupling's group 1: its uniform block and two storage buffers.
    pub drag_layout: wgpu::BindGroupLayout,
    /// Workgroups per row of a dispatch: the device's limit per dimension (65 535 on most),
    /// or fewer to run the 2-D path at small sizes ([`super::GpuEmps::set_dispatch_row`]).
    pub row: u32,
}

impl Kernels {
    /// Compiles the kernels (with wide positions when `buffers` are: the override `WIDE`) and
    /// binds `buffers`.
    pub fn new(dev: &GpuDevice, buffers: &Buffers) -> Kernels {
        let device = &dev.device;
        let source = SOURCES.join("\n");
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("emps"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
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
        for b in 1..=buffers.storage.len() as u32 {
            entries.push(entry(b, wgpu::BufferBindingType::Storage { read_only: false }));
        }
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("emps"),
            entries: &entries,
        });
        let mut bindings = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: buffers.params.as_entire_binding(),
        }];
        for (k, b) in buffers.storage.iter().enumerate() {
            bindings.push(wgpu::BindGroupEntry {
                binding: k as u32 + 1,
                resource: b.as_entire_binding(),
            });
        }
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("emps"),
            layout: &layout,
            entries: &bindings,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("emps"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let drag_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("drag"),
            entries: &[
                entry(0, wgpu::BufferBindingType::Uniform),
                entry(1, wgpu::BufferBindingType::Storage { read_only: false }),
                entry(2, wgpu::BufferBindingType::Storage { read_only: false }),
            ],
        });
        let drag_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("drag"),
            bind_group_layouts: &[Some(&layout), Some(&drag_layout)],
            immediate_size: 0,
        });
        let constants = [("WIDE", if buffers.wide { 1.0 } else { 0.0 })];
        let make_in = |name: &str, pipeline_layout: &wgpu::PipelineLayout| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(pipeline_layout),
                module: &module,
                entry_point: Some(name),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let make = |name: &str| make_in(name, &pipeline_layout);
        let make_drag = |name: &str| make_in(name, &drag_pipeline_layout);
        Kernels {
            clear_cells: make("clear_cells"),
            count_cells: make("count_cells"),
            scan_cells: make("scan_cells"),
            scan_block_sums: make("scan_block_sums"),
            scan_tops: make("scan_tops"),
            add_tops: make("add_tops"),
            add_blocks: make("add_blocks"),
            scatter: make("scatter"),
            order_cells: make("order_cells"),
            gather_positions: make("gather_positions"),
            gather_lows: make("gather_lows"),
            gather_velocities: make("gather_velocities"),
            gather_ids: make("gather_ids"),
            clear_sums: make("clear_sums"),
            laplacian: make("laplacian"),
            predict: make("predict"),
            density: make("density"),
            gradient: make("gradient"),
            artificial_viscosity: make("artificial_viscosity"),
            correct: make("correct"),
            collide: make("collide"),
            apply_collisions: make("apply_collisions"),
            relax_damping: make("relax_damping"),
            reduce_step: make("reduce_step"),
            place_bodies: make("place_bodies"),
            clear_body_loads: make("clear_body_loads"),
            body_viscous: make("body_viscous"),
            body_pressure: make("body_pressure"),
            body_collision: make("body_collision"),
            reduce_bodies: make("reduce_bodies"),
            sum_bodies: make("sum_bodies"),
            react_viscous: make("react_viscous"),
            react_pressure: make("react_pressure"),
            react_collision: make("react_collision"),
            place_paddle: make("place_paddle"),
            open_boundaries: make("open_boundaries"),
            water_extent: make("water_extent"),
            run_up: make("run_up"),
            remove_escaped: make("remove_escaped"),
            sample_flow: make_drag("sample_flow"),
            reaction_sums: make_drag("reaction_sums"),
            spread_reactions: make_drag("spread_reactions"),
            bind_group,
            drag_layout,
            row: device.limits().max_compute_workgroups_per_dimension,
        }
    }
}

/// Threads per workgroup of the per-particle and per-cell kernels.
pub const WG: u32 = 64;
/// Threads per workgroup of the scans and the reduction.
pub const WIDE_WG: u32 = 256;

/// Records `pipeline` over `items` threads of `group` per workgroup: one row of workgroups
/// while they fit in [`Kernels::row`], else rows of `row` workgroups (a 2-D dispatch; the
/// kernels number the workgroups row by row, `group_index` in `shaders/common.wgsl`, and the
/// last row's surplus threads find their index past the end).
pub fn dispatch(
    pass: &mut wgpu::ComputePass<'_>,
    k: &Kernels,
    pipeline: &wgpu::ComputePipeline,
    items: u32,
    group: u32,
) {
    dispatch_layers(pass, k, pipeline, items, group, 1);
}

/// Records the drag coupling's `pipeline` ([`super::drag`]) over `items` threads of [`WG`] per
/// workgroup, as [`dispatch`] does, with the drag's bind group `drag` as group 1.
pub fn dispatch_drag(
    pass: &mut wgpu::ComputePass<'_>,
    k: &Kernels,
    pipeline: &wgpu::ComputePipeline,
    drag: &wgpu::BindGroup,
    items: u32,
) {
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, &k.bind_group, &[]);
    pass.set_bind_group(1, drag, &[]);
    let (x, y) = grid_of(items.div_ceil(WG).max(1), k.row);
    pass.dispatch_workgroups(x, y, 1);
}

/// Records `pipeline` over `items` threads of `group` per workgroup, as [`dispatch`] does, in
/// each of `layers` layers (the layer is `workgroup_id.z`; the reaction's body).
pub fn dispatch_layers(
    pass: &mut wgpu::ComputePass<'_>,
    k: &Kernels,
    pipeline: &wgpu::ComputePipeline,
    items: u32,
    group: u32,
    layers: u32,
) {
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, &k.bind_group, &[]);
    let (x, y) = grid_of(items.div_ceil(group).max(1), k.row);
    pass.dispatch_workgroups(x, y, layers);
}

/// Workgroups per row and rows for `groups` workgroups in rows of at most `row`.
pub(super) fn grid_of(groups: u32, row: u32) -> (u32, u32) {
    if groups <= row {
        (groups, 1)
    } else {
        (row, groups.div_ceil(row))
    }
}
