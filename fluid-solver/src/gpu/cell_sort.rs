//! Counting sort and prefix sum by cell on the device (the CPU's [`crate::neighbour_search`]):
//! count per cell, exclusive scan in blocks of 256, scatter, order each cell's slots by previous
//! index (so a run is repeatable), gather positions, velocities and ids into the new order.

use super::buffers::{Buffers, ID, POS, SPARE_ID, SPARE_POS, SPARE_VEL, VEL};
use super::kernels::{dispatch, Kernels, WG, WIDE_WG};

/// Records the sort of `n` particles into `cells` cells.
pub fn encode(enc: &mut wgpu::CommandEncoder, k: &Kernels, b: &Buffers, n: u32, cells: u32) {
    {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cell sort"),
            timestamp_writes: None,
        });
        dispatch(&mut pass, k, &k.clear_cells, cells, WG);
        dispatch(&mut pass, k, &k.count_cells, n, WG);
        dispatch(&mut pass, k, &k.scan_blocks, cells, WIDE_WG);
        dispatch(&mut pass, k, &k.scan_sums, 1, WIDE_WG);
        dispatch(&mut pass, k, &k.scan_add, cells, WIDE_WG);
        dispatch(&mut pass, k, &k.scatter, n, WG);
        dispatch(&mut pass, k, &k.order_cells, cells, WG);
        dispatch(&mut pass, k, &k.reorder, n, WG);
    }
    let bytes = |size: u64| size * u64::from(n);
    enc.copy_buffer_to_buffer(b.at(SPARE_POS), 0, b.at(POS), 0, bytes(16));
    enc.copy_buffer_to_buffer(b.at(SPARE_VEL), 0, b.at(VEL), 0, bytes(16));
    enc.copy_buffer_to_buffer(b.at(SPARE_ID), 0, b.at(ID), 0, bytes(4));
}
