// The wave maker's paddle (src/boundaries/paddle.rs, src/gpu/paddle.rs): before each step each
// paddle particle is placed where the prescribed motion has it at the step's end and given the
// step's chord velocity, from its rest position (x, z) in the members' buffer (row
// prm.paddle_row + id − prm.paddle_first) and the placement the host put in the uniform block:
// x = x0 + s + r_x (cos θ − 1) + r_z sin θ, z = z0 − r_x sin θ + r_z (cos θ − 1) with r the rest
// position less the hinge, y and v_y unchanged (a piston: θ = 0; a flap: s = 0). With wide
// positions x0, z0 are the rest position's high parts and the rest goes to the low parts.
@compute @workgroup_size(64)
fn place_paddle(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n {
        return;
    }
    // below paddle_first the difference wraps past paddle_count
    let k = pid[i] - prm.paddle_first;
    if k >= prm.paddle_count {
        return;
    }
    let row = members[prm.paddle_row + k];
    let rest = row.offset;
    var rx = rest.x - prm.hinge_x;
    var rz = rest.z - prm.hinge_z;
    if WIDE {
        rx = rx + (row.low_x - prm.hinge_low_x);
        rz = rz + (row.low_z - prm.hinge_low_z);
    }
    let x = rest.x + prm.paddle_shift + (rx * prm.paddle_cos_m1 + rz * prm.paddle_sin);
    let z = rest.z + (rz * prm.paddle_cos_m1 - rx * prm.paddle_sin);
    let vx = prm.paddle_speed + (rx * prm.paddle_dcos + rz * prm.paddle_dsin);
    let vz = rz * prm.paddle_dcos - rx * prm.paddle_dsin;
    let p = pos[i];
    if WIDE {
        // the rest position's high parts stay; its low parts take the motion
        let x_lo = row.low_x + prm.paddle_shift + (rx * prm.paddle_cos_m1 + rz * prm.paddle_sin);
        let z_lo = row.low_z + (rz * prm.paddle_cos_m1 - rx * prm.paddle_sin);
        place(i, vec3<f32>(rest.x, p.y, rest.z), vec3<f32>(x_lo, pos_lo[i].y, z_lo));
    } else {
        pos[i] = vec4<f32>(x, p.y, z, p.w);
    }
    vel[i] = vec4<f32>(vx, vel[i].y, vz, 0.0);
}
