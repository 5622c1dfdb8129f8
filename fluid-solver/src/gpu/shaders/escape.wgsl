// Fluid that left through the open top (src/boundaries/escape.rs; reduce.wgsl's `finding` sets
// `left` by the same rule the last step's scan counted with), marked REMOVED for the cell sort
// that follows to drop, and counted in cell_count[cells + 10], which the host zeroes first.
@compute @workgroup_size(64)
fn remove_escaped(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    var left = false;
    let f = finding(i, &left);
    if left && kind_of(i) == FLUID {
        pos[i].w = f32(REMOVED);
        atomicAdd(&cell_count[prm.cells + 10u], 1u);
    }
}
