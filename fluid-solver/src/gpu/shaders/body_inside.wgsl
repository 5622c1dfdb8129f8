// The instability detector's "inside a body" check (src/particles/body_interior.rs) at each
// body's present pose (body_kin): BODY_ENTRY words per body from word prm.body_table of
// solid_bits, then the mesh bodies' sites (src/gpu/body_inside.rs).

const BODY_ENTRY: u32 = 8u;
const BODY_BOX: u32 = 0u;

// Three f32 from words e … e + 2 of solid_bits.
fn table_vec(e: u32) -> vec3<f32> {
    return vec3<f32>(bitcast<f32>(solid_bits[e]), bitcast<f32>(solid_bits[e + 1u]),
        bitcast<f32>(solid_bits[e + 2u]));
}

// BodyInterior::holds: p, in a body's frame about its centre R(q)ᵀ (p − c), lies within a box
// body's half extents less half a spacing, or more than half a spacing inside a mesh body's
// sites (deep_in_sites on its lattice, whose origin is kept relative to the initial centre;
// nothing beyond that lattice is the body's).
fn inside_body(p: vec3<f32>) -> bool {
    for (var b = 0u; b < prm.n_bodies; b = b + 1u) {
        let k = body_kin[b];
        let local = rotate(vec4<f32>(k.quat.x, -k.quat.yzw), p - k.centre.xyz);
        let e = prm.body_table + BODY_ENTRY * b;
        let v = table_vec(e + 1u);
        if solid_bits[e] == BODY_BOX {
            if all(abs(local) < v) {
                return true;
            }
        } else {
            let n = vec3<u32>(solid_bits[e + 4u], solid_bits[e + 5u], solid_bits[e + 6u]);
            if deep_in_sites(solid_bits[e + 7u], n, floor((local - v) / prm.spacing), false) {
                return true;
            }
        }
    }
    return false;
}
