// The ISPH step on the device (src/gpu/isph.rs): the stages of src/isph/step.rs with the default
// discretisation (pressure_gradient = "conservative": the exact projection of
// src/isph/exact_projection.rs, pairs corrected by the moment matrices of
// src/isph/kernel_correction.rs), as gathers: particle i sums over the particles of the cells
// around its own and writes only its own slots. Compiled with common.wgsl (group 0: the
// particles, the cell list, the reduction); its own arrays are group 1. f32 throughout, the
// conjugate gradient's scalars included (their sums run over per-workgroup partials).

struct IsphParams {
    w_factor: f32, dw_factor: f32, inv_radius: f32, volume: f32,
    lattice_density: f32, lattice_moment: f32, radius: f32, reach: u32,
    rho: f32, alpha_d: f32, eps: f32, dt_p: f32,
    dt: f32, share: f32, n0_mps: f32, nu: f32,
    gravity: vec3<f32>, tol2: f32,
    corrected: u32, no_slip: u32, viscous: u32, groups: u32,
    max_iterations: u32, spacing: f32, short: u32, _pad: u32,
};

@group(1) @binding(0) var<uniform> ip: IsphParams;
// ρ̂/ρ0 of fluid particles, the fill of solids' supports (S2-7, src/isph/operators.rs).
@group(1) @binding(1) var<storage, read_write> ratio: array<f32>;
// 1 for the particles that take part in the free-surface detection (src/isph/free_surface.rs).
@group(1) @binding(2) var<storage, read_write> part: array<u32>;
// 1 for fluid on the free surface (p = Dirichlet value), and for fluid without fluid neighbours.
@group(1) @binding(3) var<storage, read_write> surf: array<u32>;
// The kernel correction L_i (rows 3i … 3i + 2; w of the first row 1 where it is not I).
@group(1) @binding(4) var<storage, read_write> lmat: array<vec4<f32>>;
// The walls' completion M_i of surface water the PPE does not hold (src/isph/surface_walls.rs;
// w of the first row 1 where there is one).
@group(1) @binding(5) var<storage, read_write> smat: array<vec4<f32>>;
// By particle id: a solid's normal into the fluid (xyz) and its depth behind its wall's face (w)
// (src/isph/walls.rs), computed on the host once: the walls are fixed.
@group(1) @binding(6) var<storage, read_write> geom: array<vec4<f32>>;
// By particle id: 1 for a solid on a convex edge or corner (walls.rs CONVEX).
@group(1) @binding(7) var<storage, read_write> convex: array<u32>;
// The Dirichlet pressure of each surface particle (free_surface::surface_pressure).
@group(1) @binding(8) var<storage, read_write> dirich: array<f32>;
// A vector field on the fluid: the known gradient's (ρ/Δt) v* − c, then G_x d (xyz).
@group(1) @binding(9) var<storage, read_write> yv: array<vec4<f32>>;
// The conjugate gradient's vectors by particle (0 off the unknowns): solution, residual,
// direction, operator times direction; the Jacobi diagonal and the right-hand side.
@group(1) @binding(10) var<storage, read_write> xs: array<f32>;
@group(1) @binding(11) var<storage, read_write> rs: array<f32>;
@group(1) @binding(12) var<storage, read_write> ds: array<f32>;
@group(1) @binding(13) var<storage, read_write> qs: array<f32>;
@group(1) @binding(14) var<storage, read_write> dg: array<f32>;
@group(1) @binding(15) var<storage, read_write> bs: array<f32>;
// The velocities at the step's start, kept over a short step (IsphStep::short_step).
@group(1) @binding(16) var<storage, read_write> vstart: array<vec4<f32>>;
// Per-workgroup partial sums of the conjugate gradient's dot products (4 per workgroup).
@group(1) @binding(17) var<storage, read_write> cgp: array<f32>;
// The conjugate gradient's scalars (CG_* below).
@group(1) @binding(18) var<storage, read_write> cgs: array<f32>;

const CG_B2: u32 = 0u;
const CG_R2: u32 = 1u;
const CG_RZ: u32 = 2u;
const CG_ALPHA: u32 = 3u;
const CG_BETA: u32 = 4u;
// 0 iterating, 1 converged, 2 failed (iterations spent or not finite), 3 zero right-hand side.
const CG_DONE: u32 = 5u;
const CG_ITER: u32 = 6u;
const CG_TARGET: u32 = 7u;
const CG_UNKNOWNS: u32 = 8u;

// S2-11's thresholds, the wet fill, the divergence floor's companions (free_surface.rs).
const LAMBDA_SPLASH: f32 = 0.2;
const LAMBDA_INNER: f32 = 0.9;
const WET_FILL: f32 = 0.9;
// surface_walls.rs MIN_WALL_SHARE.
const MIN_WALL_SHARE: f32 = 0.1;

// Wendland C2 (src/isph/kernel.rs) at q = r / r_e, and W'/r renormalised on the lattice.
fn w_at(q: f32) -> f32 {
    if q < 1.0 {
        let a = 1.0 - q;
        return ip.w_factor * a * a * a * a * (1.0 + 4.0 * q);
    }
    return 0.0;
}

fn dw_at(q: f32) -> f32 {
    if q < 1.0 {
        let a = 1.0 - q;
        return ip.dw_factor * a * a * a;
    }
    return 0.0;
}

fn is_unknown(i: u32) -> bool {
    return kind_of(i) == FLUID && surf[i] == 0u;
}

// Symmetric 3×3 matrices as (xx, xy, xz) and (yy, yz, zz).
struct Sym {
    a: vec3<f32>, b: vec3<f32>,
};

fn sym_add(m: Sym, c: f32, d: vec3<f32>) -> Sym {
    return Sym(m.a + c * d.x * d, m.b + c * vec3<f32>(d.y * d.y, d.y * d.z, d.z * d.z));
}

fn sym_full(m: Sym) -> mat3x3<f32> {
    return mat3x3<f32>(m.a, vec3<f32>(m.a.y, m.b.x, m.b.y), vec3<f32>(m.a.z, m.b.y, m.b.z));
}

// The smallest eigenvalue of a symmetric 3×3 matrix (moments.rs smallest_eigenvalue: the
// trigonometric closed form, Smith 1961).
fn smallest_eigenvalue(m: mat3x3<f32>) -> f32 {
    let p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    let q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    if p1 <= 1e-12 * max(q * q, 1e-30) {
        return min(m[0][0], min(m[1][1], m[2][2]));
    }
    let p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) + (m[2][2] - q) * (m[2][2] - q)
        + 2.0 * p1;
    let p = sqrt(p2 / 6.0);
    let b = (m - mat3x3<f32>(q, 0.0, 0.0, 0.0, q, 0.0, 0.0, 0.0, q)) * (1.0 / p);
    let phi = acos(clamp(determinant(b) / 2.0, -1.0, 1.0)) / 3.0;
    return q + 2.0 * p * cos(phi + 2.0943951);
}

// λ_min where it is at most `settled`, a lower bound above it (smallest_eigenvalue_up_to).
fn smallest_eigenvalue_up_to(m: mat3x3<f32>, settled: f32) -> f32 {
    let bound = min(m[0][0] - abs(m[0][1]) - abs(m[0][2]),
        min(m[1][1] - abs(m[1][0]) - abs(m[1][2]), m[2][2] - abs(m[2][0]) - abs(m[2][1])));
    if bound > settled {
        return bound;
    }
    return smallest_eigenvalue(m);
}

// Whether m is regular by moments.rs' test (|det| above 1e-12 of its largest entry cubed; in
// f32 1e-6).
fn regular(m: mat3x3<f32>) -> bool {
    let big = max(max(max(abs(m[0][0]), abs(m[0][1])), max(abs(m[0][2]), abs(m[1][1]))),
        max(abs(m[1][2]), abs(m[2][2])));
    let det = determinant(m);
    return abs(det) > 1e-6 * big * big * big && det == det;
}

// L_i v (v itself where particle i's correction is I).
fn corrected(i: u32, v: vec3<f32>) -> vec3<f32> {
    if ip.corrected == 0u || lmat[3u * i].w == 0.0 {
        return v;
    }
    return vec3<f32>(dot(lmat[3u * i].xyz, v), dot(lmat[3u * i + 1u].xyz, v), dot(lmat[3u * i + 2u].xyz, v));
}

// The pair vector of fluid i and fluid j, ½ (L_i + L_j) v (kernel_correction.rs).
fn pair_fluid(i: u32, j: u32, v: vec3<f32>) -> vec3<f32> {
    return 0.5 * (corrected(i, v) + corrected(j, v));
}

// A wall term t of surface particle i completed by the walls (surface_walls.rs).
fn completed(i: u32, t: vec3<f32>) -> vec3<f32> {
    if smat[3u * i].w == 0.0 {
        return t;
    }
    return vec3<f32>(dot(smat[3u * i].xyz, t), dot(smat[3u * i + 1u].xyz, t), dot(smat[3u * i + 2u].xyz, t));
}

// The normal of the face fluid particle f (at xf from w) stands in front of, for a convex solid
// w (NeumannPair::face_normal): among w's solid neighbours on a face, the normal with the
// largest n·(x_f − x_w); w's own where it has none.
fn face_normal(w: u32, to_f: vec3<f32>, own: vec3<f32>) -> vec3<f32> {
    let xw = pos[w].xyz;
    let lw = low(w);
    let c = cell_sorted[w];
    let r = ip.reach;
    let re2 = ip.radius * ip.radius;
    var best = -3.0e38;
    var n_best = own;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                if j == w || kind_of(j) == FLUID {
                    continue;
                }
                let d = apart_near(pos[j].xyz, j, xw, lw);
                if dot(d, d) >= re2 {
                    continue;
                }
                let id = pid[j];
                let g = geom[id];
                if convex[id] != 0u || g.w >= ip.spacing || all(g.xyz == vec3<f32>(0.0)) {
                    continue;
                }
                let ahead = dot(g.xyz, to_f);
                if ahead > best {
                    best = ahead;
                    n_best = g.xyz;
                }
            }
        }
    }
    return n_best;
}

// Δp_fw = p_w − p_f of fluid f and solid w at d = x_w − x_f, with v* in the particles and the
// step's Δt_p (NeumannPair::difference, src/isph/walls.rs).
fn wall_difference(f: u32, w: u32, d: vec3<f32>) -> f32 {
    let g = ip.gravity;
    let hydro = ip.rho * dot(g, d);
    let id = pid[w];
    let geo = geom[id];
    var n = geo.xyz;
    if convex[id] != 0u {
        n = face_normal(w, -d, n);
    }
    let u = vel[f].xyz - g * ip.dt_p - vel[w].xyz;
    var un = dot(u, n);
    let dn = dot(d, n);
    if surf[f] != 0u {
        let gap = max(-dn - geo.w - 0.5 * ip.spacing, 0.0);
        un = min(un + gap / ip.dt_p, 0.0);
    }
    return hydro + ip.rho / ip.dt_p * un * dn;
}

// S2-7 normalised (operators::density_ratio) and the detection's flags (fill_flags); the fluid's
// number density becomes n0 ρ̂/ρ0 (the shared probes' measure).
@compute @workgroup_size(64)
fn isph_density(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    let k = kind_of(i);
    let c = cell_sorted[i];
    var fill = 1.0;
    if k == FLUID || fluid_near(c, ip.reach) {
        let xi = pos[i].xyz;
        let li = low(i);
        let re2 = ip.radius * ip.radius;
        var s = ip.volume * w_at(0.0);
        var seen = 0u;
        let r = ip.reach;
        for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
            for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
                let range = row_range(c, r, dy, dz);
                seen = seen + range.y - range.x;
                for (var j = range.x; j < range.y; j = j + 1u) {
                    let d = apart_near(pos[j].xyz, j, xi, li);
                    let r2 = dot(d, d);
                    if r2 < re2 && j != i {
                        s = s + ip.volume * w_at(sqrt(r2) * ip.inv_radius);
                    }
                }
            }
        }
        fill = s / ip.lattice_density;
        cand[i] = cand[i] + seen;
    }
    ratio[i] = fill;
    part[i] = u32(k == FLUID || fill >= WET_FILL);
    var nd = 0.0;
    if k == FLUID {
        nd = ip.n0_mps * fill;
    }
    dens[i] = vec2<f32>(nd, dens[i].y);
}

// The surface flags (free_surface::detect): λ_min of S2-10 over the neighbours that take part,
// normalised (free_surface::lambda_min), S2-11's thresholds, in between Marrone's normal and the
// umbrella; and fluid without fluid neighbours (the PPE's rule, IsphStep::assemble).
@compute @workgroup_size(64)
fn isph_surface(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        surf[i] = 0u;
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    let scale = -ip.volume / ip.lattice_moment;
    var m = Sym(vec3<f32>(0.0), vec3<f32>(0.0));
    var g = vec3<f32>(0.0);
    var fluid_neighbour = false;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 < re2 && j != i {
                    if kind_of(j) == FLUID {
                        fluid_neighbour = true;
                    }
                    if part[j] != 0u {
                        let w = dw_at(sqrt(r2) * ip.inv_radius);
                        m = sym_add(m, scale * w, d);
                        // ∇_i W_ij = (W'/r)(x_i − x_j)
                        g = g - ip.volume * w * d;
                    }
                }
            }
        }
    }
    let l = smallest_eigenvalue_up_to(sym_full(m), LAMBDA_INNER);
    var s = 0u;
    if !fluid_neighbour || l <= LAMBDA_SPLASH {
        s = 1u;
    } else if l <= LAMBDA_INNER {
        let mm = sym_full(m);
        if regular(mm) {
            let nu = inverse3(mm) * g;
            let norm = length(nu);
            if norm > 0.0 && norm <= 3.0e38 {
                let n = -nu / norm;
                if umbrella_is_empty(i, n) {
                    s = 1u;
                }
            }
        }
    }
    surf[i] = s;
}

// The inverse of a regular 3×3 matrix (adjugate over determinant).
fn inverse3(m: mat3x3<f32>) -> mat3x3<f32> {
    let a = m[0];
    let b = m[1];
    let c = m[2];
    let r0 = cross(b, c);
    let r1 = cross(c, a);
    let r2 = cross(a, b);
    let det = dot(a, r0);
    // the rows of m⁻¹ are r0, r1, r2 over det (m symmetric or not: columns a, b, c)
    return transpose(mat3x3<f32>(r0, r1, r2)) * (1.0 / det);
}

// Whether no neighbour that takes part occupies the umbrella along n (free_surface.rs).
fn umbrella_is_empty(i: u32, n: vec3<f32>) -> bool {
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let h = 0.5 * ip.radius;
    let t = h * n;
    let near2 = 2.0 * h * h;
    let r = ip.reach;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i || part[j] == 0u {
                    continue;
                }
                if r2 < near2 {
                    let along = dot(d, n);
                    let across2 = max(r2 - along * along, 0.0);
                    if along > 0.0 && across2 < along * along {
                        return false;
                    }
                } else {
                    let e = d - t;
                    if dot(e, e) < h * h {
                        return false;
                    }
                }
            }
        }
    }
    return true;
}

// Per fluid particle, after the surface flags: the Dirichlet value of a surface particle
// (free_surface::surface_pressure, from the last step's pressures), the kernel correction L_i
// (kernel_correction::corrections) and the walls' completion M_i of surface water the PPE does
// not hold (surface_walls::completions).
@compute @workgroup_size(64)
fn isph_fields(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    lmat[3u * i] = vec4<f32>(1.0, 0.0, 0.0, 0.0);
    lmat[3u * i + 1u] = vec4<f32>(0.0, 1.0, 0.0, 0.0);
    lmat[3u * i + 2u] = vec4<f32>(0.0, 0.0, 1.0, 0.0);
    smat[3u * i] = vec4<f32>(0.0);
    dirich[i] = 0.0;
    if kind_of(i) != FLUID {
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    let on_surface = surf[i] != 0u;
    var s = vec3<f32>(0.0);
    var every = Sym(vec3<f32>(0.0), vec3<f32>(0.0));
    var fluid = Sym(vec3<f32>(0.0), vec3<f32>(0.0));
    var wall = Sym(vec3<f32>(0.0), vec3<f32>(0.0));
    var edge_neighbour = false;
    var held = false;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let w = dw_at(sqrt(r2) * ip.inv_radius);
                let kj = kind_of(j);
                if part[j] != 0u {
                    s = s - w * d;
                }
                every = sym_add(every, -ip.volume * w, d);
                if kj == FLUID {
                    if surf[j] != 0u {
                        edge_neighbour = true;
                    } else {
                        held = true;
                    }
                    fluid = sym_add(fluid, -ip.volume * w, d);
                } else if kj != BODY {
                    wall = sym_add(wall, -ip.volume * w, d);
                }
            }
        }
    }
    if !on_surface && !edge_neighbour && ip.corrected != 0u {
        let m = sym_full(every);
        if smallest_eigenvalue_up_to(m, LAMBDA_INNER) > LAMBDA_INNER && regular(m) {
            let inv = inverse3(m);
            // rows of the symmetric inverse
            lmat[3u * i] = vec4<f32>(inv[0], 1.0);
            lmat[3u * i + 1u] = vec4<f32>(inv[1], 0.0);
            lmat[3u * i + 2u] = vec4<f32>(inv[2], 0.0);
        }
    }
    if !on_surface {
        return;
    }
    if !held {
        let wm = sym_full(wall);
        if smallest_eigenvalue(wm) >= MIN_WALL_SHARE && regular(wm) {
            let id = mat3x3<f32>(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
            // M = (I − N_f) N_w⁻¹; the columns of WGSL's matrices: M's row a is column a of Mᵀ
            let mt = transpose((id - sym_full(fluid)) * inverse3(wm));
            smat[3u * i] = vec4<f32>(mt[0], 1.0);
            smat[3u * i + 1u] = vec4<f32>(mt[1], 0.0);
            smat[3u * i + 2u] = vec4<f32>(mt[2], 0.0);
        }
    }
    let norm = length(s);
    if !(norm > 0.0 && norm <= 3.0e38) {
        return;
    }
    let mn = s / norm;
    let cap = ip.rho * dot(ip.gravity, mn) * 0.5 * ip.spacing;
    if cap <= 0.0 {
        return;
    }
    let pi = dens[i].y;
    var num = 0.0;
    var den = 0.0;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i || kind_of(j) != FLUID {
                    continue;
                }
                let dm = dot(d, mn);
                let w = w_at(sqrt(r2) * ip.inv_radius);
                num = num + w * (dens[j].y - pi) * dm;
                den = den + w * dm * dm;
            }
        }
    }
    var slope = 0.0;
    if den > 0.0 {
        slope = num / den;
    }
    dirich[i] = clamp(0.5 * ip.spacing * slope, 0.0, cap);
}

// S2-9 on the velocity (operators::laplacian): Σ F_ij (v_j − v_i) over fluid neighbours, and
// with no slip the solids at their own velocity (their part, times m ν, the walls' force).
@compute @workgroup_size(64)
fn isph_laplacian(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        acc[i] = vec4<f32>(0.0);
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    var l = vec3<f32>(0.0);
    var wall = vec3<f32>(0.0);
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let solid = kind_of(j) != FLUID;
                if solid && ip.no_slip == 0u {
                    continue;
                }
                let f = -2.0 * ip.volume * dw_at(sqrt(r2) * ip.inv_radius);
                let du = f * (vel[j].xyz - ui);
                l = l + du;
                if solid {
                    wall = wall + du;
                }
            }
        }
    }
    acc[i] = vec4<f32>(l, 0.0);
    wallf[i] = wallf[i] + vec4<f32>(prm.mass * ip.nu * wall, 0.0);
}

// S2-3: v* = v + (ν ∇²v + g) Δt_p for fluid, keeping v^n over a short step.
@compute @workgroup_size(64)
fn isph_predict(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let u = vel[i].xyz;
    if ip.short != 0u {
        vstart[i] = vec4<f32>(u, 0.0);
    }
    var lap = vec3<f32>(0.0);
    if ip.viscous != 0u {
        lap = acc[i].xyz;
    }
    vel[i] = vec4<f32>(u + (ip.nu * lap + ip.gravity) * ip.dt_p, 0.0);
}

// S2-9's row of an unknown (IsphStep::assemble): its diagonal Σ_fluid F_ij, and its right-hand
// side b_S2 with the surface neighbours' Dirichlet values, the walls' Neumann differences and
// the source −(ρ/Δt_p ∇·v* + α_d ρ (1 − ρ̂/ρ0)/Δt_p²), ∇·v* S2-8's plain difference divergence.
@compute @workgroup_size(64)
fn isph_assemble(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if !is_unknown(i) {
        dg[i] = 1.0;
        bs[i] = 0.0;
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    var diag = 0.0;
    var rhs = 0.0;
    var div = 0.0;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let w = dw_at(sqrt(r2) * ip.inv_radius);
                let f = -2.0 * ip.volume * w;
                if kind_of(j) == FLUID {
                    // (v_j − v_i)·∇_i W_ij V, ∇_i W_ij = (W'/r)(x_i − x_j)
                    div = div - ip.volume * w * dot(vel[j].xyz - ui, d);
                    diag = diag + f;
                    if surf[j] != 0u {
                        rhs = rhs + f * dirich[j];
                    }
                } else {
                    rhs = rhs + f * wall_difference(i, j, d);
                }
            }
        }
    }
    let dt = ip.dt_p;
    dg[i] = diag;
    bs[i] = rhs - (ip.rho / dt * div + ip.alpha_d * ip.rho * (1.0 - ratio[i]) / (dt * dt));
}

// The pressure a particle's known part carries: a surface particle's Dirichlet value, 0 for an
// unknown.
fn known_pressure(i: u32) -> f32 {
    if surf[i] != 0u {
        return dirich[i];
    }
    return 0.0;
}

// c_i, the symmetric gradient of the known pressures alone (exact_projection::known_gradient),
// and yv = (ρ/Δt_p) v* − c for fluid i (0 elsewhere).
@compute @workgroup_size(64)
fn isph_known(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        yv[i] = vec4<f32>(0.0);
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    let pi = known_pressure(i);
    var g = vec3<f32>(0.0);
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let kj = kind_of(j);
                if kj == BODY {
                    continue;
                }
                // V W'/r (x_i − x_j)
                let e = -ip.volume * dw_at(sqrt(r2) * ip.inv_radius) * d;
                if kj == FLUID {
                    g = g + pair_fluid(i, j, (pi + known_pressure(j)) * e);
                } else {
                    g = g + completed(i, corrected(i, (2.0 * pi + wall_difference(i, j, d)) * e));
                }
            }
        }
    }
    yv[i] = vec4<f32>(ip.rho / ip.dt_p * vel[i].xyz - g, 0.0);
}

// c_ij of the exact projection's operator (PairGradients): V ∇W_ij corrected, times 1 for a
// fluid neighbour and 2 for a solid, with e = V (W'/r)(x_i − x_j).
fn pair_vector(i: u32, j: u32, e: vec3<f32>, fluid: bool) -> vec3<f32> {
    if fluid {
        return pair_fluid(i, j, e);
    }
    return corrected(i, 2.0 * e);
}

// The exact projection's right-hand side blended with S2-9's (exact_projection::
// blend_right_hand_side): b = Σ_j (y_k − y_j)·c_kj − (ρ/Δt_p) Σ_w u_w·c_kw − (ρ/Δt_p) α_d
// (1 − ρ̂/ρ0)/Δt_p, then (1 − ε) b + ε b_S2; and the solve's warm start: the last pressure on
// the unknowns, 0 elsewhere (also the direction the first operator product reads).
@compute @workgroup_size(64)
fn isph_rhs(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if i == 0u {
        cgs[CG_DONE] = 0.0;
    }
    if !is_unknown(i) {
        xs[i] = 0.0;
        ds[i] = 0.0;
        rs[i] = 0.0;
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let yi = yv[i].xyz;
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    let s = ip.rho / ip.dt_p;
    var b = 0.0;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let kj = kind_of(j);
                if kj == BODY {
                    continue;
                }
                let fluid = kj == FLUID;
                let cij = pair_vector(i, j, -ip.volume * dw_at(sqrt(r2) * ip.inv_radius) * d, fluid);
                var dy_ = yi - yv[j].xyz;
                if !fluid {
                    dy_ = dy_ - s * vel[j].xyz;
                }
                b = b + dot(dy_, cij);
            }
        }
    }
    let relaxation = s * ip.alpha_d * (1.0 - ratio[i]) / ip.dt_p;
    bs[i] = (1.0 - ip.eps) * (b - relaxation) + ip.eps * bs[i];
    let warm = dens[i].y;
    xs[i] = warm;
    ds[i] = warm;
}

// (G_x d)_i = Σ_j (d_i + d_j) c_ij for fluid i (exact_projection::gradient_of_unknowns), d = 0
// off the unknowns; nothing once the solve has ended.
@compute @workgroup_size(64)
fn cg_gradient(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if cgs[CG_DONE] != 0.0 {
        return;
    }
    if kind_of(i) != FLUID {
        yv[i] = vec4<f32>(0.0);
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let di = ds[i];
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    var g = vec3<f32>(0.0);
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let kj = kind_of(j);
                if kj == BODY {
                    continue;
                }
                let fluid = kj == FLUID;
                let cij = pair_vector(i, j, -ip.volume * dw_at(sqrt(r2) * ip.inv_radius) * d, fluid);
                g = g + (di + ds[j]) * cij;
            }
        }
    }
    yv[i] = vec4<f32>(g, 0.0);
}

// ((1 − ε) G_xᵀ G_x + ε L) d at unknown i (exact_projection::apply_operator), with yv = G_x d.
fn operator_at(i: u32) -> f32 {
    let xi = pos[i].xyz;
    let li = low(i);
    let yi = yv[i].xyz;
    let di = ds[i];
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    var adjoint = 0.0;
    var laplacian = 0.0;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let kj = kind_of(j);
                if kj == BODY {
                    continue;
                }
                let fluid = kj == FLUID;
                let w = dw_at(sqrt(r2) * ip.inv_radius);
                let cij = pair_vector(i, j, -ip.volume * w * d, fluid);
                adjoint = adjoint + dot(yi - yv[j].xyz, cij);
                if fluid {
                    laplacian = laplacian - 2.0 * ip.volume * w * (di - ds[j]);
                }
            }
        }
    }
    return (1.0 - ip.eps) * adjoint + ip.eps * laplacian;
}

var<workgroup> red: array<vec4<f32>, 256>;

// Sums each thread's `a` over the workgroup into cgp (4 per workgroup).
fn reduce_into_partials(v: Invocation, a: vec4<f32>) {
    let l = v.local;
    red[l] = a;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s / 2u) {
        if l < s {
            red[l] = red[l] + red[l + s];
        }
        workgroupBarrier();
    }
    let group = group_index(v);
    if l == 0u && group < ip.groups {
        cgp[4u * group] = red[0].x;
        cgp[4u * group + 1u] = red[0].y;
        cgp[4u * group + 2u] = red[0].z;
        cgp[4u * group + 3u] = red[0].w;
    }
}

// Sums the partials of every workgroup (one workgroup of 256 threads).
fn sum_partials(v: Invocation) -> vec4<f32> {
    let l = v.local;
    var a = vec4<f32>(0.0);
    for (var g = l; g < ip.groups; g = g + 256u) {
        a = a + vec4<f32>(cgp[4u * g], cgp[4u * g + 1u], cgp[4u * g + 2u], cgp[4u * g + 3u]);
    }
    red[l] = a;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s / 2u) {
        if l < s {
            red[l] = red[l] + red[l + s];
        }
        workgroupBarrier();
    }
    return red[0];
}

// The start of the solve (ppe::pcg): A x from the warm start (in d) at the unknowns.
@compute @workgroup_size(64)
fn cg_start(v: Invocation) {
    let i = item_index(v, WG);
    if i < prm.n && is_unknown(i) {
        qs[i] = operator_at(i);
    }
}

// r = b − A x, z = r / diag, d = z; the partials of r·r, r·z and b·b.
@compute @workgroup_size(256)
fn cg_start_residual(v: Invocation) {
    let i = item_index(v, SCAN_WG);
    var a = vec4<f32>(0.0);
    if i < prm.n && is_unknown(i) {
        let res = bs[i] - qs[i];
        let z = res / dg[i];
        rs[i] = res;
        ds[i] = z;
        a = vec4<f32>(res * res, res * z, bs[i] * bs[i], 1.0);
    }
    reduce_into_partials(v, a);
}

@compute @workgroup_size(256)
fn cg_start_scalars(v: Invocation) {
    let a = sum_partials(v);
    if v.local == 0u {
        cgs[CG_R2] = a.x;
        cgs[CG_RZ] = a.y;
        cgs[CG_B2] = a.z;
        cgs[CG_TARGET] = ip.tol2 * a.z;
        cgs[CG_UNKNOWNS] = a.w;
        cgs[CG_ITER] = 0.0;
        cgs[CG_ALPHA] = 0.0;
        cgs[CG_BETA] = 0.0;
        var done = 0.0;
        if a.z == 0.0 {
            done = 3.0;
        } else if a.x <= ip.tol2 * a.z {
            done = 1.0;
        }
        cgs[CG_DONE] = done;
    }
}

// q = A d at the unknowns, and the partials of d·q.
@compute @workgroup_size(256)
fn cg_apply(v: Invocation) {
    let i = item_index(v, SCAN_WG);
    var a = vec4<f32>(0.0);
    if i < prm.n && is_unknown(i) && cgs[CG_DONE] == 0.0 {
        let q = operator_at(i);
        qs[i] = q;
        a = vec4<f32>(ds[i] * q, 0.0, 0.0, 0.0);
    }
    reduce_into_partials(v, a);
}

@compute @workgroup_size(256)
fn cg_step_length(v: Invocation) {
    let a = sum_partials(v);
    if v.local == 0u {
        var alpha = 0.0;
        if cgs[CG_DONE] == 0.0 {
            alpha = cgs[CG_RZ] / a.x;
        }
        cgs[CG_ALPHA] = alpha;
    }
}

// x += α d, r −= α q, z = r / diag; the partials of r·r and r·z.
@compute @workgroup_size(256)
fn cg_update(v: Invocation) {
    let i = item_index(v, SCAN_WG);
    var a = vec4<f32>(0.0);
    if i < prm.n && is_unknown(i) && cgs[CG_DONE] == 0.0 {
        let alpha = cgs[CG_ALPHA];
        xs[i] = xs[i] + alpha * ds[i];
        let res = rs[i] - alpha * qs[i];
        rs[i] = res;
        a = vec4<f32>(res * res, res * res / dg[i], 0.0, 0.0);
    }
    reduce_into_partials(v, a);
}

// The iteration's end: |r|², β = r·z / r·z_old, and whether the solve has converged (|r| ≤ tol
// |b|) or failed (its iterations spent, or a residual that is not finite).
@compute @workgroup_size(256)
fn cg_iteration_end(v: Invocation) {
    let a = sum_partials(v);
    if v.local == 0u && cgs[CG_DONE] == 0.0 {
        let iter = cgs[CG_ITER] + 1.0;
        cgs[CG_ITER] = iter;
        cgs[CG_R2] = a.x;
        cgs[CG_BETA] = a.y / cgs[CG_RZ];
        cgs[CG_RZ] = a.y;
        if a.x <= cgs[CG_TARGET] {
            cgs[CG_DONE] = 1.0;
        } else if iter >= f32(ip.max_iterations) || !(abs(a.x) <= 3.0e38) {
            cgs[CG_DONE] = 2.0;
        }
    }
}

// d = z + β d.
@compute @workgroup_size(64)
fn cg_direction(v: Invocation) {
    let i = item_index(v, WG);
    if i < prm.n && is_unknown(i) && cgs[CG_DONE] == 0.0 {
        ds[i] = rs[i] / dg[i] + cgs[CG_BETA] * ds[i];
    }
}

// The fluid's pressure (IsphStep::solve_ppe): max(0, x) on the unknowns (no tension), the
// Dirichlet value on the surface.
@compute @workgroup_size(64)
fn isph_pressure(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    var p = dirich[i];
    if surf[i] == 0u {
        p = max(xs[i], 0.0);
        if cgs[CG_DONE] == 3.0 {
            p = 0.0;
        }
    }
    dens[i] = vec2<f32>(dens[i].x, p);
}

// Adami's extrapolation onto the solids (walls::extrapolated): Σ_f W (p_f + Δp_fw) / Σ_f W,
// 0 without fluid neighbours.
@compute @workgroup_size(64)
fn isph_wall_pressure(v: Invocation) {
    let w = item_index(v, WG);
    if w >= prm.n || kind_of(w) == FLUID {
        return;
    }
    let c = cell_sorted[w];
    if !fluid_near(c, ip.reach) {
        dens[w] = vec2<f32>(dens[w].x, 0.0);
        return;
    }
    let xw = pos[w].xyz;
    let lw = low(w);
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    var num = 0.0;
    var den = 0.0;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var f = range.x; f < range.y; f = f + 1u) {
                if kind_of(f) != FLUID {
                    continue;
                }
                // x_w − x_f
                let d = -apart_near(pos[f].xyz, f, xw, lw);
                let r2 = dot(d, d);
                if r2 >= re2 {
                    continue;
                }
                let wf = w_at(sqrt(r2) * ip.inv_radius);
                num = num + wf * (dens[f].y + wall_difference(f, w, d));
                den = den + wf;
            }
        }
    }
    var p = 0.0;
    if den > 0.0 {
        p = num / den;
    }
    dens[w] = vec2<f32>(dens[w].x, p);
}

// The symmetric pressure gradient of the momentum equation (operators::symmetric_gradient):
// Σ_fluid V (p_i + p_j) ∇W_ij corrected, plus the walls' V (2 p_i + Δp_iw) ∇W_iw corrected and
// completed; the walls' terms, times −V, are their force on the fluid.
@compute @workgroup_size(64)
fn isph_gradient(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        acc[i] = vec4<f32>(0.0);
        return;
    }
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let re2 = ip.radius * ip.radius;
    let r = ip.reach;
    let pi = dens[i].y;
    var g = vec3<f32>(0.0);
    var wall = vec3<f32>(0.0);
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 >= re2 || j == i {
                    continue;
                }
                let kj = kind_of(j);
                let e = -ip.volume * dw_at(sqrt(r2) * ip.inv_radius) * d;
                if kj == FLUID {
                    g = g + pair_fluid(i, j, (pi + dens[j].y) * e);
                } else {
                    let t = completed(i, corrected(i, (2.0 * pi + wall_difference(i, j, d)) * e));
                    g = g + t;
                    wall = wall + t;
                }
            }
        }
    }
    acc[i] = vec4<f32>(g, 0.0);
    wallf[i] = wallf[i] - vec4<f32>(ip.volume * wall, 0.0);
}

// S2-4 for fluid: over a short step v* is first cut back to its share of the step
// (IsphStep::short_step), then v = v* − (Δt/ρ) ∇p and x += v Δt.
@compute @workgroup_size(64)
fn isph_correct(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    var u = vel[i].xyz;
    if ip.short != 0u {
        let u0 = vstart[i].xyz;
        u = u0 + ip.share * (u - u0);
    }
    u = u - ip.dt / ip.rho * acc[i].xyz;
    vel[i] = vec4<f32>(u, 0.0);
    shift(i, u * ip.dt);
}
