// Bindings and helpers shared by every kernel of the GPU E-MPS step (src/gpu). One bind group
// holds every buffer; each kernel touches only the ones it needs.
// Precision: positions, velocities, number density, pressure and the per-particle sums are f32
// (see the README's GPU section); counts and indices are u32.

struct Params {
    origin: vec3<f32>, inv_cell: f32,
    dims: vec3<u32>, n: u32,
    gravity: vec3<f32>, dt: f32,
    re: f32, re_grad: f32, inv_n0: f32, grad_factor: f32,
    lap_factor: f32, nu: f32, rho: f32, c2: f32,
    coll_dist: f32, restitution: f32, reach: u32, reach_grad: u32,
    reach_coll: u32, cells: u32, pad: u32, viscous: u32,
    domain_lo: vec3<f32>, spacing: f32,
    domain_hi: vec3<f32>, wall_top: f32,
    tank_lo: vec3<f32>, open_top: u32,
    tank_hi: vec3<f32>, n_boxes: u32,
    mass: f32, volume: f32, scan_blocks: u32, n_bodies: u32,
    n_members: u32, reach_contact: u32, contact_k: f32, contact_c: f32,
    solid_lo: vec3<f32>, solid_inv_ds: f32,
    solid_n: vec3<u32>, solids: u32,
    n_damping: u32, av_scale: f32, av_eta2: f32, body_table: u32,
    paddle_first: u32, paddle_count: u32, paddle_row: u32, paddle_shift: f32,
    paddle_speed: f32, paddle_cos_m1: f32, paddle_sin: f32, paddle_dcos: f32,
    paddle_dsin: f32, hinge_x: f32, hinge_z: f32, quantum: f32,
    inflow_u: f32, inflow_dx: f32, inflow_enter: f32, inflow_cut: f32,
    outflow_x: f32, outflow_low: f32, hinge_low_x: f32, hinge_low_z: f32,
};

// Kind codes (src/particles/kind.rs).
const FLUID: u32 = 0u;
const WALL: u32 = 1u;
const DUMMY: u32 = 2u;
const BODY: u32 = 3u;
const INFLOW: u32 = 5u;
// A particle the open boundaries removed (shaders/open_boundary.wgsl): the next cell sort puts
// it past the particles it keeps.
const REMOVED: u32 = 255u;

const WG: u32 = 64u;
const SCAN_WG: u32 = 256u;
const NONE: u32 = 0xffffffffu;
// cell_count's flag of a cell that holds fluid.
const FLUID_CELL: u32 = 0x80000000u;

@group(0) @binding(0) var<uniform> prm: Params;
// xyz: position [m]; w: kind code.
@group(0) @binding(1) var<storage, read_write> pos: array<vec4<f32>>;
// xyz: velocity [m/s].
@group(0) @binding(2) var<storage, read_write> vel: array<vec4<f32>>;
// Stable particle id.
@group(0) @binding(3) var<storage, read_write> pid: array<u32>;
// x: number density n (S1-15); y: pressure P (S1-14).
@group(0) @binding(4) var<storage, read_write> dens: array<vec2<f32>>;
// Per-particle result of the last pair pass (Laplacian, gradient or collision Δu); free while
// the particles are sorted, when it takes the gathered positions, then velocities
// (cell_sort.wgsl).
@group(0) @binding(5) var<storage, read_write> acc: array<vec4<f32>>;
// xyz: force of non-fluid neighbours on the particle summed over the step's passes [N];
// w: unused.
@group(0) @binding(6) var<storage, read_write> wallf: array<vec4<f32>>;
// Neighbour candidates examined by the particle's slot in this step.
@group(0) @binding(7) var<storage, read_write> cand: array<u32>;
// Cell of each particle before the sort (unsorted order).
@group(0) @binding(8) var<storage, read_write> cell_of: array<u32>;
// Sorting permutation: sorted slot → index before the sort; then the gathered ids.
@group(0) @binding(9) var<storage, read_write> perm: array<u32>;
// Particles of cell c are cell_start[c] .. cell_start[c + 1] (cells + 1 entries).
@group(0) @binding(10) var<storage, read_write> cell_start: array<u32>;
// Bits 0–30: particles per cell (count pass), then counted down to 0 by the scatter; bit 31
// (FLUID_CELL): the cell holds fluid, kept after the scatter for fluid_near. Then (cells + 0 …
// cells + 3) the open boundaries' counters (shaders/open_boundary.wgsl): the removed particles
// the sort has placed, and the step's particles entered, removed and withdrawn.
@group(0) @binding(11) var<storage, read_write> cell_count: array<atomic<u32>>;
// Totals of the scan's blocks (then their exclusive prefix), then of their groups.
@group(0) @binding(12) var<storage, read_write> block_sums: array<u32>;
// Cell of each particle in the sorted order.
@group(0) @binding(13) var<storage, read_write> cell_sorted: array<u32>;
// Wall blocks for the instability detector: min (xyz), max (xyz) per box, shrunk by Δs/2.
@group(0) @binding(14) var<storage, read_write> boxes: array<vec4<f32>>;
// One partial per workgroup of the reduction (see reduce.wgsl).
@group(0) @binding(15) var<storage, read_write> partials: array<Partial>;
// The bodies' particles, sorted by id (bodies.wgsl); then, from row prm.paddle_row, the wave
// maker's paddle particles' rest positions by id − prm.paddle_first (paddle.wgsl).
@group(0) @binding(16) var<storage, read_write> members: array<Member>;
// Each body's pose and velocity, from the host each step it is given one.
@group(0) @binding(17) var<storage, read_write> body_kin: array<BodyKin>;
// One BodyLoad per workgroup of 256 particles, body and sum (load_slot: (group · bodies + body)
// · SUMS + sum).
@group(0) @binding(18) var<storage, read_write> body_partials: array<BodyLoad>;
// Each body's sums over the step's exchanges, SUMS per body: what the host reads back.
@group(0) @binding(19) var<storage, read_write> body_loads: array<BodyLoad>;
// Per cell: bit b % 32 set when a particle of body b lies within reach_react cells of it (the
// reaction's skip test, reaction.wgsl; filled by the cell sort). One entry without bodies.
@group(0) @binding(20) var<storage, read_write> body_cells: array<atomic<u32>>;
// The damping zones (damping.wgsl); one entry without zones.
@group(0) @binding(21) var<storage, read_write> damping: array<DampingZone>;
// One bit per site of the mesh solids' and terrains' lattice, set for a solid site (solids.wgsl);
// then, from word prm.body_table, the detector's table of the bodies and the mesh bodies' sites
// (body_inside.wgsl); one word without either.
@group(0) @binding(22) var<storage, read_write> solid_bits: array<u32>;

// Wide positions only (src/gpu/frame.rs): the low part of each particle's position, within half
// a quantum of 0 (xyz; w unused); one entry otherwise.
@group(0) @binding(23) var<storage, read_write> pos_lo: array<vec4<f32>>;

// A body particle's offset from its body's initial centre (f32), its id and its body; a paddle
// particle's rest position (x, 0, z; with wide positions its high parts, and the low parts in
// low_x, low_z).
struct Member {
    offset: vec3<f32>, id: u32,
    body: u32, low_x: f32, low_z: f32, _p2: u32,
};

// A body's pose and velocity for the step (f32): centre (its w: the lead), quaternion
// (w, x, y, z), V, ω, and the low part of the centre with wide positions (xyz).
struct BodyKin {
    centre: vec4<f32>, quat: vec4<f32>, vel: vec4<f32>, omega: vec4<f32>, low: vec4<f32>,
};

// The sums kept per body: the loads on the body summed by body particle (LOADS), the reaction
// on the fluid summed by fluid particle (REACTION, reaction.wgsl), and the walls' contact on the
// body, a part of LOADS that the walls take (WALLS).
const SUMS: u32 = 3u;
const LOADS: u32 = 0u;
const REACTION: u32 = 1u;
const WALLS: u32 = 2u;

// A damping zone (src/boundaries/damping.rs): its box, the axis (0 x, 1 y) and the sign (±1) of
// the direction the damping grows along, and its rate at the far face [1/s].
struct DampingZone {
    lo: vec3<f32>, axis: u32,
    hi: vec3<f32>, sign: f32,
    rate: f32, _p0: u32, _p1: u32, _p2: u32,
};

// Force and moment about the body's centre (xyz of each; f32).
struct BodyLoad {
    force: vec4<f32>, moment: vec4<f32>,
};

struct Partial {
    wall: vec3<f32>, energy: f32,
    candidates: u32, finding: u32, escaped: u32, fluid: u32,
    fastest: f32, _p0: u32, _p1: u32, _p2: u32,
};

// Where an invocation is in a dispatch of rows of workgroups (kernels::dispatch: past the
// device's workgroups per dimension, a dispatch is 2-D): the workgroups are numbered row by row.
struct Invocation {
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
};

// Linear index of the invocation's workgroup.
fn group_index(v: Invocation) -> u32 {
    return v.group.y * v.groups.x + v.group.x;
}

// Linear index of the invocation in a dispatch of workgroups of `size` threads.
fn item_index(v: Invocation, size: u32) -> u32 {
    return group_index(v) * size + v.local;
}

// Wide positions (src/gpu/frame.rs): set when the tank is longer than 16 777 spacings. Each
// position is then hi + lo, hi (pos.xyz) a multiple of prm.quantum, lo (pos_lo) within half of
// it; off, the helpers below are plain f32 arithmetic on pos.
override WIDE: bool = false;

// The low part of particle i's position (0 with plain positions).
fn low(i: u32) -> vec3<f32> {
    if WIDE {
        return pos_lo[i].xyz;
    }
    return vec3<f32>(0.0);
}

// r_j − r_i of particle j (high part pj) from a point of high part xi and low part li.
fn apart(pj: vec3<f32>, j: u32, xi: vec3<f32>, li: vec3<f32>) -> vec3<f32> {
    if WIDE {
        return (pj - xi) + (pos_lo[j].xyz - li);
    }
    return pj - xi;
}

// apart for the step's pair passes, whose radii are at most r_e: a candidate whose high parts
// lie further apart than r_e + a quantum is out of every pass's reach whatever its low parts,
// so its low part is not read (about three candidates in four: memory the pair loops save).
fn apart_near(pj: vec3<f32>, j: u32, xi: vec3<f32>, li: vec3<f32>) -> vec3<f32> {
    if WIDE {
        let d = pj - xi;
        let far = prm.re + prm.quantum;
        if dot(d, d) > far * far {
            return d;
        }
        return d + (pos_lo[j].xyz - li);
    }
    return pj - xi;
}

// With wide positions only: puts particle i (kind kept) at hi + lo, hi a multiple of the
// quantum, lo's whole quanta carried into hi (exact: both are multiples of it, and hi stays
// below 2²⁴ quanta).
fn place(i: u32, hi: vec3<f32>, lo: vec3<f32>) {
    let q = prm.quantum;
    let carry = round(lo / q) * q;
    pos[i] = vec4<f32>(hi + carry, pos[i].w);
    pos_lo[i] = vec4<f32>(lo - carry, 0.0);
}

// Moves particle i by d (S1-11, S1-13's r += u Δt).
fn shift(i: u32, d: vec3<f32>) {
    if WIDE {
        place(i, pos[i].xyz, pos_lo[i].xyz + d);
        return;
    }
    pos[i] = vec4<f32>(pos[i].xyz + d, pos[i].w);
}

fn kind_of(i: u32) -> u32 {
    return u32(pos[i].w);
}

// Cell index of a point, clamped onto the grid's inner border like CellGrid::cell_index.
fn cell_index(p: vec3<f32>) -> u32 {
    let c = floor((p - prm.origin) * prm.inv_cell);
    let lo = f32(prm.pad);
    let hi = vec3<f32>(prm.dims - vec3<u32>(prm.pad + 1u));
    let cc = vec3<u32>(min(max(c, vec3<f32>(lo)), hi));
    return cc.x + prm.dims.x * (cc.y + prm.dims.y * cc.z);
}

// Whether a cell within `r` cells of cell c holds fluid (CellGrid::fluid_near): after the
// scatter, a cell's count is 0 and only its FLUID_CELL flag is left.
fn fluid_near(c: u32, r: u32) -> bool {
    let nx = prm.dims.x;
    let nxy = nx * prm.dims.y;
    let base = c - r * nxy - r * nx - r;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            for (var dx = 0u; dx <= 2u * r; dx = dx + 1u) {
                if (atomicLoad(&cell_count[base + dz * nxy + dy * nx + dx]) & FLUID_CELL) != 0u {
                    return true;
                }
            }
        }
    }
    return false;
}

// First particle slot of the run of cells along x that starts `reach` cells before cell c,
// shifted by (dy, dz) rows, and one past its last slot.
fn row_range(c: u32, reach: u32, dy: u32, dz: u32) -> vec2<u32> {
    let nx = prm.dims.x;
    let nxy = nx * prm.dims.y;
    let row = c + dz * nxy + dy * nx;
    let lo = row - reach * nxy - reach * nx - reach;
    return vec2<u32>(cell_start[lo], cell_start[lo + 2u * reach + 1u]);
}
