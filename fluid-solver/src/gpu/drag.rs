//! The fluid's side of the unresolved drag coupling on the device (`shaders/drag.wgsl`; the
//! CPU's is [`crate::unresolved`]): only the coupler's point data cross to the device and back.
//!
//! - **Sampling** at the coupler's points (once per window, between steps): one thread per point
//!   sums the Shepard velocity and the moment matrix over the particles' cells within the
//!   kernel's support widened by [`super::gather::MARGIN_CELLS`] cells (the cell list is the
//!   step's last, at r*; the particles moved less than that since), and returns the velocity and
//!   λ_min (16 B per point).
//! - **Spreading** of the point reactions before each step (where the CPU spreads them, after
//!   the step's first cell sort so the list is exact): one thread per reaction sums its weights
//!   around its centroid, or its paired sample point where no fluid is near the centroid
//!   (`reaction_sums`); then one thread per fluid particle gathers its share of every reaction
//!   near it (`spread_reactions`) from a grid of the reactions' centres built on the host
//!   ([`ReactionGrid`]; cells at least one footprint reach wide, so a particle reads the 27 cells
//!   around its own). Each reaction's state in the step (around its centroid, its sample point,
//!   not applied) comes back with the step's reduction (4 B per reaction), from which the host
//!   books the impulse handed to the fluid and the impulse not applied, in f64 as the CPU does.
//!
//! The reactions, their sample points and widths are uploaded only when they change (80 B per
//! reaction: with wide positions the centres' low parts too, [`super::frame`]); the grid is
//! rebuilt only when their centres or widths change.

use super::buffers::map_read;
use super::device::GpuDevice;
use super::frame::Frame;
use super::gather::MARGIN_CELLS;
use super::kernels::{dispatch_drag, Kernels};
use super::step::GpuEmps;
use crate::unresolved::kernel::Wendland;
use crate::unresolved::spreading::footprint_half_width;
use bytemuck::{Pod, Zeroable};

/// Mirror of `DragParams` in `shaders/drag.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, Pod, Zeroable)]
pub struct DragParams {
    pub lo: [f32; 3],
    pub inv_cell: f32,
    pub dims: [u32; 3],
    pub points: u32,
    pub radius: f32,
    pub norm: f32,
    pub reactions: u32,
    pub sample_reach: u32,
}

/// A reaction's state in a step (`REACTION_*` in `shaders/drag.wgsl`).
pub const SPREAD_AT_CENTROID: u32 = 0;
pub const SPREAD_AT_SAMPLE_POINT: u32 = 1;
pub const NOT_APPLIED: u32 = 2;

/// Rows of 4 floats per reaction in the floats' buffer (`REACTION_ROWS` in `shaders/drag.wgsl`):
/// centroid and half-width, force, paired sample point and flag, the low parts of the centroid
/// and of the sample point; the sums follow, one row per reaction, then the sample points.
const REACTION_ROWS: u64 = 5;

/// At most this many cells in the reactions' grid (4 MiB of starts): wider cells beyond.
const MOST_GRID_CELLS: u64 = 1 << 20;

/// The reactions' centres binned in a uniform grid: each reaction's centroid (entry 2r) and its
/// paired sample point (2r + 1), by a counting sort.
#[derive(Debug, Clone, PartialEq)]
pub struct ReactionGrid {
    pub lo: [f64; 3],
    pub cell: f64,
    pub dims: [u32; 3],
    /// Entries of cell c: `entries[starts[c] .. starts[c + 1]]`.
    pub starts: Vec<u32>,
    pub entries: Vec<u32>,
}

impl ReactionGrid {
    /// The grid of `centres` (point, entry) in cells at least `reach` wide; a centre that is not
    /// finite is left out (no particle could find it).
    pub fn of(centres: &[([f64; 3], u32)], reach: f64) -> ReactionGrid {
        let finite: Vec<([f64; 3], u32)> = centres
            .iter()
            .filter(|(c, _)| c.iter().all(|x| x.is_finite()))
            .copied()
            .collect();
        let centres = &finite[..];
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (c, _) in centres {
            for a in 0..3 {
                lo[a] = lo[a].min(c[a]);
                hi[a] = hi[a].max(c[a]);
            }
        }
        if centres.is_empty() {
            (lo, hi) = ([0.0; 3], [0.0; 3]);
        }
        let mut cell = reach.max(f64::MIN_POSITIVE);
        let dims = loop {
            let dims: [u32; 3] = std::array::from_fn(|a| ((hi[a] - lo[a]) / cell).floor() as u32 + 1);
            if dims.iter().map(|&d| u64::from(d)).product::<u64>() <= MOST_GRID_CELLS {
                break dims;
            }
            cell *= 2.0;
        };
        let index = |c: &[f64; 3]| {
            let k: [u32; 3] =
                std::array::from_fn(|a| (((c[a] - lo[a]) / cell).floor() as u32).min(dims[a] - 1));
            (k[0] + dims[0] * (k[1] + dims[1] * k[2])) as usize
        };
        let cells = (dims[0] * dims[1] * dims[2]) as usize;
        let mut starts = vec![0u32; cells + 1];
        for (c, _) in centres {
            starts[index(c) + 1] += 1;
        }
        for k in 0..cells {
            starts[k + 1] += starts[k];
        }
        let mut next = starts.clone();
        let mut entries = vec![0u32; centres.len()];
        for (c, e) in centres {
            let k = index(c);
            entries[next[k] as usize] = *e;
            next[k] += 1;
        }
        ReactionGrid {
            lo,
            cell,
            dims,
            starts,
            entries,
        }
    }
}

/// The reactions as the device holds them, to tell what changed.
#[derive(Debug, Clone, Default, PartialEq)]
struct Uploaded {
    reactions: Vec<f64>,
    sample_points: Vec<f64>,
    widths: Vec<f64>,
}

/// The drag coupling's buffers on the device (group 1 of its kernels) and what they hold.
pub struct DragState {
    params: wgpu::Buffer,
    floats: wgpu::Buffer,
    ints: wgpu::Buffer,
    /// Where the reactions' states and the samples are read back.
    staging: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    dp: DragParams,
    uploaded: Uploaded,
    /// Some reaction has a force: the step spreads them.
    loaded: bool,
    /// Each reaction's state in the last step (empty when none was spread).
    pub states: Vec<u32>,
    /// Bytes copied host → device and device → host.
    pub bytes: (u64, u64),
}

/// A storage (or map-read) buffer of `size` bytes (at least 16).
fn buffer(dev: &GpuDevice, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    dev.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16).next_multiple_of(16),
        usage,
        mapped_at_creation: false,
    })
}

const STORAGE: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
    .union(wgpu::BufferUsages::COPY_SRC)
    .union(wgpu::BufferUsages::COPY_DST);
const STAGING: wgpu::BufferUsages = wgpu::BufferUsages::MAP_READ.union(wgpu::BufferUsages::COPY_DST);

impl DragState {
    /// Empty buffers for particles of `spacing` on the grid of cells `cell` wide.
    fn new(dev: &GpuDevice, kernels: &Kernels, spacing: f64, cell: f64) -> DragState {
        let kernel = Wendland::for_spacing(spacing);
        let dp = DragParams {
            radius: kernel.radius as f32,
            norm: (21.0 / (2.0 * std::f64::consts::PI * kernel.radius.powi(3))) as f32,
            sample_reach: ((kernel.radius / cell) - 1e-9).ceil() as u32 + MARGIN_CELLS as u32,
            ..DragParams::default()
        };
        let params = buffer(
            dev,
            "drag params",
            std::mem::size_of::<DragParams>() as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let floats = buffer(dev, "drag floats", 16, STORAGE);
        let ints = buffer(dev, "drag ints", 16, STORAGE);
        let staging = buffer(dev, "drag staging", 16, STAGING);
        let bind_group = bind(dev, kernels, &params, &floats, &ints);
        DragState {
            params,
            floats,
            ints,
            staging,
            bind_group,
            dp,
            uploaded: Uploaded::default(),
            loaded: false,
            states: Vec::new(),
            bytes: (0, 0),
        }
    }

    /// Binds the buffers again (after the kernels were made anew: [`GpuEmps::regrow`]).
    pub fn rebind(&mut self, dev: &GpuDevice, kernels: &Kernels) {
        self.bind_group = bind(dev, kernels, &self.params, &self.floats, &self.ints);
    }

    /// Makes the buffers hold `floats` vec4s, `ints` words and `staging` bytes (kept when they
    /// do; contents of a grown buffer are copied over).
    fn reserve(&mut self, dev: &GpuDevice, kernels: &Kernels, floats: u64, ints: u64, staging: u64) {
        let mut grown = false;
        let mut enc = dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("drag") });
        for (b, size, label) in [
            (&mut self.floats, 16 * floats, "drag floats"),
            (&mut self.ints, 4 * ints, "drag ints"),
        ] {
            if b.size() < size {
                let fresh = buffer(dev, label, size + size / 2, STORAGE);
                enc.copy_buffer_to_buffer(b, 0, &fresh, 0, b.size());
                *b = fresh;
                grown = true;
            }
        }
        if grown {
            dev.queue.submit([enc.finish()]);
            self.rebind(dev, kernels);
        }
        if self.staging.size() < staging {
            self.staging = buffer(dev, "drag staging", staging + staging / 2, STAGING);
        }
    }

    fn write<T: Pod>(&mut self, dev: &GpuDevice, b: &wgpu::Buffer, offset: u64, data: &[T]) {
        let bytes: &[u8] = bytemuck::cast_slice(data);
        if !bytes.is_empty() {
            dev.queue.write_buffer(b, offset, bytes);
            self.bytes.0 += bytes.len() as u64;
        }
    }

    fn write_params(&mut self, dev: &GpuDevice) {
        let p = self.params.clone();
        let dp = self.dp;
        self.write(dev, &p, 0, std::slice::from_ref(&dp));
    }

    /// Hands over the point reactions (6 each: centroid, force), their paired sample points (3
    /// each, or none) and their members' widths (1 each, or none) for particles of `spacing`:
    /// uploaded when they changed, their grid rebuilt when their centres or widths did.
    fn set_reactions(
        &mut self,
        dev: &GpuDevice,
        kernels: &Kernels,
        (spacing, frame): (f64, &Frame),
        (reactions, sample_points, widths): (&[f64], &[f64], &[f64]),
    ) {
        let count = reactions.len() / 6;
        self.loaded = reactions
            .chunks_exact(6)
            .any(|r| r[3..6].iter().any(|&f| f != 0.0));
        let old = &self.uploaded;
        if old.reactions == reactions && old.sample_points == sample_points && old.widths == widths {
            return;
        }
        let same_centres = old.sample_points == sample_points
            && old.widths == widths
            && old.reactions.len() == reactions.len()
            && old
                .reactions
                .chunks_exact(6)
                .zip(reactions.chunks_exact(6))
                .all(|(a, b)| a[..3] == b[..3]);
        let paired = 2 * sample_points.len() == reactions.len();
        let half_widths: Vec<f64> = (0..count)
            .map(|k| widths.get(k).map_or(0.0, |&w| footprint_half_width(w, spacing)))
            .collect();
        let rows: Vec<[f32; 4]> = reactions
            .chunks_exact(6)
            .enumerate()
            .flat_map(|(k, r)| {
                let f = |x: f64| x as f32;
                let at = |p: &[f64]| frame.split([p[0], p[1], p[2]]);
                let (s, s_low) = match paired {
                    true => {
                        let ([x, y, z], [lx, ly, lz]) = at(&sample_points[3 * k..3 * k + 3]);
                        ([x, y, z, 1.0], [lx, ly, lz, 0.0])
                    }
                    false => ([0.0; 4], [0.0; 4]),
                };
                let ([cx, cy, cz], [lx, ly, lz]) = at(r);
                [
                    [cx, cy, cz, f(half_widths[k])],
                    [f(r[3]), f(r[4]), f(r[5]), 0.0],
                    s,
                    [lx, ly, lz, 0.0],
                    s_low,
                ]
            })
            .collect();
        let grid = (!same_centres).then(|| {
            // in the device's frame, where the particles are
            let at = |p: &[f64]| -> [f64; 3] { std::array::from_fn(|a| p[a] - frame.origin[a]) };
            let mut centres: Vec<([f64; 3], u32)> = Vec::with_capacity(2 * count);
            for (k, r) in reactions.chunks_exact(6).enumerate() {
                centres.push((at(r), 2 * k as u32));
                if paired {
                    centres.push((at(&sample_points[3 * k..3 * k + 3]), 2 * k as u32 + 1));
                }
            }
            let widest = schemas::validation::largest(half_widths.iter().copied(), 0.0);
            // a particle's cell is found from its high part, within half a quantum: cells a
            // quantum wider keep every particle within a footprint in the 27 cells it reads
            let slack = frame.quantum.unwrap_or(0.0);
            ReactionGrid::of(&centres, widest + f64::from(self.dp.radius) + slack)
        });
        // the states, and a new grid after them (an unchanged one is in place already)
        let ints = count + grid.as_ref().map_or(0, |g| g.starts.len() + g.entries.len());
        let floats = (REACTION_ROWS + 1) * count as u64;
        self.reserve(dev, kernels, floats, ints as u64, 4 * count as u64);
        let f = self.floats.clone();
        self.write(dev, &f, 0, &rows);
        if let Some(g) = grid {
            let i = self.ints.clone();
            self.write(dev, &i, 4 * count as u64, &g.starts);
            self.write(dev, &i, 4 * (count + g.starts.len()) as u64, &g.entries);
            self.dp.lo = g.lo.map(|x| x as f32);
            self.dp.inv_cell = (1.0 / g.cell) as f32;
            self.dp.dims = g.dims;
        }
        self.dp.reactions = count as u32;
        self.uploaded = Uploaded {
            reactions: reactions.to_vec(),
            sample_points: sample_points.to_vec(),
            widths: widths.to_vec(),
        };
    }
}

/// The drag's bind group (group 1) over its uniform block and buffers.
fn bind(
    dev: &GpuDevice,
    kernels: &Kernels,
    params: &wgpu::Buffer,
    floats: &wgpu::Buffer,
    ints: &wgpu::Buffer,
) -> wgpu::BindGroup {
    dev.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("drag"),
        layout: &kernels.drag_layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: params.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: floats.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: ints.as_entire_binding(),
            },
        ],
    })
}

impl GpuEmps {
    /// The drag's state, made on first use.
    fn drag_state(&self) -> std::sync::MutexGuard<'_, Option<DragState>> {
        let mut guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if guard.is_none() {
            let cell = 1.0 / f64::from(self.params.inv_cell);
            *guard = Some(DragState::new(
                &self.dev,
                &self.kernels,
                f64::from(self.params.spacing),
                cell,
            ));
        }
        guard
    }

    /// Hands over the point reactions (6 each: centroid, force) with their paired sample points
    /// (3 each, or none) and their members' widths (1 each, or none), spread over the fluid from
    /// the next step on, as [`crate::FluidSolver::set_point_reactions`] on the CPU.
    pub fn set_point_reactions(&mut self, reactions: &[f64], sample_points: &[f64], widths: &[f64]) {
        let spacing = f64::from(self.params.spacing);
        let frame = self.frame;
        let mut guard = self.drag_state();
        if let Some(d) = guard.as_mut() {
            d.set_reactions(
                &self.dev,
                &self.kernels,
                (spacing, &frame),
                (reactions, sample_points, widths),
            );
        }
    }

    /// Each reaction's state in the last step ([`SPREAD_AT_CENTROID`], [`SPREAD_AT_SAMPLE_POINT`],
    /// [`NOT_APPLIED`], or 3: no force); empty when the step spread none.
    pub fn reaction_states(&self) -> Vec<u32> {
        let guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        guard.as_ref().map_or(Vec::new(), |d| d.states.clone())
    }

    /// Bytes the drag coupling copied host → device and device → host.
    pub(super) fn drag_bytes(&self) -> (u64, u64) {
        let guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        guard.as_ref().map_or((0, 0), |d| d.bytes)
    }

    /// The flow at `points` (3 per point): velocity (3 per point) and λ_min (1 per point), as
    /// [`crate::unresolved::sampling::sample`] finds them, from the device's particles after the
    /// last step.
    pub fn sample_points(&self, points: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let count = points.len() / 3;
        if count == 0 {
            return (Vec::new(), Vec::new());
        }
        let mut guard = self.drag_state();
        let Some(d) = guard.as_mut() else {
            unreachable!("drag_state makes the state")
        };
        let first = (REACTION_ROWS + 1) * u64::from(d.dp.reactions);
        let n = count as u64;
        d.reserve(&self.dev, &self.kernels, first + 3 * n, 0, 16 * n);
        let parts: Vec<([f32; 3], [f32; 3])> = points
            .chunks_exact(3)
            .map(|p| self.frame.split([p[0], p[1], p[2]]))
            .collect();
        let rows: Vec<[f32; 4]> = parts.iter().map(|([x, y, z], _)| [*x, *y, *z, 0.0]).collect();
        let lows: Vec<[f32; 4]> = parts.iter().map(|(_, [x, y, z])| [*x, *y, *z, 0.0]).collect();
        let f = d.floats.clone();
        d.write(&self.dev, &f, 16 * first, &rows);
        d.write(&self.dev, &f, 16 * (first + 2 * n), &lows);
        d.dp.points = count as u32;
        d.write_params(&self.dev);
        let mut enc = self
            .dev
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("drag sampling"),
            });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("drag sampling"),
                timestamp_writes: None,
            });
            let k = &self.kernels;
            dispatch_drag(&mut pass, k, &k.sample_flow, &d.bind_group, count as u32);
        }
        let size = 16 * count as u64;
        enc.copy_buffer_to_buffer(&d.floats, 16 * (first + count as u64), &d.staging, 0, size);
        self.dev.queue.submit([enc.finish()]);
        let out: Vec<[f32; 4]> = map_read(&self.dev, &d.staging.slice(..size));
        d.bytes.1 += size;
        (
            out.iter()
                .flat_map(|s| s[..3].iter().map(|&x| f64::from(x)))
                .collect(),
            out.iter().map(|s| f64::from(s[3])).collect(),
        )
    }

    /// Whether some reaction handed over has a force (the step spreads them).
    pub(crate) fn spreads_reactions(&self) -> bool {
        let guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        guard.as_ref().is_some_and(|d| d.loaded)
    }

    /// Records the spreading of the reactions handed over into `enc` (the particles' cell list
    /// sorted for their present positions) with the copy of their states; for a step
    /// [`GpuEmps::spreads_reactions`] said yes to. [`GpuEmps::take_reaction_states`] reads the
    /// states after the submit.
    pub(super) fn encode_spreading(&self, enc: &mut wgpu::CommandEncoder) {
        let mut guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let Some(d) = guard.as_mut() else {
            return;
        };
        d.write_params(&self.dev);
        let reactions = d.dp.reactions;
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("drag spreading"),
                timestamp_writes: None,
            });
            let k = &self.kernels;
            dispatch_drag(&mut pass, k, &k.reaction_sums, &d.bind_group, reactions);
            dispatch_drag(&mut pass, k, &k.spread_reactions, &d.bind_group, self.params.n);
        }
        enc.copy_buffer_to_buffer(&d.ints, 0, &d.staging, 0, 4 * u64::from(reactions));
    }

    /// After the step's submit: the reactions' states its spreading copied
    /// ([`GpuEmps::encode_spreading`]) when it `spread` them, else none.
    pub(super) fn take_reaction_states(&self, spread: bool) {
        let mut guard = self
            .drag
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(d) = guard.as_mut() {
            let size = if spread { 4 * u64::from(d.dp.reactions) } else { 0 };
            d.states = match size {
                0 => Vec::new(),
                _ => map_read(&self.dev, &d.staging.slice(..size)),
            };
            d.bytes.1 += size;
        }
    }

    /// Binds the drag's buffers to the kernels made anew.
    pub(super) fn rebind_drag(&mut self) {
        let dev = &self.dev;
        if let Some(d) = self
            .drag
            .get_mut()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .as_mut()
        {
            d.rebind(dev, &self.kernels);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every centre is entered once, in the cell that holds it, and a point within `reach` of a
    /// centre finds it in the 27 cells around its own.
    #[test]
    fn the_reactions_grid_holds_each_centre_where_a_neighbour_finds_it() {
        let centres: Vec<([f64; 3], u32)> = (0..50)
            .map(|k| {
                let t = k as f64;
                (
                    [0.013 * t, 0.2 + 0.007 * (t * 1.7).sin(), -0.05 * (t * 0.3).cos()],
                    k as u32,
                )
            })
            .collect();
        let reach = 0.03;
        let g = ReactionGrid::of(&centres, reach);
        assert!(g.cell >= reach);
        assert_eq!(g.entries.len(), centres.len());
        let mut seen: Vec<u32> = g.entries.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..50).collect::<Vec<u32>>());
        let cell_of = |x: &[f64; 3]| -> [i64; 3] {
            std::array::from_fn(|a| ((x[a] - g.lo[a]) / g.cell).floor() as i64)
        };
        for (c, e) in &centres {
            // a point `reach` away along a diagonal
            let x = [c[0] + 0.5 * reach, c[1] - 0.5 * reach, c[2] + 0.7 * reach];
            let k = cell_of(&x);
            let mut found = false;
            for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let q = [k[0] + dx, k[1] + dy, k[2] + dz];
                        if (0..3).any(|a| q[a] < 0 || q[a] >= i64::from(g.dims[a])) {
                            continue;
                        }
                        let cell =
                            (q[0] + i64::from(g.dims[0]) * (q[1] + i64::from(g.dims[1]) * q[2])) as usize;
                        let range = g.starts[cell] as usize..g.starts[cell + 1] as usize;
                        found |= g.entries[range].contains(e);
                    }
                }
            }
            assert!(found, "centre {e} was not found from a point {reach} m away");
        }
    }
}
