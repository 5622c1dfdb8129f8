// The instability detector's scan (src/stability.rs) and the step's totals, reduced on the
// device to one Partial per workgroup of 256 particles: the force of the walls on the fluid,
// the fluid's mechanical energy per unit mass Σ ½|u|² − g·r, the candidates, the smallest
// (id · 8 + finding code) of a particle with a finding, and the particles that left through the
// open top. The host sums the partials in f64 and, on a finding, explains it with the CPU
// detector on a copy of the particles.

// Finding codes (the host's StabilityMonitor names them).
const F_NOT_FINITE: u32 = 1u;
const F_INSIDE_WALL: u32 = 2u;
const F_LEFT_DOMAIN: u32 = 3u;
const F_TOO_FAST: u32 = 4u;
const F_INSIDE_BODY: u32 = 5u;

var<workgroup> r_wall: array<vec3<f32>, 256>;
var<workgroup> r_energy: array<f32, 256>;
var<workgroup> r_cand: array<u32, 256>;
var<workgroup> r_find: array<u32, 256>;
var<workgroup> r_esc: array<u32, 256>;
var<workgroup> r_fluid: array<u32, 256>;
var<workgroup> r_fast: array<f32, 256>;

fn is_finite(v: f32) -> bool {
    // NaN fails both comparisons; ±inf fails the bound.
    return abs(v) <= 3.0e38;
}

fn outside(p: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> bool {
    return any(p < lo) || any(p > hi);
}

// The finding code of particle i (0 when none), as StabilityMonitor::check_particle; sets
// `left` when the particle left through the open top (removed at the next step's start).
fn finding(i: u32, left: ptr<function, bool>) -> u32 {
    let p = pos[i].xyz;
    let u = vel[i].xyz;
    let pr = dens[i].y;
    if !(is_finite(p.x) && is_finite(p.y) && is_finite(p.z) && is_finite(u.x) && is_finite(u.y)
        && is_finite(u.z) && is_finite(pr)) {
        return F_NOT_FINITE;
    }
    let k = kind_of(i);
    if k != FLUID && k != BODY {
        return 0u;
    }
    let h = 0.5 * prm.spacing;
    // the walls' height (StabilityMonitor::inside_wall): an open tank's wall top gets half a
    // spacing like every face, and beyond its outer faces the particle passed over the walls
    let open = prm.open_top != 0u;
    let within_outer = p.x >= prm.domain_lo.x && p.x <= prm.domain_hi.x && p.y >= prm.domain_lo.y
        && p.y <= prm.domain_hi.y;
    let below_top = select(p.z <= prm.tank_hi.z, p.z < prm.tank_hi.z - h && within_outer, open);
    let out_tank = p.x < prm.tank_lo.x - h || p.x > prm.tank_hi.x + h || p.y < prm.tank_lo.y - h
        || p.y > prm.tank_hi.y + h || p.z < prm.tank_lo.z - h;
    if out_tank && below_top {
        return F_INSIDE_WALL;
    }
    if deep_in_solid(p) {
        return F_INSIDE_WALL;
    }
    for (var b = 0u; b < prm.n_boxes; b = b + 1u) {
        if all(p >= boxes[2u * b].xyz) && all(p <= boxes[2u * b + 1u].xyz) {
            return F_INSIDE_WALL;
        }
    }
    if k == BODY {
        return 0u;
    }
    let out_domain = outside(p, prm.domain_lo, prm.domain_hi);
    if open && out_domain && p.z > prm.wall_top - h {
        *left = true;
        return 0u;
    }
    if out_domain {
        return F_LEFT_DOMAIN;
    }
    if inside_body(p) {
        return F_INSIDE_BODY;
    }
    if length(u) * prm.dt > 0.5 * prm.spacing {
        return F_TOO_FAST;
    }
    return 0u;
}

// Workgroups of 256 particles of the reductions (one Partial, and SUMS BodyLoads per body, each;
// a 2-D dispatch's surplus workgroups write none).
fn reduction_groups() -> u32 {
    return (prm.n + SCAN_WG - 1u) / SCAN_WG;
}

@compute @workgroup_size(256)
fn reduce_step(v: Invocation) {
    let i = item_index(v, SCAN_WG);
    let group = group_index(v);
    let l = v.local;
    var wall = vec3<f32>(0.0);
    var energy = 0.0;
    var seen = 0u;
    var found = NONE;
    var esc = 0u;
    var fluid = 0u;
    var fast = 0.0;
    if i < prm.n {
        var left = false;
        let f = finding(i, &left);
        if f != 0u {
            found = pid[i] * 8u + f;
        }
        if left && kind_of(i) == FLUID {
            esc = 1u;
        }
        if kind_of(i) == FLUID {
            let u = vel[i].xyz;
            energy = 0.5 * dot(u, u) - dot(prm.gravity, pos[i].xyz);
            fluid = 1u;
            fast = length(u);
            // a body particle's wallf holds the walls' contact on it (bodies.wgsl)
            wall = wallf[i].xyz;
        }
        seen = cand[i];
    }
    r_wall[l] = wall;
    r_energy[l] = energy;
    r_cand[l] = seen;
    r_find[l] = found;
    r_esc[l] = esc;
    r_fluid[l] = fluid;
    r_fast[l] = fast;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s / 2u) {
        if l < s {
            r_wall[l] = r_wall[l] + r_wall[l + s];
            r_energy[l] = r_energy[l] + r_energy[l + s];
            r_cand[l] = r_cand[l] + r_cand[l + s];
            r_find[l] = min(r_find[l], r_find[l + s]);
            r_esc[l] = r_esc[l] + r_esc[l + s];
            r_fluid[l] = r_fluid[l] + r_fluid[l + s];
            r_fast[l] = max(r_fast[l], r_fast[l + s]);
        }
        workgroupBarrier();
    }
    if l == 0u && group < reduction_groups() {
        partials[group] = Partial(r_wall[0], r_energy[0], r_cand[0], r_find[0], r_esc[0], r_fluid[0],
            r_fast[0], 0u, 0u, 0u);
    }
}
