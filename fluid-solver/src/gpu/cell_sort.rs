//! Counting sort and prefix sum by cell on the device (the CPU's [`crate::neighbours::neighbour_search`]):
//! count per cell, exclusive scan in three levels (blocks of 4096 cells, groups of 256 blocks,
//! and the groups' totals: any cell count a buffer holds), scatter, order each cell's slots by
//! previous index (so a run is repeatable), gather positions (and their low parts when wide),
//! velocities and ids into the new order through arrays that are free during the sort.

use super::buffers::{Buffers, ACC, ID, PERM, POS, POS_LO, VEL};
use super::kernels::{dispatch, Kernels, WG, WIDE_WG};

/// Records the sort of `n` particles into `cells` cells.
pub fn encode(enc: &mut wgpu::CommandEncoder, k: &Kernels, b: &Buffers, n: u32, cells: u32) {
    pass(enc, "cell sort", |pass| {
        dispatch(pass, k, &k.clear_cells, cells, WG);
        dispatch(pass, k, &k.count_cells, n, WG);
        scan(pass, k, cells);
        dispatch(pass, k, &k.scatter, n, WG);
        dispatch(pass, k, &k.order_cells, cells, WG);
        dispatch(pass, k, &k.gather_positions, n, WG);
    });
    // the gathers go through acc and perm, free during the sort (`shaders/cell_sort.wgsl`)
    let bytes = |size: u64| size * u64::from(n);
    enc.copy_buffer_to_buffer(b.at(ACC), 0, b.at(POS), 0, bytes(16));
    if b.wide {
        pass(enc, "gather low parts", |pass| {
            dispatch(pass, k, &k.gather_lows, n, WG)
        });
        enc.copy_buffer_to_buffer(b.at(ACC), 0, b.at(POS_LO), 0, bytes(16));
    }
    pass(enc, "gather velocities", |pass| {
        dispatch(pass, k, &k.gather_velocities, n, WG)
    });
    enc.copy_buffer_to_buffer(b.at(ACC), 0, b.at(VEL), 0, bytes(16));
    pass(enc, "gather ids", |pass| dispatch(pass, k, &k.gather_ids, n, WG));
    enc.copy_buffer_to_buffer(b.at(PERM), 0, b.at(ID), 0, bytes(4));
}

/// Records one compute pass filled by `f`.
fn pass(enc: &mut wgpu::CommandEncoder, label: &str, f: impl FnOnce(&mut wgpu::ComputePass<'_>)) {
    let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    f(&mut pass);
}

/// Cells per thread and per block of the scan's first level (`SCAN_RUN`, `SCAN_BLOCK` in
/// `shaders/cell_sort.wgsl`).
const SCAN_RUN: u32 = 16;
const SCAN_BLOCK: u32 = SCAN_RUN * WIDE_WG;

/// Records the exclusive prefix sum of the counts of `cells` cells into the cell starts
/// (`shaders/cell_sort.wgsl`: blocks of 4096 cells, groups of 256 blocks, then the groups'
/// totals by one workgroup; the uniform block's `cells` and `scan_blocks` must be these).
pub fn scan(pass: &mut wgpu::ComputePass<'_>, k: &Kernels, cells: u32) {
    let blocks = scan_blocks(cells);
    dispatch(pass, k, &k.scan_cells, cells.div_ceil(SCAN_RUN), WIDE_WG);
    dispatch(pass, k, &k.scan_block_sums, blocks, WIDE_WG);
    dispatch(pass, k, &k.scan_tops, 1, WIDE_WG);
    dispatch(pass, k, &k.add_tops, blocks, WIDE_WG);
    dispatch(pass, k, &k.add_blocks, cells, WIDE_WG);
}

/// Blocks of 4096 cells of the scan's first level.
pub fn scan_blocks(cells: u32) -> u32 {
    cells.div_ceil(SCAN_BLOCK).max(1)
}

/// Entries of the scan's block totals: the blocks', then their groups' of 256.
pub fn block_sum_entries(cells: u32) -> u64 {
    let blocks = scan_blocks(cells);
    u64::from(blocks) + u64::from(blocks.div_ceil(WIDE_WG))
}
