// The E-MPS stages (src/emps/step.rs) as gathers: particle i sums over the particles of the
// cells around its own and writes only its own slots, so no atomics on floats are needed.

// Clears the step's per-particle sums (force from non-fluid neighbours, candidates).
@compute @workgroup_size(64)
fn clear_sums(v: Invocation) {
    let i = item_index(v, WG);
    if i < prm.n {
        wallf[i] = vec4<f32>(0.0);
        cand[i] = 0u;
    }
}

// S1-4: ⟨∇²u⟩_i = 2d/(λ0 n0) Σ_j (u_j − u_i) w(r_ij) for fluid i (walls have u = 0: no slip);
// the part from non-fluid j, times m ν, is the walls' viscous force.
@compute @workgroup_size(64)
fn laplacian(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        acc[i] = vec4<f32>(0.0);
        return;
    }
    let re = prm.re;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    var l = vec3<f32>(0.0);
    var wall = vec3<f32>(0.0);
    var seen = 0u;
    let r = prm.reach;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            seen = seen + range.y - range.x;
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let d = apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 < re2 && r2 > 0.0 {
                    let rr = sqrt(r2);
                    let w = (re - rr) * (re - rr) / (rr * re);
                    let du = (vel[j].xyz - ui) * w;
                    l = l + du;
                    if u32(pj.w) != FLUID {
                        wall = wall + du;
                    }
                }
            }
        }
    }
    acc[i] = vec4<f32>(prm.lap_factor * l, 0.0);
    wallf[i] = wallf[i] + vec4<f32>(prm.mass * prm.nu * prm.lap_factor * wall, 0.0);
    cand[i] = cand[i] + seen;
}

// S1-10, S1-11: u* = u + (ν⟨∇²u⟩ + g)Δt, r* = r + u*Δt for fluid; bodies move with their own
// velocity; walls stay.
@compute @workgroup_size(64)
fn predict(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    let k = kind_of(i);
    var u = vel[i].xyz;
    if k == FLUID {
        var lap = vec3<f32>(0.0);
        if prm.viscous != 0u {
            lap = acc[i].xyz;
        }
        u = u + (prm.nu * lap + prm.gravity) * prm.dt;
        vel[i] = vec4<f32>(u, 0.0);
    }
    if k == FLUID || k == BODY {
        shift(i, u * prm.dt);
    }
}

// S1-15 and S1-14: n_i = Σ_{j≠i} w(r_ij) with r_e = 3.1 Δs for fluid, and for wall, body and
// gate particles with fluid within r_e,grad (others n = 0); ρ* = ρ0 n/n0,
// P = c²(ρ* − ρ0) where ρ* > ρ0, else 0.
@compute @workgroup_size(64)
fn density(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    let k = kind_of(i);
    let c = cell_sorted[i];
    if k == DUMMY || (k != FLUID && !fluid_near(c, prm.reach_grad)) {
        dens[i] = vec2<f32>(0.0, 0.0);
        return;
    }
    let re = prm.re;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    var sum = 0.0;
    var seen = 0u;
    let r = prm.reach;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            seen = seen + range.y - range.x;
            for (var j = range.x; j < range.y; j = j + 1u) {
                let d = apart_near(pos[j].xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 < re2 && r2 > 0.0 {
                    let rr = sqrt(r2);
                    sum = sum + (re - rr) * (re - rr) / (rr * re);
                }
            }
        }
    }
    let rho_star = prm.rho * sum * prm.inv_n0;
    var p = 0.0;
    if rho_star > prm.rho {
        p = prm.c2 * (rho_star - prm.rho);
    }
    dens[i] = vec2<f32>(sum, p);
    cand[i] = cand[i] + seen;
}

// S1-3: ⟨∇P⟩_i = d/n0_grad Σ_j (P_j + P_i) r_ij/|r_ij|² w_grad(r_ij) for fluid i over
// neighbours that carry pressure (not dummies); the part from non-fluid j, times −V, is the
// walls' pressure force.
@compute @workgroup_size(64)
fn gradient(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        acc[i] = vec4<f32>(0.0);
        return;
    }
    let re = prm.re_grad;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    let fi = dens[i].y;
    let c = cell_sorted[i];
    var gr = vec3<f32>(0.0);
    var wall = vec3<f32>(0.0);
    var seen = 0u;
    let r = prm.reach_grad;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            seen = seen + range.y - range.x;
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let kj = u32(pj.w);
                let d = apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 < re2 && r2 > 0.0 && kj != DUMMY {
                    let rr = sqrt(r2);
                    let cc = (dens[j].y + fi) * (re / rr - rr / re) / r2;
                    gr = gr + cc * d;
                    if kj != FLUID {
                        wall = wall + cc * d;
                    }
                }
            }
        }
    }
    acc[i] = vec4<f32>(prm.grad_factor * gr, 0.0);
    wallf[i] = wallf[i] - vec4<f32>(prm.volume * prm.grad_factor * wall, 0.0);
    cand[i] = cand[i] + seen;
}

// S1-12, S1-13: u = u* − Δt/ρ0 ⟨∇P⟩, r = r* + (u − u*)Δt for fluid (the gradient is 0 off the
// fluid; a body particle's acc holds its load, bodies.wgsl).
@compute @workgroup_size(64)
fn correct(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let du = -(prm.dt / prm.rho) * acc[i].xyz;
    vel[i] = vec4<f32>(vel[i].xyz + du, 0.0);
    shift(i, du * prm.dt);
}

// Collision of close approaching particles (src/neighbours/collision.rs): for fluid i and j closer than
// the collision distance with (u_j − u_i)·r_ij < 0, Δu_i = s (1+e) ((u_j − u_i)·r_ij) r_ij/|r_ij|²
// with s = 1/2 for fluid j and 1 for others; the part from non-fluid j, times m/Δt, is the
// walls' contact force.
@compute @workgroup_size(64)
fn collide(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) != FLUID {
        acc[i] = vec4<f32>(0.0);
        return;
    }
    let d2 = prm.coll_dist * prm.coll_dist;
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    var du = vec3<f32>(0.0);
    var wall = vec3<f32>(0.0);
    var seen = 0u;
    let r = prm.reach_coll;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            seen = seen + range.y - range.x;
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let d = apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                if r2 < d2 && r2 > 0.0 {
                    let closing = dot(vel[j].xyz - ui, d);
                    if closing < 0.0 {
                        var share = 1.0;
                        if u32(pj.w) == FLUID {
                            share = 0.5;
                        }
                        let cc = share * (1.0 + prm.restitution) * closing / r2;
                        du = du + cc * d;
                        if u32(pj.w) != FLUID {
                            wall = wall + cc * d;
                        }
                    }
                }
            }
        }
    }
    acc[i] = vec4<f32>(du, 0.0);
    wallf[i] = wallf[i] + vec4<f32>(prm.mass / prm.dt * wall, 0.0);
    cand[i] = cand[i] + seen;
}

// Adds the collision velocity change Δu to a fluid particle and moves it by Δu Δt, as S1-13 does.
@compute @workgroup_size(64)
fn apply_collisions(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let du = acc[i].xyz;
    vel[i] = vec4<f32>(vel[i].xyz + du, 0.0);
    shift(i, du * prm.dt);
}
