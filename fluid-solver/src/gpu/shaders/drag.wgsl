// The fluid's side of the unresolved drag coupling on the device (src/unresolved, S2 §4): the
// flow at the coupler's sample points (Shepard velocity and λ_min of the moment matrix, S2-10)
// and the point reactions spread over the fluid around their centroids (S2-24 over the members'
// footprints). The same kernel and rules as the CPU's; sums in f32. Bound in group 1 (their
// sizes change with the coupler's points, src/gpu/drag.rs).

// The drag coupling's constants for one dispatch.
struct DragParams {
    // The reactions' grid (src/gpu/drag.rs ReactionGrid): origin, 1 / cell, cells per axis.
    lo: vec3<f32>, inv_cell: f32,
    dims: vec3<u32>, points: u32,
    // Wendland C2 (src/unresolved/kernel.rs): support R and 21 / (2π R³).
    radius: f32, norm: f32, reactions: u32,
    // Cells (of the particles' grid) each way a sample point reads: its support and a margin for
    // what the particles moved since the step's last sort.
    sample_reach: u32,
};

@group(1) @binding(0) var<uniform> drg: DragParams;
// REACTION_ROWS per reaction: (centroid, footprint half-width a), (force, 0), (paired sample
// point, 1 when there is one), and the low parts of the centroid and of the sample point (with
// wide positions, src/gpu/frame.rs; 0 otherwise); then 1 per reaction: (Σ_k W(ρ_k), 0, 0, 0);
// then the sample points (xyz), the flow at them (velocity, λ_min), and their low parts.
@group(1) @binding(1) var<storage, read_write> drag_f: array<vec4<f32>>;
// [0, reactions): each reaction's state in the step (REACTION_*); then the reactions' grid: its
// cells' starts (cells + 1), then its entries (reaction · 2 + 1 for a paired sample point's,
// reaction · 2 for a centroid's).
@group(1) @binding(2) var<storage, read_write> drag_u: array<u32>;

// A reaction's state: spread around its centroid, around its sample point (no fluid near the
// centroid), not applied (no fluid near either), no force (not spread).
const REACTION_CENTROID: u32 = 0u;
const REACTION_MOVED: u32 = 1u;
const REACTION_UNAPPLIED: u32 = 2u;
const REACTION_IDLE: u32 = 3u;

// W(r) (src/unresolved/kernel.rs Wendland::value).
fn wendland(r: f32) -> f32 {
    let q = r / drg.radius;
    if q >= 1.0 {
        return 0.0;
    }
    let s = 1.0 - q;
    return drg.norm * s * s * s * s * (1.0 + 4.0 * q);
}

// dW/dr (Wendland::derivative).
fn wendland_slope(r: f32) -> f32 {
    let q = r / drg.radius;
    if q >= 1.0 {
        return 0.0;
    }
    let s = 1.0 - q;
    return -20.0 * drg.norm * q * s * s * s / drg.radius;
}

// The particles' cell of x along each axis, clamped onto the grid (unlike cell_index, not onto
// its inner border: a point may lie anywhere).
fn grid_cell(x: vec3<f32>) -> vec3<i32> {
    let c = floor((x - prm.origin) * prm.inv_cell);
    let hi = vec3<f32>(prm.dims - vec3<u32>(1u));
    return vec3<i32>(clamp(c, vec3<f32>(0.0), hi));
}

// The slots of the particles' cells from cell (x0, y, z) to (x1, y, z).
fn grid_row(x0: i32, x1: i32, y: i32, z: i32) -> vec2<u32> {
    let row = u32(y) * prm.dims.x + u32(z) * prm.dims.x * prm.dims.y;
    return vec2<u32>(cell_start[row + u32(x0)], cell_start[row + u32(x1) + 1u]);
}

// The smallest eigenvalue of the symmetric 3 × 3 matrix [[a b c] [b d e] [c e f]]
// (sampling.rs smallest_eigenvalue: Smith 1961).
fn smallest_eigenvalue(a: f32, b: f32, c: f32, d: f32, e: f32, f: f32) -> f32 {
    let off = b * b + c * c + e * e;
    let q = (a + d + f) / 3.0;
    let p2 = (a - q) * (a - q) + (d - q) * (d - q) + (f - q) * (f - q) + 2.0 * off;
    if p2 <= 1e-14 * max(q * q, 1e-30) {
        return q;
    }
    let p = sqrt(p2 / 6.0);
    let ba = (a - q) / p;
    let bd = (d - q) / p;
    let bf = (f - q) / p;
    let bb = b / p;
    let bc = c / p;
    let be = e / p;
    let det = ba * (bd * bf - be * be) - bb * (bb * bf - be * bc) + bc * (bb * be - bd * bc);
    let phi = acos(clamp(0.5 * det, -1.0, 1.0)) / 3.0;
    return q + 2.0 * p * cos(phi + 2.0 * 3.14159265358979 / 3.0);
}

// sampling.rs sample: the Shepard velocity of the fluid within the support of point k and the
// smallest eigenvalue of the moment matrix Σ_j V_j (x_j − x) ⊗ ∇W(x − x_j) over every particle
// there; (0, 0) where no fluid is within the support.
@compute @workgroup_size(64)
fn sample_flow(v: Invocation) {
    let k = item_index(v, WG);
    if k >= drg.points {
        return;
    }
    let points = points_row();
    let x = drag_f[points + k].xyz;
    let xl = drag_f[points + 2u * drg.points + k].xyz;
    let c = grid_cell(x);
    let reach = i32(drg.sample_reach);
    let lo = max(c - vec3<i32>(reach), vec3<i32>(0));
    let hi = min(c + vec3<i32>(reach), vec3<i32>(prm.dims) - vec3<i32>(1));
    let r2max = drg.radius * drg.radius;
    var u = vec3<f32>(0.0);
    var weight = 0.0;
    // the upper triangle: xx xy xz yy yz zz
    var m0 = vec3<f32>(0.0);
    var m1 = vec3<f32>(0.0);
    for (var z = lo.z; z <= hi.z; z = z + 1) {
        for (var y = lo.y; y <= hi.y; y = y + 1) {
            let run = grid_row(lo.x, hi.x, y, z);
            for (var j = run.x; j < run.y; j = j + 1u) {
                let kind = kind_of(j);
                if kind == REMOVED {
                    continue;
                }
                let d = apart(pos[j].xyz, j, x, xl);
                let r2 = dot(d, d);
                if r2 >= r2max {
                    continue;
                }
                let r = sqrt(r2);
                if kind == FLUID {
                    let w = prm.volume * wendland(r);
                    weight = weight + w;
                    u = u + w * vel[j].xyz;
                }
                if r > 0.0 {
                    let s = -prm.volume * wendland_slope(r) / r;
                    m0 = m0 + s * d.x * d;
                    m1 = m1 + s * vec3<f32>(d.y * d.y, d.y * d.z, d.z * d.z);
                }
            }
        }
    }
    if weight <= 0.0 {
        drag_f[points + drg.points + k] = vec4<f32>(0.0);
        return;
    }
    let lambda = smallest_eigenvalue(m0.x, m0.y, m0.z, m1.x, m1.y, m1.z);
    drag_f[points + drg.points + k] = vec4<f32>(u / weight, lambda);
}

// Σ_k W(max(0, |x_k − x| − a)) over the fluid particles around x (spreading.rs shares_around,
// before normalising), the particles' cell list being sorted for their present positions.
fn footprint_sum(x: vec3<f32>, xl: vec3<f32>, a: f32) -> f32 {
    let reach = a + drg.radius;
    let cells = i32(ceil(reach * prm.inv_cell));
    let c = grid_cell(x);
    let lo = max(c - vec3<i32>(cells), vec3<i32>(0));
    let hi = min(c + vec3<i32>(cells), vec3<i32>(prm.dims) - vec3<i32>(1));
    var sum = 0.0;
    for (var z = lo.z; z <= hi.z; z = z + 1) {
        for (var y = lo.y; y <= hi.y; y = y + 1) {
            let run = grid_row(lo.x, hi.x, y, z);
            for (var j = run.x; j < run.y; j = j + 1u) {
                if kind_of(j) != FLUID {
                    continue;
                }
                sum = sum + wendland(max(0.0, length(apart(pos[j].xyz, j, x, xl)) - a));
            }
        }
    }
    return sum;
}

// Rows per reaction in drag_f.
const REACTION_ROWS: u32 = 5u;

// The base of reaction r's rows in drag_f.
fn reaction_row(r: u32) -> u32 {
    return REACTION_ROWS * r;
}

// The first row of the sample points in drag_f.
fn points_row() -> u32 {
    return (REACTION_ROWS + 1u) * drg.reactions;
}

// spreading.rs share_of, the normalisation of each reaction with a force: its weights' sum
// around its centroid, else (no fluid there) around its paired sample point, else not applied.
@compute @workgroup_size(64)
fn reaction_sums(v: Invocation) {
    let r = item_index(v, WG);
    if r >= drg.reactions {
        return;
    }
    let row = reaction_row(r);
    let centroid = drag_f[row];
    let force = drag_f[row + 1u].xyz;
    let sums = REACTION_ROWS * drg.reactions;
    if all(force == vec3<f32>(0.0)) {
        drag_u[r] = REACTION_IDLE;
        return;
    }
    var state = REACTION_CENTROID;
    var sum = footprint_sum(centroid.xyz, drag_f[row + 3u].xyz, centroid.w);
    let paired = drag_f[row + 2u];
    if sum <= 0.0 && paired.w > 0.0 {
        state = REACTION_MOVED;
        sum = footprint_sum(paired.xyz, drag_f[row + 4u].xyz, centroid.w);
    }
    if sum <= 0.0 {
        state = REACTION_UNAPPLIED;
    }
    drag_u[r] = state;
    drag_f[sums + r] = vec4<f32>(sum, 0.0, 0.0, 0.0);
}

// spreading.rs spread, gathered by each fluid particle from the reactions whose centre
// (centroid or sample point, as reaction_sums chose) lies in the 27 cells of the reactions' grid
// around it: u += Σ_r F_r W(ρ_r) / Σ_r Δt / m, ρ_r = max(0, |x − x_r| − a_r).
@compute @workgroup_size(64)
fn spread_reactions(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let x = pos[i].xyz;
    let c = vec3<i32>(floor((x - drg.lo) * drg.inv_cell));
    let top = vec3<i32>(drg.dims) - vec3<i32>(1);
    if any(c < vec3<i32>(-1)) || any(c > top + vec3<i32>(1)) {
        return;
    }
    let lo = max(c - vec3<i32>(1), vec3<i32>(0));
    let hi = min(c + vec3<i32>(1), top);
    let starts = drg.reactions;
    let cells = drg.dims.x * drg.dims.y * drg.dims.z;
    let entries = starts + cells + 1u;
    let sums = REACTION_ROWS * drg.reactions;
    let xl = low(i);
    var f = vec3<f32>(0.0);
    for (var z = lo.z; z <= hi.z; z = z + 1) {
        for (var y = lo.y; y <= hi.y; y = y + 1) {
            for (var xc = lo.x; xc <= hi.x; xc = xc + 1) {
                let cell = u32(xc) + drg.dims.x * (u32(y) + drg.dims.y * u32(z));
                for (var e = drag_u[starts + cell]; e < drag_u[starts + cell + 1u]; e = e + 1u) {
                    let entry = drag_u[entries + e];
                    let r = entry >> 1u;
                    let moved = entry & 1u;
                    let state = drag_u[r];
                    if state != moved {
                        continue;
                    }
                    let row = reaction_row(r);
                    let centroid = drag_f[row];
                    var centre = centroid.xyz;
                    var centre_low = drag_f[row + 3u].xyz;
                    if moved == 1u {
                        centre = drag_f[row + 2u].xyz;
                        centre_low = drag_f[row + 4u].xyz;
                    }
                    let w = wendland(max(0.0, length((x - centre) + (xl - centre_low)) - centroid.w));
                    if w > 0.0 {
                        f = f + drag_f[row + 1u].xyz * (w / drag_f[sums + r].x);
                    }
                }
            }
        }
    }
    if any(f != vec3<f32>(0.0)) {
        vel[i] = vec4<f32>(vel[i].xyz + f * (prm.dt / prm.mass), 0.0);
    }
}
