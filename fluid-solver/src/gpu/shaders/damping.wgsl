// Damping zones (src/boundaries/damping.rs): after each step the velocity of a fluid particle in
// a zone is relaxed towards rest, u ← u Π_zones exp(−rate s² Δt), s = the particle's distance from
// the zone's near face over the zone's length along its axis (a box with its faces; 1 outside).

// The factor exp(−rate s² Δt) of zone z at p (DampingZone::factor).
fn damping_factor(z: DampingZone, p: vec3<f32>) -> f32 {
    if any(p < z.lo) || any(p > z.hi) {
        return 1.0;
    }
    let len = z.hi[z.axis] - z.lo[z.axis];
    var s = (p[z.axis] - z.lo[z.axis]) / len;
    if z.sign < 0.0 {
        s = (z.hi[z.axis] - p[z.axis]) / len;
    }
    return exp(-z.rate * s * s * prm.dt);
}

// damping::relax on fluid particle i, at its position after the step.
@compute @workgroup_size(64)
fn relax_damping(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let p = pos[i].xyz;
    var f = 1.0;
    for (var z = 0u; z < prm.n_damping; z = z + 1u) {
        f = f * damping_factor(damping[z], p);
    }
    vel[i] = vec4<f32>(vel[i].xyz * f, 0.0);
}
