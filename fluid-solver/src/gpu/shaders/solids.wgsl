// The mesh solids' and terrains' sites (src/particles/solid_sites.rs) for the instability
// detector: one bit per site of the tank's lattice, site (i, j, k) at bit i + n_x (j + n_y k);
// a mesh body's sites take the same form (body_inside.wgsl).

// Whether site c of the lattice of n sites whose bits start at word `base` of solid_bits is set;
// a site beyond the lattice counts as `beyond`.
fn site_at(base: u32, n: vec3<u32>, c: vec3<i32>, beyond: bool) -> bool {
    if any(c < vec3<i32>(0)) || any(c >= vec3<i32>(n)) {
        return beyond;
    }
    let u = vec3<u32>(c);
    let b = u.x + n.x * (u.y + n.y * u.z);
    return (solid_bits[base + b / 32u] & (1u << (b % 32u))) != 0u;
}

// deep_inside_sites: the site f (a point's lattice coordinates, floored) and its six face
// neighbours are all set (a neighbour beyond the lattice counts as `beyond`).
fn deep_in_sites(base: u32, n: vec3<u32>, f: vec3<f32>, beyond: bool) -> bool {
    // off the lattice (checked in f32: far spray must not overflow an i32)
    if any(f < vec3<f32>(0.0)) || any(f >= vec3<f32>(n)) {
        return false;
    }
    let c = vec3<i32>(f);
    if !site_at(base, n, c, false) {
        return false;
    }
    for (var a = 0; a < 3; a = a + 1) {
        let e = vec3<i32>(select(0, 1, a == 0), select(0, 1, a == 1), select(0, 1, a == 2));
        if !site_at(base, n, c - e, beyond) || !site_at(base, n, c + e, beyond) {
            return false;
        }
    }
    return true;
}

// SolidSites::deep_inside: p lies more than about half a spacing inside a solid (beyond the
// lattice is the tank's wall: solid).
fn deep_in_solid(p: vec3<f32>) -> bool {
    if prm.solids == 0u {
        return false;
    }
    return deep_in_sites(0u, prm.solid_n, floor((p - prm.solid_lo) * prm.solid_inv_ds), true);
}
