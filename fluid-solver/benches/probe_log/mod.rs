//! A per-step log of what a point pressure probe reads and where it comes from: the probe is the
//! kernel-weighted mean `Σ w_i p_i / Σ w_i` over the fluid and solid particles within r_e,grad
//! ([`fluid_solver::probes::sample`]), split here into the fluid's and the solids' shares
//! (`fluid + solid = probe`); the nearest particle; the largest solid pressure read; and, for
//! ISPH, the surface (p = 0) particles near the probe and how many of them changed flag since
//! the step before (by particle id).
//!
//! Columns: `time, dt, probe, fluid, solid, solid_weight` (the solids' share of Σw), `nearest_kind,
//! nearest_id, nearest_r` (in Δs), `nearest_p, solid_max, fluid_near, surface_near, flips_near` (fluid within
//! 2 r_e,grad of the probe).

use fluid_solver::emps::kernel::weight;
use fluid_solver::method::MethodState;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::ProbeConfig;
use std::collections::HashMap;
use std::fs::File;
use std::io::{BufWriter, Write};

/// The log file and the surface flags of the step before, by particle id.
pub struct ProbeLog {
    out: BufWriter<File>,
    at: [f64; 3],
    surface: HashMap<u32, u8>,
}

impl ProbeLog {
    /// Creates the file with its header for the point probe `probe`.
    pub fn create(path: &str, probe: &ProbeConfig) -> std::io::Result<ProbeLog> {
        let mut out = BufWriter::new(File::create(path)?);
        writeln!(out, "time,dt,probe,fluid,solid,solid_weight,nearest_kind,nearest_id,nearest_r,nearest_p,solid_max,fluid_near,surface_near,flips_near")?;
        Ok(ProbeLog {
            out,
            at: [probe.position[0], probe.position[1], probe.position[2]],
            surface: HashMap::new(),
        })
    }

    /// One row after a step of `dt` whose probe read `probe`.
    pub fn row(&mut self, solver: &FluidSolver, dt: f64, probe: f64) {
        let (p, k) = (solver.particles(), solver.kernel());
        let ds = k.spacing;
        let flags = match solver.method_state() {
            MethodState::Isph(s) => Some(&s.surface),
            _ => None,
        };
        let (mut wf, mut ws, mut pf, mut ps) = (0.0, 0.0, 0.0, 0.0);
        let (mut nearest, mut solid_max) = ((f64::INFINITY, Kind::Fluid, 0.0, 0u32), f64::NEG_INFINITY);
        let (mut fluid_near, mut surface_near, mut flips) = (0, 0, 0);
        let mut surface = HashMap::new();
        for i in 0..p.len() {
            let kind = p.kind_of(i);
            if kind == Kind::Dummy || kind == Kind::Gate {
                continue;
            }
            let d = [p.x[i] - self.at[0], p.y[i] - self.at[1], p.z[i] - self.at[2]];
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if kind == Kind::Fluid && r < 2.0 * k.re_grad {
                fluid_near += 1;
                if let Some(flags) = flags {
                    let f = flags.get(i).copied().unwrap_or(0);
                    surface_near += usize::from(f != 0);
                    flips += usize::from(self.surface.get(&p.id[i]).is_some_and(|&g| g != f));
                    surface.insert(p.id[i], f);
                }
            }
            let w = weight(r.max(1e-6 * ds), k.re_grad);
            if w <= 0.0 {
                continue;
            }
            if r < nearest.0 {
                nearest = (r, kind, p.pressure[i], p.id[i]);
            }
            if kind == Kind::Fluid {
                (wf, pf) = (wf + w, pf + w * p.pressure[i]);
            } else {
                (ws, ps) = (ws + w, ps + w * p.pressure[i]);
                solid_max = solid_max.max(p.pressure[i]);
            }
        }
        self.surface = surface;
        let total = (wf + ws).max(f64::MIN_POSITIVE);
        let _ = writeln!(
            self.out,
            "{:.6},{:.3e},{:.1},{:.1},{:.1},{:.3},{:?},{},{:.3},{:.1},{:.1},{},{},{}",
            solver.time(),
            dt,
            probe,
            pf / total,
            ps / total,
            ws / total,
            nearest.1,
            nearest.3,
            nearest.0 / ds,
            nearest.2,
            solid_max,
            fluid_near,
            surface_near,
            flips
        );
    }
}
