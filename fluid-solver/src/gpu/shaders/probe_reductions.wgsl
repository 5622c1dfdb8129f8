// What the global probes read, reduced on the device (src/sensors/probes.rs,
// src/gpu/probe_reductions.rs), over the fluid particles that are water, not spray (number
// density at least half of n0, the probes' rule), as atomic maxima of order-preserving keys of
// f32 values in cell_count[cells + 4 …], which the host zeroes first; each workgroup merges its
// own first. Plain positions only: with wide positions the host reads a light copy instead.
// - water_extent: the largest and the smallest x, y and z (the surge fronts), in words 4 … 9
//   (+x, −x, +y, −y, +z, −z: the largest of x and of −x, …);
// - run_up: the highest z of the water resting on a solid (the run-up gauge), in word 11.

// A key of `v` whose unsigned order is the order of the values (negative values' bits flipped).
fn order_key(v: f32) -> u32 {
    let b = bitcast<u32>(v);
    return select(b | 0x80000000u, ~b, (b & 0x80000000u) != 0u);
}

// Whether particle i is water, not spray.
fn is_water(i: u32) -> bool {
    return i < prm.n && kind_of(i) == FLUID && dens[i].x >= 0.5 / prm.inv_n0;
}

// The workgroup's own maxima, merged into the global words by one thread each.
var<workgroup> group_keys: array<atomic<u32>, 6>;

// Clears the workgroup's keys (every thread calls it, then waits).
fn clear_group_keys(local: u32) {
    if local < 6u {
        atomicStore(&group_keys[local], 0u);
    }
    workgroupBarrier();
}

// Merges the workgroup's first `words` keys into cell_count[cells + first …] (every thread
// calls it after its own maxima).
fn merge_group_keys(local: u32, first: u32, words: u32) {
    workgroupBarrier();
    if local < words {
        let key = atomicLoad(&group_keys[local]);
        if key != 0u {
            atomicMax(&cell_count[prm.cells + first + local], key);
        }
    }
}

@compute @workgroup_size(64)
fn water_extent(v: Invocation) {
    clear_group_keys(v.local);
    let i = item_index(v, WG);
    if is_water(i) {
        let p = pos[i];
        for (var a = 0u; a < 3u; a++) {
            atomicMax(&group_keys[2u * a], order_key(p[a]));
            atomicMax(&group_keys[2u * a + 1u], order_key(-p[a]));
        }
    }
    merge_group_keys(v.local, 4u, 6u);
}

// Whether water particle i rests on a solid (a wall or body particle lies below it within
// r_e,grad and within atan ½ of the vertical: its horizontal offset under half its depth below),
// as probes.rs's run_up decides.
fn rests_on_solid(i: u32) -> bool {
    let xi = pos[i].xyz;
    let li = low(i);
    let c = cell_sorted[i];
    let reach2 = prm.re_grad * prm.re_grad;
    let r = prm.reach;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            for (var j = range.x; j < range.y; j = j + 1u) {
                let k = kind_of(j);
                if k != WALL && k != BODY {
                    continue;
                }
                let d = apart_near(pos[j].xyz, j, xi, li);
                let across = d.x * d.x + d.y * d.y;
                let below = -d.z;
                if below > 0.0 && 4.0 * across < below * below && across + below * below <= reach2 {
                    return true;
                }
            }
        }
    }
    return false;
}

@compute @workgroup_size(64)
fn run_up(v: Invocation) {
    clear_group_keys(v.local);
    let i = item_index(v, WG);
    if is_water(i) && rests_on_solid(i) {
        atomicMax(&group_keys[0], order_key(pos[i].z));
    }
    merge_group_keys(v.local, 11u, 1u);
}
