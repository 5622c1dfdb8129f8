// Resolved rigid bodies on the device (src/bodies/: rigid_bodies.rs, body_wall_contact.rs): body particles
// placed from the pose the host hands over, the fluid's pair forces on each body particle as
// gathers (the body particle sums over its fluid neighbours, no float atomics), and their force
// and moment about the body's centre reduced per body on the device. Each body kernel writes the
// body particle's force into acc (whose other users read it only for fluid) and the walls' share
// of it into wallf (which the step's totals read only for fluid), and reduce_bodies runs right
// after it, while the positions are those the forces were computed at.

// Index of the member with particle id `id` (binary search over the sorted ids), or NONE.
fn member_of(id: u32) -> u32 {
    var lo = 0u;
    var hi = prm.n_members;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        let m = members[mid].id;
        if m == id {
            return mid;
        }
        if m < id {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return NONE;
}

// v rotated by the unit quaternion q = (w, x, y, z) stored as (q.x, q.y, q.z, q.w) = (w, x, y, z).
fn rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let u = q.yzw;
    let t = 2.0 * cross(u, v);
    return v + q.x * t + cross(u, t);
}

// RigidBodies::set_kinematics: u = V + ω × R(q) a and r = c + R(q) a − u·lead for each body
// particle of offset a from its body's initial centre (S1-21); lead rides in centre.w.
@compute @workgroup_size(64)
fn place_bodies(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != BODY {
        return;
    }
    let m = member_of(pid[i]);
    if m == NONE {
        return;
    }
    let k = body_kin[members[m].body];
    let arm = rotate(k.quat, members[m].offset);
    let u = k.vel.xyz + cross(k.omega.xyz, arm);
    if WIDE {
        place(i, k.centre.xyz, k.low.xyz + arm - u * k.centre.w);
    } else {
        pos[i] = vec4<f32>(k.centre.xyz + arm - u * k.centre.w, pos[i].w);
    }
    vel[i] = vec4<f32>(u, 0.0);
}

// r_i − c_b: body particle i's arm about its body's centre (with wide positions, of both parts).
fn arm_of(i: u32, b: u32) -> vec3<f32> {
    let k = body_kin[b];
    if WIDE {
        return (pos[i].xyz - k.centre.xyz) + (pos_lo[i].xyz - k.low.xyz);
    }
    return pos[i].xyz - k.centre.xyz;
}

@compute @workgroup_size(64)
fn clear_body_loads(v: Invocation) {
    let k = item_index(v, WG);
    if k < prm.n_bodies * SUMS {
        body_loads[k] = BodyLoad(vec4<f32>(0.0), vec4<f32>(0.0));
    }
}

// Slot of sum `sum` of `body` in the partials of reduction group `group`.
fn load_slot(group: u32, body: u32, sum: u32) -> u32 {
    return (group * prm.n_bodies + body) * SUMS + sum;
}

// S1-4's viscous pair force on body particle i from its fluid neighbours j (pair_laws::viscous):
// −m ν 2d/(λ0 n0) Σ_j (u_i − u_j) w(r_ij).
@compute @workgroup_size(64)
fn body_viscous(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != BODY {
        return;
    }
    let re = prm.re;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    var f = vec3<f32>(0.0);
    let r = prm.reach;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let d = -apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if u32(pj.w) == FLUID && r2 < re2 && r2 > 0.0 {
                    let rr = sqrt(r2);
                    f = f + (ui - vel[j].xyz) * ((re - rr) * (re - rr) / (rr * re));
                }
            }
        }
    }
    acc[i] = vec4<f32>(-prm.mass * prm.nu * prm.lap_factor * f, 0.0);
    wallf[i] = vec4<f32>(0.0);
}

// S1-3's pressure pair force on body particle i from its fluid neighbours j (pair_laws::pressure):
// Δs³ d/n0_grad Σ_j (P_i + P_j) r_ji/|r_ji|² w_grad(r_ji), r_ji = r_i − r_j.
@compute @workgroup_size(64)
fn body_pressure(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != BODY {
        return;
    }
    let re = prm.re_grad;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    let pi = dens[i].y;
    let c = cell_sorted[i];
    var f = vec3<f32>(0.0);
    let r = prm.reach_grad;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let d = -apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if u32(pj.w) == FLUID && r2 < re2 && r2 > 0.0 {
                    let rr = sqrt(r2);
                    f = f + ((dens[j].y + pi) * (re / rr - rr / re) / r2) * d;
                }
            }
        }
    }
    acc[i] = vec4<f32>(prm.volume * prm.grad_factor * f, 0.0);
    wallf[i] = vec4<f32>(0.0);
}

// The collision stage on body particle i (collision::contact_law): −m/Δt (1+e) (u_ij·r_ji) r_ji/|r_ji|²
// from each fluid neighbour j closer than the collision distance that approaches it
// (u_ij = u_i − u_j), plus the walls' contact (body_wall_contact.rs): for each wall or dummy
// particle w closer than Δs, max(0, k (Δs − |r|) − c u_i·n) n with r = r_i − r_w, n = r/|r|.
@compute @workgroup_size(64)
fn body_collision(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != BODY {
        return;
    }
    let d2 = prm.coll_dist * prm.coll_dist;
    let s2 = prm.spacing * prm.spacing;
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    var fluid = vec3<f32>(0.0);
    var walls = vec3<f32>(0.0);
    let r = max(prm.reach_coll, prm.reach_contact);
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let kj = u32(pj.w);
                let d = -apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if !(r2 > 0.0) {
                    continue;
                }
                if kj == FLUID && r2 < d2 {
                    let closing = dot(ui - vel[j].xyz, d);
                    if closing < 0.0 {
                        fluid = fluid + (closing / r2) * d;
                    }
                } else if (kj == WALL || kj == DUMMY) && r2 < s2 {
                    let rr = sqrt(r2);
                    let n = d / rr;
                    let magnitude = prm.contact_k * (prm.spacing - rr) - prm.contact_c * dot(ui, n);
                    if magnitude > 0.0 {
                        walls = walls + magnitude * n;
                    }
                }
            }
        }
    }
    let f = -(prm.mass / prm.dt) * (1.0 + prm.restitution) * fluid + walls;
    acc[i] = vec4<f32>(f, 0.0);
    wallf[i] = vec4<f32>(walls, 0.0);
}

var<workgroup> r_bf: array<vec3<f32>, 256>;
var<workgroup> r_bm: array<vec3<f32>, 256>;

// Sums force f and moment m over the workgroup of 256 threads (thread l) and writes the total
// to body_partials[load_slot(group, body, sum)]; a 2-D dispatch's surplus workgroups (group ≥
// reduction_groups()) write none. Called in uniform control flow.
fn reduce_into(l: u32, group: u32, body: u32, sum: u32, f: vec3<f32>, m: vec3<f32>) {
    r_bf[l] = f;
    r_bm[l] = m;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s / 2u) {
        if l < s {
            r_bf[l] = r_bf[l] + r_bf[l + s];
            r_bm[l] = r_bm[l] + r_bm[l + s];
        }
        workgroupBarrier();
    }
    if l == 0u && group < reduction_groups() {
        body_partials[load_slot(group, body, sum)] = BodyLoad(vec4<f32>(r_bf[0], 0.0), vec4<f32>(r_bm[0], 0.0));
    }
    workgroupBarrier();
}

// The force in acc of each body particle and its moment (r − c) × f about its body's centre
// (LOADS), and the walls' share in wallf (WALLS), summed per workgroup of 256 particles and per
// body into body_partials.
@compute @workgroup_size(256)
fn reduce_bodies(v: Invocation) {
    let i = item_index(v, SCAN_WG);
    let group = group_index(v);
    let l = v.local;
    var b = NONE;
    var f = vec3<f32>(0.0);
    var fw = vec3<f32>(0.0);
    var arm = vec3<f32>(0.0);
    if i < prm.n && kind_of(i) == BODY {
        let k = member_of(pid[i]);
        if k != NONE {
            b = members[k].body;
            f = acc[i].xyz;
            fw = wallf[i].xyz;
            arm = arm_of(i, b);
        }
    }
    for (var body = 0u; body < prm.n_bodies; body = body + 1u) {
        let mine = b == body;
        let fb = select(vec3<f32>(0.0), f, mine);
        let fwb = select(vec3<f32>(0.0), fw, mine);
        reduce_into(l, group, body, LOADS, fb, cross(arm, fb));
        reduce_into(l, group, body, WALLS, fwb, cross(arm, fwb));
    }
}

// Sums the workgroups' partials per body and sum (one workgroup) and adds them to body_loads,
// which holds the step's sums over its exchanges (cleared at the step's start).
@compute @workgroup_size(256)
fn sum_bodies(v: Invocation) {
    let l = v.local;
    let groups = reduction_groups();
    for (var slot = 0u; slot < prm.n_bodies * SUMS; slot = slot + 1u) {
        var f = vec3<f32>(0.0);
        var m = vec3<f32>(0.0);
        for (var k = l; k < groups; k = k + SCAN_WG) {
            let p = body_partials[k * prm.n_bodies * SUMS + slot];
            f = f + p.force.xyz;
            m = m + p.moment.xyz;
        }
        r_bf[l] = f;
        r_bm[l] = m;
        workgroupBarrier();
        for (var s = 128u; s > 0u; s = s / 2u) {
            if l < s {
                r_bf[l] = r_bf[l] + r_bf[l + s];
                r_bm[l] = r_bm[l] + r_bm[l + s];
            }
            workgroupBarrier();
        }
        if l == 0u {
            let old = body_loads[slot];
            body_loads[slot] = BodyLoad(old.force + vec4<f32>(r_bf[0], 0.0), old.moment + vec4<f32>(r_bm[0], 0.0));
        }
        workgroupBarrier();
    }
}
