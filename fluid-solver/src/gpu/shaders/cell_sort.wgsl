// Counting sort of the particles by cell (the CPU's CellGrid::sort): count, exclusive prefix
// sum of the counts, scatter, then each cell's slots ordered by previous index so the order is
// the same every run, then the particle arrays gathered into the new order.

@compute @workgroup_size(64)
fn clear_cells(@builtin(global_invocation_id) g: vec3<u32>) {
    let c = g.x;
    if c < prm.cells {
        atomicStore(&cell_count[c], 0u);
        atomicStore(&fluid_count[c], 0u);
        if prm.n_bodies > 0u {
            atomicStore(&body_cells[c], 0u);
        }
    }
}

@compute @workgroup_size(64)
fn count_cells(@builtin(global_invocation_id) g: vec3<u32>) {
    let i = g.x;
    if i >= prm.n {
        return;
    }
    let c = cell_index(pos[i].xyz);
    cell_of[i] = c;
    atomicAdd(&cell_count[c], 1u);
    let k = kind_of(i);
    if k == FLUID {
        atomicAdd(&fluid_count[c], 1u);
    }
    if k == BODY && prm.n_bodies > 0u {
        let m = member_of(pid[i]);
        if m != NONE {
            mark_body_near(c, 1u << (members[m].body % 32u));
        }
    }
}

// Sets `bit` in every cell within reach_react of cell c (cell_index keeps c at least pad ≥
// reach cells from the grid's faces).
fn mark_body_near(c: u32, bit: u32) {
    let r = reach_react();
    let nx = prm.dims.x;
    let nxy = nx * prm.dims.y;
    let base = c - r * nxy - r * nx - r;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            for (var dx = 0u; dx <= 2u * r; dx = dx + 1u) {
                atomicOr(&body_cells[base + dz * nxy + dy * nx + dx], bit);
            }
        }
    }
}

var<workgroup> scan_tmp: array<u32, 256>;

// Exclusive scan of one block of 256 counts in workgroup memory (Hillis–Steele); the block's
// total goes to block_sums.
@compute @workgroup_size(256)
fn scan_blocks(@builtin(global_invocation_id) g: vec3<u32>, @builtin(local_invocation_id) l: vec3<u32>, @builtin(workgroup_id) w: vec3<u32>) {
    let c = g.x;
    var v = 0u;
    if c < prm.cells {
        v = atomicLoad(&cell_count[c]);
    }
    scan_tmp[l.x] = v;
    workgroupBarrier();
    for (var d = 1u; d < SCAN_WG; d = d * 2u) {
        var t = 0u;
        if l.x >= d {
            t = scan_tmp[l.x - d];
        }
        workgroupBarrier();
        scan_tmp[l.x] = scan_tmp[l.x] + t;
        workgroupBarrier();
    }
    if c < prm.cells {
        cell_start[c] = scan_tmp[l.x] - v;
    }
    if l.x == SCAN_WG - 1u {
        block_sums[w.x] = scan_tmp[l.x];
    }
}

// Exclusive scan of the block totals by one workgroup, 256 at a time with a carry; writes the
// grand total (the particle count) to cell_start[cells].
@compute @workgroup_size(256)
fn scan_sums(@builtin(local_invocation_id) l: vec3<u32>) {
    var carry = 0u;
    for (var base = 0u; base < prm.scan_blocks; base = base + SCAN_WG) {
        let b = base + l.x;
        var v = 0u;
        if b < prm.scan_blocks {
            v = block_sums[b];
        }
        scan_tmp[l.x] = v;
        workgroupBarrier();
        for (var d = 1u; d < SCAN_WG; d = d * 2u) {
            var t = 0u;
            if l.x >= d {
                t = scan_tmp[l.x - d];
            }
            workgroupBarrier();
            scan_tmp[l.x] = scan_tmp[l.x] + t;
            workgroupBarrier();
        }
        if b < prm.scan_blocks {
            block_sums[b] = carry + scan_tmp[l.x] - v;
        }
        carry = carry + scan_tmp[SCAN_WG - 1u];
        workgroupBarrier();
    }
    if l.x == 0u {
        cell_start[prm.cells] = carry;
    }
}

@compute @workgroup_size(256)
fn scan_add(@builtin(global_invocation_id) g: vec3<u32>, @builtin(workgroup_id) w: vec3<u32>) {
    if g.x < prm.cells {
        cell_start[g.x] = cell_start[g.x] + block_sums[w.x];
    }
}

@compute @workgroup_size(64)
fn scatter(@builtin(global_invocation_id) g: vec3<u32>) {
    let i = g.x;
    if i >= prm.n {
        return;
    }
    let c = cell_of[i];
    let slot = cell_start[c] + atomicSub(&cell_count[c], 1u) - 1u;
    perm[slot] = i;
}

// Insertion sort of each cell's slots by previous index (a handful per cell).
@compute @workgroup_size(64)
fn order_cells(@builtin(global_invocation_id) g: vec3<u32>) {
    let c = g.x;
    if c >= prm.cells {
        return;
    }
    let s = cell_start[c];
    let e = cell_start[c + 1u];
    for (var k = s + 1u; k < e; k = k + 1u) {
        let v = perm[k];
        var m = k;
        while m > s && perm[m - 1u] > v {
            perm[m] = perm[m - 1u];
            m = m - 1u;
        }
        perm[m] = v;
    }
}

// Gathers positions, velocities and ids into the sorted order (into the spare arrays, copied
// back by the host's command encoder).
@compute @workgroup_size(64)
fn reorder(@builtin(global_invocation_id) g: vec3<u32>) {
    let k = g.x;
    if k >= prm.n {
        return;
    }
    let j = perm[k];
    spare_pos[k] = pos[j];
    spare_vel[k] = vel[j];
    spare_id[k] = pid[j];
    cell_sorted[k] = cell_of[j];
}
