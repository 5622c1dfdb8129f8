// The bodies' reaction on the fluid summed from the fluid's side (src/bodies/rigid_bodies.rs, fluid_side_sum):
// fluid particle i gathers, over the particles j of body b within the exchange's radius, minus
// the pair force the fluid exerts on j — evaluated again from i's side, not read from the body
// kernels — with its moment about the body's centre taken at r_j, as the loads take it. The
// workgroups of 256 fluid slots (numbered row by row in x and y, group_index) reduce it per body
// (workgroup_id.z = b) into the REACTION slot of body_partials, beside the loads that
// reduce_bodies summed by body particle: two sums of the one law in different orders and over
// different neighbour searches, which the coupler's ledger compares. A fluid particle with no particle of body b within reach skips the gather
// (body_cells, filled by the cell sort).

// Cells each way within which the exchanges pair a fluid and a body particle: the largest reach
// of the laws in use (S1-4's r_e only with the viscous term).
fn reach_react() -> u32 {
    return max(select(prm.reach_grad, max(prm.reach, prm.reach_grad), prm.viscous != 0u), prm.reach_coll);
}

// Fluid slot i of an exchange's reaction on body b: whether i takes part (a particle of body b
// within reach_react of its cell; b % 32: a false positive only costs the gather).
fn reacts(i: u32, b: u32) -> bool {
    return i < prm.n && b < prm.n_bodies && kind_of(i) == FLUID
        && (atomicLoad(&body_cells[cell_sorted[i]]) & (1u << (b % 32u))) != 0u;
}

// The body of body particle j (NONE when it is no member, as reduce_bodies skips it).
fn body_of(j: u32) -> u32 {
    let m = member_of(pid[j]);
    if m == NONE {
        return NONE;
    }
    return members[m].body;
}

// The squared range of exchange `law` (0 viscous, 1 pressure, 2 collision).
fn range2(law: u32) -> f32 {
    if law == 0u {
        return prm.re * prm.re;
    } else if law == 1u {
        return prm.re_grad * prm.re_grad;
    }
    return prm.coll_dist * prm.coll_dist;
}

// The pair force of exchange `law` (0 viscous, 1 pressure, 2 collision) that fluid particle i
// exerts on body particle j, with d = r_j − r_i, r2 = |d|² (0 when out of the law's range).
fn pair_on_body(law: u32, i: u32, j: u32, d: vec3<f32>, r2: f32) -> vec3<f32> {
    if law == 0u {
        // S1-4 (pair_laws::viscous): −m ν 2d/(λ0 n0) (u_j − u_i) w(r_ij)
        let re = prm.re;
        if r2 < re * re {
            let rr = sqrt(r2);
            let w = (re - rr) * (re - rr) / (rr * re);
            return -prm.mass * prm.nu * prm.lap_factor * w * (vel[j].xyz - vel[i].xyz);
        }
    } else if law == 1u {
        // S1-3 (pair_laws::pressure): Δs³ d/n0_grad (P_i + P_j) r_ji/|r_ji|² w_grad(r_ji)
        let re = prm.re_grad;
        if r2 < re * re {
            let rr = sqrt(r2);
            let c = (dens[i].y + dens[j].y) * (re / rr - rr / re) / r2;
            return prm.volume * prm.grad_factor * c * d;
        }
    } else {
        // collision::contact_law: −m/Δt (1+e) (u_ji·r_ji) r_ji/|r_ji|² for approaching pairs
        if r2 < prm.coll_dist * prm.coll_dist {
            let closing = dot(vel[j].xyz - vel[i].xyz, d);
            if closing < 0.0 {
                return -(prm.mass / prm.dt) * (1.0 + prm.restitution) * (closing / r2) * d;
            }
        }
    }
    return vec3<f32>(0.0);
}

// One exchange's reaction: slot i's sum over body b's particles within `reach` cells, reduced
// into the REACTION partial of its workgroup and body.
fn react(law: u32, reach: u32, v: Invocation) {
    let i = item_index(v, SCAN_WG);
    let b = v.group.z;
    var f = vec3<f32>(0.0);
    var m = vec3<f32>(0.0);
    if reacts(i, b) {
        let xi = pos[i].xyz;
        let li = low(i);
        let c = cell_sorted[i];
        let reach2 = range2(law);
        for (var dz = 0u; dz <= 2u * reach; dz = dz + 1u) {
            for (var dy = 0u; dy <= 2u * reach; dy = dy + 1u) {
                let range = row_range(c, reach, dy, dz);
                for (var j = range.x; j < range.y; j = j + 1u) {
                    let pj = pos[j];
                    if u32(pj.w) != BODY {
                        continue;
                    }
                    let d = apart_near(pj.xyz, j, xi, li);
                    let r2 = dot(d, d);
                    if r2 > 0.0 && r2 < reach2 && body_of(j) == b {
                        let r = -pair_on_body(law, i, j, d, r2);
                        f = f + r;
                        m = m + cross(arm_of(j, b), r);
                    }
                }
            }
        }
    }
    if b < prm.n_bodies {
        reduce_into(v.local, group_index(v), b, REACTION, f, m);
    }
}

@compute @workgroup_size(256)
fn react_viscous(v: Invocation) {
    react(0u, prm.reach, v);
}

@compute @workgroup_size(256)
fn react_pressure(v: Invocation) {
    react(1u, prm.reach_grad, v);
}

@compute @workgroup_size(256)
fn react_collision(v: Invocation) {
    react(2u, prm.reach_coll, v);
}
