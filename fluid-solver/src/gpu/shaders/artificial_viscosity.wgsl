// The optional artificial viscosity of E-MPS (src/emps/artificial_viscosity.rs: Monaghan 1992,
// eq. 4.2, in S1-3's form): for fluid i at r*, u*,
// ⟨∇q⟩_i = d/n0_grad Σ_j q_ij r_ij/|r_ij|² w_grad(|r_ij|) over the fluid j within r_e,grad that
// approach i ((u_j − u_i)·r_ij < 0), q_ij = −α ρ0 c h (u_j − u_i)·r_ij / (|r_ij|² + 0.01 h²),
// h = r_e,grad / 2; added to ⟨∇P⟩_i in acc before S1-12. Walls and bodies take no part (their
// force stays S1-3's).
@compute @workgroup_size(64)
fn artificial_viscosity(v: Invocation) {
    let i = item_index(v, WG);
    if i >= prm.n || kind_of(i) != FLUID {
        return;
    }
    let re = prm.re_grad;
    let re2 = re * re;
    let xi = pos[i].xyz;
    let li = low(i);
    let ui = vel[i].xyz;
    let c = cell_sorted[i];
    var g = vec3<f32>(0.0);
    var seen = 0u;
    let r = prm.reach_grad;
    for (var dz = 0u; dz <= 2u * r; dz = dz + 1u) {
        for (var dy = 0u; dy <= 2u * r; dy = dy + 1u) {
            let range = row_range(c, r, dy, dz);
            seen = seen + range.y - range.x;
            for (var j = range.x; j < range.y; j = j + 1u) {
                let pj = pos[j];
                let d = apart_near(pj.xyz, j, xi, li);
                let r2 = dot(d, d);
                let approach = dot(vel[j].xyz - ui, d);
                if r2 < re2 && r2 > 0.0 && u32(pj.w) == FLUID && approach < 0.0 {
                    let rr = sqrt(r2);
                    let q = prm.av_scale * approach / (r2 + prm.av_eta2);
                    g = g + (q * (re / rr - rr / re) / r2) * d;
                }
            }
        }
    }
    acc[i] = acc[i] + vec4<f32>(prm.grad_factor * g, 0.0);
    cand[i] = cand[i] + seen;
}
