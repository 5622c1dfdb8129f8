// Counting sort of the particles by cell (the CPU's CellGrid::sort): count (and flag the cells
// that hold fluid; with bodies, mark the cells near each body in body_cells, which the gather
// leaves alone), exclusive prefix sum of the counts, scatter, then each cell's slots ordered by
// previous index so the order is the same every run, then the particle arrays gathered into the
// new order. Particles the open boundaries removed (kind REMOVED) are counted in no cell and
// scattered past the others, so the sort also closes their gaps (shaders/open_boundary.wgsl).

@compute @workgroup_size(64)
fn clear_cells(v: Invocation) {
    let c = item_index(v, WG);
    if c < prm.cells {
        atomicStore(&cell_count[c], 0u);
        if prm.n_bodies > 0u {
            atomicStore(&body_cells[c], 0u);
        }
    }
}

@compute @workgroup_size(64)
fn count_cells(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    if kind_of(i) == REMOVED {
        cell_of[i] = NONE;
        return;
    }
    let c = cell_index(pos[i].xyz);
    cell_of[i] = c;
    atomicAdd(&cell_count[c], 1u);
    let k = kind_of(i);
    if k == FLUID {
        atomicOr(&cell_count[c], FLUID_CELL);
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

// The exclusive prefix sum of the counts, in three levels, each an exact integer scan: the
// cells by blocks of 4096 (scan_cells: each of 256 threads sums a run of 16 cells, the
// workgroup scans the runs' totals in workgroup memory, each thread writes its run's starts),
// the blocks' totals by groups of 256 (scan_block_sums), the groups' totals by one workgroup
// that loops with a carry (scan_tops; one pass per 2^28 cells), then each level's prefix added
// back down (add_tops, add_blocks). block_sums holds the blocks' totals (prm.scan_blocks of
// them), then the groups' totals.

// Cells per thread of the first level (fewer workgroup barriers per cell).
const SCAN_RUN: u32 = 16u;
// Cells per block of the first level.
const SCAN_BLOCK: u32 = 4096u;

// Groups of 256 blocks.
fn scan_tops_count() -> u32 {
    return (prm.scan_blocks + SCAN_WG - 1u) / SCAN_WG;
}

// Inclusive scan (Hillis–Steele) of the workgroup's values `x`, thread `l` holding its own:
// returns the thread's inclusive prefix; scan_tmp[255] holds the total afterwards.
fn scan_workgroup(l: u32, x: u32) -> u32 {
    scan_tmp[l] = x;
    workgroupBarrier();
    for (var d = 1u; d < SCAN_WG; d = d * 2u) {
        var t = 0u;
        if l >= d {
            t = scan_tmp[l - d];
        }
        workgroupBarrier();
        scan_tmp[l] = scan_tmp[l] + t;
        workgroupBarrier();
    }
    return scan_tmp[l];
}

// Level 1: exclusive scan of each block of 4096 counts into cell_start; the block's total goes
// to block_sums[block].
@compute @workgroup_size(256)
fn scan_cells(v: Invocation) {
    let first = item_index(v, SCAN_WG) * SCAN_RUN;
    let block = group_index(v);
    let end = min(first + SCAN_RUN, prm.cells);
    var total = 0u;
    for (var c = first; c < end; c = c + 1u) {
        total = total + (atomicLoad(&cell_count[c]) & ~FLUID_CELL);
    }
    let inclusive = scan_workgroup(v.local, total);
    var start = inclusive - total;
    for (var c = first; c < end; c = c + 1u) {
        cell_start[c] = start;
        start = start + (atomicLoad(&cell_count[c]) & ~FLUID_CELL);
    }
    if v.local == SCAN_WG - 1u && block < prm.scan_blocks {
        block_sums[block] = inclusive;
    }
}

// Level 2: exclusive scan of each group of 256 block totals in place; the group's total goes
// after the blocks' totals.
@compute @workgroup_size(256)
fn scan_block_sums(v: Invocation) {
    let b = item_index(v, SCAN_WG);
    let group = group_index(v);
    var x = 0u;
    if b < prm.scan_blocks {
        x = block_sums[b];
    }
    let inclusive = scan_workgroup(v.local, x);
    if b < prm.scan_blocks {
        block_sums[b] = inclusive - x;
    }
    if v.local == SCAN_WG - 1u && group < scan_tops_count() {
        block_sums[prm.scan_blocks + group] = inclusive;
    }
}

// Level 3: exclusive scan of the groups' totals by one workgroup, 256 at a time with a carry;
// writes the grand total (the particle count) to cell_start[cells].
@compute @workgroup_size(256)
fn scan_tops(v: Invocation) {
    let l = v.local;
    let tops = scan_tops_count();
    let at = prm.scan_blocks;
    var carry = 0u;
    for (var base = 0u; base < tops; base = base + SCAN_WG) {
        let t = base + l;
        var x = 0u;
        if t < tops {
            x = block_sums[at + t];
        }
        let inclusive = scan_workgroup(l, x);
        if t < tops {
            block_sums[at + t] = carry + inclusive - x;
        }
        carry = carry + scan_tmp[SCAN_WG - 1u];
        workgroupBarrier();
    }
    if l == 0u {
        cell_start[prm.cells] = carry;
    }
}

// Each block's prefix plus its group's.
@compute @workgroup_size(256)
fn add_tops(v: Invocation) {
    let b = item_index(v, SCAN_WG);
    if b < prm.scan_blocks {
        block_sums[b] = block_sums[b] + block_sums[prm.scan_blocks + b / SCAN_WG];
    }
}

// Each cell's prefix plus its block's.
@compute @workgroup_size(256)
fn add_blocks(v: Invocation) {
    let c = item_index(v, SCAN_WG);
    if c < prm.cells {
        cell_start[c] = cell_start[c] + block_sums[c / SCAN_BLOCK];
    }
}

@compute @workgroup_size(64)
fn scatter(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    let c = cell_of[i];
    if c == NONE {
        // removed by the open boundaries: past the kept particles (cell_start[cells]), in any
        // order, as the host then drops them
        perm[cell_start[prm.cells] + atomicAdd(&cell_count[prm.cells], 1u)] = i;
        return;
    }
    let slot = cell_start[c] + (atomicSub(&cell_count[c], 1u) & ~FLUID_CELL) - 1u;
    perm[slot] = i;
}

// Insertion sort of each cell's slots by previous index (a handful per cell).
@compute @workgroup_size(64)
fn order_cells(v: Invocation) {
    let c = item_index(v, WG);
    if c >= prm.cells {
        return;
    }
    let s = cell_start[c];
    let e = cell_start[c + 1u];
    for (var k = s + 1u; k < e; k = k + 1u) {
        let x = perm[k];
        var m = k;
        while m > s && perm[m - 1u] > x {
            perm[m] = perm[m - 1u];
            m = m - 1u;
        }
        perm[m] = x;
    }
}

// The gather of the particle arrays into the sorted order, in three passes through arrays that
// are free during the sort (no spare copies): positions into acc, velocities into acc, then ids
// into perm (each slot read, then written, by its own thread) with the cells; the host's
// command encoder copies each back after its pass (cell_sort.rs).
@compute @workgroup_size(64)
fn gather_positions(v: Invocation) {
    let k = item_index(v, WG);
    if k < prm.n {
        acc[k] = pos[perm[k]];
    }
}

// With wide positions, their low parts (after the velocities' pass).
@compute @workgroup_size(64)
fn gather_lows(v: Invocation) {
    let k = item_index(v, WG);
    if k < prm.n {
        acc[k] = pos_lo[perm[k]];
    }
}

@compute @workgroup_size(64)
fn gather_velocities(v: Invocation) {
    let k = item_index(v, WG);
    if k < prm.n {
        acc[k] = vel[perm[k]];
    }
}

@compute @workgroup_size(64)
fn gather_ids(v: Invocation) {
    let k = item_index(v, WG);
    if k < prm.n {
        let j = perm[k];
        cell_sorted[k] = cell_of[j];
        perm[k] = pid[j];
    }
}
