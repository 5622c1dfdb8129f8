//! Inflow and outflow boundaries on the device, the GPU path of
//! [`crate::boundaries::open_boundary`] (`shaders/open_boundary.wgsl`).
//!
//! The host keeps a copy of the inflow strip (its particles only, a few rows of sites) and runs
//! the CPU's own [`OpenBoundaries::apply`] on it before each step, in f64: so the strip's travel,
//! the rows it inserts and withdraws, the ids it gives them and the balance's `inserted`,
//! `entered` and `withdrawn` are the CPU's exactly. From that copy the host hands the device a
//! few numbers ([`OpenPass`]): the strip's velocity and travel, the x from which a strip particle
//! becomes fluid and the z above which one is withdrawn (each half-way between the copy's strip
//! particles that do and those that do not, so the device's f32 positions decide as the f64
//! ones do: the strip's layers are a spacing apart, its rows too; a layer that lands on the
//! plane enters whole, [`crate::boundaries::open_boundary::PLANE_SLACK`]), and the outflow plane. The
//! device's pass converts, withdraws, moves the strip and marks the fluid past the outflow plane,
//! counting each; only these three counts come back (12 B). When it removed any, a cell sort
//! closes the gaps (`shaders/cell_sort.wgsl`: removed particles are counted in no cell and land
//! past the others, which the device then drops). The new rows the copy inserted are appended to
//! the device's arrays (44 B each: position and kind, velocity, id, density and pressure); with
//! an inflow the arrays are made with room for more particles, and regrown (by half) when full.
//! The balance's `removed` is the device's count.

use crate::boundaries::open_boundary::OpenBoundaries;
use crate::particles::kind::Kind;
use crate::particles::Particles;

/// What the device's pass needs for one step (see the module doc); `f64::INFINITY`: nothing of
/// that kind this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpenPass {
    /// The strip's velocity u(t + Δt/2) and its travel u Δt over the step.
    pub u: f64,
    pub dx: f64,
    /// Strip particles at x ≥ `enter` become fluid.
    pub enter: f64,
    /// Strip particles (that stay strip) at z > `cut` are withdrawn.
    pub cut: f64,
    /// Fluid at x > `outflow` is removed.
    pub outflow: f64,
}

/// One step's open boundaries as the host's copy of the strip has them.
#[derive(Debug, Clone)]
pub struct OpenPlan {
    pub pass: OpenPass,
    /// The rows the strip inserted (and kept) this step, to append on the device.
    pub rows: Particles,
    /// Strip particles of the device that must become fluid, and be withdrawn.
    pub entered: u64,
    pub withdrawn: u64,
}

/// The host's copy of the inflow strip.
#[derive(Debug, Clone, Default)]
pub struct StripCopy {
    strip: Particles,
    spacing: f64,
}

impl StripCopy {
    /// The strip particles of `p`, on a lattice of `spacing`.
    pub fn of(p: &Particles, spacing: f64) -> StripCopy {
        let keep: Vec<u32> = (0..p.len() as u32)
            .filter(|&i| p.kind[i as usize] == Kind::Inflow.code())
            .collect();
        StripCopy {
            strip: p.subset(&keep),
            spacing,
        }
    }

    /// Strip particles in the copy.
    pub fn len(&self) -> usize {
        self.strip.len()
    }

    /// True when the strip is empty.
    pub fn is_empty(&self) -> bool {
        self.strip.is_empty()
    }

    /// Runs the boundaries' part of the step from `t` to `t + dt` on the copy (updating `open`'s
    /// strip and balance as the CPU step does, its `removed` aside) and says what the device must
    /// do. The rule keeps the order of the particles it keeps and appends its new rows with ids
    /// past every existing one, so one walk along the copy before and after it pairs each
    /// particle with its past (an error, which stops the run, if it ever did not).
    pub fn plan(&mut self, open: &mut OpenBoundaries, t: f64, dt: f64) -> Result<OpenPlan, String> {
        let s = &mut self.strip;
        let before: Vec<(u32, f64, f64)> = (0..s.len()).map(|i| (s.id[i], s.x[i], s.z[i])).collect();
        let newest = before.iter().map(|b| b.0).max();
        let removed = open.balance().removed;
        open.apply(s, t, dt);
        // the copy holds no fluid but what entered this step, which lies short of the outflow
        // plane (validated downstream of the inflow plane) unless it travels past it in one step
        debug_assert_eq!(open.balance().removed, removed);
        let (mut crossed, mut stay_x) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut kept_z, mut gone_z) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut entered, mut withdrawn, mut u) = (0, 0, 0.0);
        let mut fresh = Vec::new();
        // `next`: the first particle of `before` not yet paired; those skipped were withdrawn
        let mut next = 0;
        for i in 0..s.len() {
            if newest.is_none_or(|m| s.id[i] > m) {
                fresh.push(i as u32);
                u = s.vx[i];
                continue;
            }
            let Some(k) = before[next..].iter().position(|b| b.0 == s.id[i]) else {
                return Err(format!(
                    "the host's copy of the inflow strip lost particle {}'s order",
                    s.id[i]
                ));
            };
            for &(_, x, z) in &before[next..next + k] {
                withdrawn += 1;
                gone_z = gone_z.min(z);
                stay_x = stay_x.max(x);
            }
            let (_, x, z) = before[next + k];
            next += k + 1;
            if s.kind[i] == Kind::Fluid.code() {
                crossed = crossed.min(x);
                entered += 1;
            } else {
                stay_x = stay_x.max(x);
                kept_z = kept_z.max(z);
                u = s.vx[i];
            }
        }
        for &(_, x, z) in &before[next..] {
            withdrawn += 1;
            gone_z = gone_z.min(z);
            stay_x = stay_x.max(x);
        }
        let half = 0.5 * self.spacing;
        let between = |lo: f64, hi: f64| match (lo.is_finite(), hi.is_finite()) {
            (_, false) => f64::INFINITY,
            (true, true) => 0.5 * (lo + hi),
            (false, true) => hi - half,
        };
        let rows = s.subset(&fresh);
        s.remove_kind(Kind::Fluid);
        Ok(OpenPlan {
            pass: OpenPass {
                u,
                dx: u * dt,
                enter: between(stay_x, crossed),
                cut: between(kept_z, gone_z),
                outflow: open.outflow_plane().unwrap_or(f64::INFINITY),
            },
            rows,
            entered,
            withdrawn,
        })
    }
}
