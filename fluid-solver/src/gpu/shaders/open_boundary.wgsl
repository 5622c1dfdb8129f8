// The open boundaries' pass before a step (src/boundaries/open_boundary.rs, src/gpu/open_boundary.rs),
// over the particles on the device: a strip particle at or past prm.inflow_enter becomes fluid;
// one above prm.inflow_cut is withdrawn; the others move by u Δt and take u as their velocity;
// then fluid past the outflow plane is removed. Removed and withdrawn particles are marked
// REMOVED for the next cell sort to drop. The counts go to cell_count[cells + 1 … cells + 3]
// (entered, removed, withdrawn), which the host zeroes before the pass.
// Whether particle i, whose position's x (its high part with wide positions) is x, lies past
// the outflow plane; with wide positions on both parts, so that it decides as the CPU's f64
// does however far the plane lies from the frame's origin.
fn past_outflow(i: u32, x: f32) -> bool {
    if WIDE {
        return (x - prm.outflow_x) + (pos_lo[i].x - prm.outflow_low) > 0.0;
    }
    return x > prm.outflow_x;
}

@compute @workgroup_size(64)
fn open_boundaries(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    var p = pos[i];
    var k = u32(p.w);
    if k == INFLOW {
        if p.x >= prm.inflow_enter {
            k = FLUID;
            p.w = f32(FLUID);
            atomicAdd(&cell_count[prm.cells + 1u], 1u);
        } else if p.z > prm.inflow_cut {
            pos[i] = vec4<f32>(p.xyz, f32(REMOVED));
            atomicAdd(&cell_count[prm.cells + 3u], 1u);
            return;
        } else {
            vel[i] = vec4<f32>(prm.inflow_u, vel[i].y, vel[i].z, 0.0);
            shift(i, vec3<f32>(prm.inflow_dx, 0.0, 0.0));
            return;
        }
    }
    if k == FLUID && past_outflow(i, p.x) {
        p.w = f32(REMOVED);
        atomicAdd(&cell_count[prm.cells + 2u], 1u);
    }
    pos[i] = p;
}
