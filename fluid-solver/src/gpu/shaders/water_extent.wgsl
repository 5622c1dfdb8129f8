// The water's extent along each axis, for the surge-front probes (src/sensors/probes.rs,
// src/gpu/water_extent.rs): over the fluid particles that are water, not spray (number density
// at least half of n0, the probes' rule), the largest and the smallest x, y and z, as atomic
// maxima of order-preserving keys of their f32 values in cell_count[cells + 4 … cells + 9]
// (+x, −x, +y, −y, +z, −z: the largest of x and of −x, …), which the host zeroes first; each
// workgroup merges its own first.
// Plain positions only: with wide positions the host reads a light copy instead.

// A key of `v` whose unsigned order is the order of the values (negative values' bits flipped).
fn order_key(v: f32) -> u32 {
    let b = bitcast<u32>(v);
    return select(b | 0x80000000u, ~b, (b & 0x80000000u) != 0u);
}

// The workgroup's own maxima, merged into the global six by one thread.
var<workgroup> group_keys: array<atomic<u32>, 6>;

@compute @workgroup_size(64)
fn water_extent(v: Invocation) {
    if v.local < 6u {
        atomicStore(&group_keys[v.local], 0u);
    }
    workgroupBarrier();
    let i = item_index(v, WG);
    if i < prm.n {
        let p = pos[i];
        if u32(p.w) == FLUID && dens[i].x >= 0.5 / prm.inv_n0 {
            for (var a = 0u; a < 3u; a++) {
                atomicMax(&group_keys[2u * a], order_key(p[a]));
                atomicMax(&group_keys[2u * a + 1u], order_key(-p[a]));
            }
        }
    }
    workgroupBarrier();
    if v.local < 6u {
        let key = atomicLoad(&group_keys[v.local]);
        if key != 0u {
            atomicMax(&cell_count[prm.cells + 4u + v.local], key);
        }
    }
}
