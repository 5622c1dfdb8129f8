// The mesh solids' and terrains' sites (src/particles/solid_sites.rs) for the instability
// detector: one bit per site of the tank's lattice, site (i, j, k) at bit i + n_x (j + n_y k).

// Whether site c is solid; a site beyond the lattice counts as `beyond`.
fn solid_at(c: vec3<i32>, beyond: bool) -> bool {
    let n = vec3<i32>(prm.solid_n);
    if any(c < vec3<i32>(0)) || any(c >= n) {
        return beyond;
    }
    let u = vec3<u32>(c);
    let b = u.x + prm.solid_n.x * (u.y + prm.solid_n.y * u.z);
    return (solid_bits[b / 32u] & (1u << (b % 32u))) != 0u;
}

// SolidSites::deep_inside: p lies more than about half a spacing inside a solid when the site
// whose cube holds it and that site's six face neighbours are all solid (beyond the lattice is
// the tank's wall: solid).
fn deep_in_solid(p: vec3<f32>) -> bool {
    if prm.solids == 0u {
        return false;
    }
    let f = floor((p - prm.solid_lo) * prm.solid_inv_ds);
    // off the lattice (checked in f32: far spray must not overflow an i32)
    if any(f < vec3<f32>(0.0)) || any(f >= vec3<f32>(prm.solid_n)) {
        return false;
    }
    let c = vec3<i32>(f);
    if !solid_at(c, false) {
        return false;
    }
    for (var a = 0; a < 3; a = a + 1) {
        let e = vec3<i32>(select(0, 1, a == 0), select(0, 1, a == 1), select(0, 1, a == 2));
        if !solid_at(c - e, true) || !solid_at(c + e, true) {
            return false;
        }
    }
    return true;
}
