//! Where the fluid is cut into slabs, and the halo each slab needs.

use crate::emps::kernel::Kernel;
use crate::neighbours::collision::COLLISION_DISTANCE;
use crate::particles::kind::FLUID;
use crate::particles::Particles;

/// Spacings added to the halo for what the particles move in a step: the detector stops a step
/// that moves a particle more than half a spacing (`crate::stability::MAX_STEP_DISPLACEMENT`),
/// and a chain of passes (see [`halo_width`]) is measured at positions up to that far from
/// those the halo is taken at: at its two ends, and twice where it turns from the positions
/// after S1-11 to those after S1-13.
pub const MOTION_SPACINGS: f64 = 2.0;

/// The halo's thickness: every fluid particle within it of a slab's faces is copied to the
/// slab, so that the owned particles' step is the whole domain's. It is the sum of the reaches
/// of the neighbour passes an owned particle's step depends on in a chain (`crate::emps::step`),
/// plus [`MOTION_SPACINGS`]: the collisions (0.8 Δs) of velocities set by the pressure gradient
/// and the artificial viscosity (r_e,grad) from pressures of the number density at r* (r_e),
/// and, with the viscous term on, r* set by the viscous term at r^k (r_e). At E-MPS's radii that
/// is 6.0 Δs + 2 Δs, 9.1 Δs + 2 Δs with the viscous term. What reads the halo (probes, the drag
/// coupling's sampling and spreading, frames) reads it after the exchange that ends a step, when
/// every copy is its owner's state.
pub fn halo_width(k: &Kernel, viscous: bool) -> f64 {
    let viscous_term = if viscous { k.re } else { 0.0 };
    let chain = COLLISION_DISTANCE * k.spacing + k.re_grad + k.re + viscous_term;
    chain + MOTION_SPACINGS * k.spacing
}

/// The cuts of `parts` slabs along x: slab r owns `cuts[r] ≤ x < cuts[r + 1]` (the first and
/// last reach ±∞). The inner cuts split the fluid particles of `p` into about equal counts, each
/// half-way between the two nearest distinct x of the fluid (so no particle sits on one). An
/// error when a slab would be thinner than `min_width` (a halo must come from one neighbour).
pub fn cuts(p: &Particles, parts: usize, min_width: f64) -> Result<Vec<f64>, String> {
    let mut x: Vec<f64> = (0..p.len())
        .filter(|&i| p.kind[i] == FLUID)
        .map(|i| p.x[i])
        .collect();
    if x.is_empty() || parts == 0 {
        return Err("no fluid to cut into slabs".into());
    }
    x.sort_by(f64::total_cmp);
    let mut cuts = vec![f64::NEG_INFINITY];
    for r in 1..parts {
        let m = (r * x.len() / parts).max(1);
        let before = x[m - 1];
        let Some(&after) = x[m..].iter().find(|&&v| v > before) else {
            return Err(format!(
                "the fluid cannot be cut into {parts} slabs along x: use fewer"
            ));
        };
        cuts.push(0.5 * (before + after));
    }
    cuts.push(f64::INFINITY);
    let (lo, hi) = (x[0], x[x.len() - 1]);
    for r in 0..parts {
        let (a, b) = (cuts[r].max(lo), cuts[r + 1].min(hi));
        // inner slabs between their cuts; the end slabs from the fluid's end
        if b - a < min_width && parts > 1 {
            return Err(format!(
                "{parts} slabs of the fluid's {:.4} m along x would leave slab {r} {:.4} m wide, less than the halo of {min_width:.4} m each slab needs: use fewer slabs",
                hi - lo,
                b - a
            ));
        }
    }
    Ok(cuts)
}

/// Whether the open boundaries fit the slabs cut at `cuts`: the first slab runs the inflow and
/// the last the outflow ([`super::subdomain`]), so the inflow plane (its strip lies upstream)
/// must lie a halo (`halo`) or more before the first inner cut and the outflow plane a halo or
/// more after the last one; an error naming the plane and the cut otherwise.
pub fn open_boundaries_fit(
    inflow: Option<f64>,
    outflow: Option<f64>,
    cuts: &[f64],
    halo: f64,
) -> Result<(), String> {
    let slabs = cuts.len() - 1;
    if slabs < 2 {
        return Ok(());
    }
    let (first, last) = (cuts[1], cuts[slabs - 1]);
    if let Some(plane) = inflow.filter(|&plane| first - plane < halo) {
        return Err(format!(
            "the inflow plane at x = {plane} m lies {:.4} m before the first cut at x = {first:.4} m, less than the halo of {halo:.4} m: use fewer slabs (the first slab runs the inflow, and no other slab may hold its strip)",
            first - plane
        ));
    }
    if let Some(plane) = outflow.filter(|&plane| plane - last < halo) {
        return Err(format!(
            "the outflow plane at x = {plane} m lies {:.4} m after the last cut at x = {last:.4} m, less than the halo of {halo:.4} m: use fewer slabs (the last slab runs the outflow, and no other slab may hold water behind it)",
            plane - last
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::kind::Kind;

    fn row(n: usize, spacing: f64) -> Particles {
        let mut p = Particles::default();
        for i in 0..n {
            p.push([(i as f64 + 0.5) * spacing, 0.0, 0.0], Kind::Fluid);
            p.push([(i as f64 + 0.5) * spacing, -spacing, 0.0], Kind::Wall);
        }
        p
    }

    #[test]
    fn cuts_split_the_fluid_evenly_between_lattice_planes() {
        let ds = 0.01;
        let p = row(100, ds);
        let cuts = cuts(&p, 4, 0.1).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(cuts.len(), 5);
        for r in 0..4 {
            let owned = (0..p.len())
                .filter(|&i| p.kind[i] == FLUID && cuts[r] <= p.x[i] && p.x[i] < cuts[r + 1])
                .count();
            assert_eq!(owned, 25, "slab {r}: {cuts:?}");
        }
        for c in &cuts[1..4] {
            let off = (c / ds).fract();
            assert!(
                off.abs() < 1e-9 || (off - 1.0).abs() < 1e-9,
                "cut {c} not half-way between particles"
            );
        }
    }

    #[test]
    fn open_boundaries_closer_to_a_cut_than_the_halo_are_refused() {
        let cuts = [f64::NEG_INFINITY, 1.0, 2.0, f64::INFINITY];
        assert!(open_boundaries_fit(Some(0.5), Some(2.5), &cuts, 0.5).is_ok());
        let e = open_boundaries_fit(Some(0.6), None, &cuts, 0.5).expect_err("inflow 0.4 m from the cut");
        assert!(
            e.contains("the inflow plane at x = 0.6 m") && e.contains("use fewer slabs"),
            "{e}"
        );
        let e = open_boundaries_fit(None, Some(2.4), &cuts, 0.5).expect_err("outflow 0.4 m from the cut");
        assert!(
            e.contains("the outflow plane at x = 2.4 m") && e.contains("use fewer slabs"),
            "{e}"
        );
        let one = [f64::NEG_INFINITY, f64::INFINITY];
        assert!(
            open_boundaries_fit(Some(10.0), Some(-10.0), &one, 0.5).is_ok(),
            "one slab runs both"
        );
    }

    #[test]
    fn slabs_thinner_than_the_halo_are_refused() {
        let p = row(100, 0.01);
        let e = cuts(&p, 8, 0.2).expect_err("8 slabs of 0.125 m against a 0.2 m halo");
        assert!(e.contains("use fewer slabs"), "{e}");
    }
}
