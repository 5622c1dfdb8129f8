//! Cross-section properties, the elastic section stiffness and the return to the section's
//! full-plastic yield surface (S2 §3; the surfaces are in `yield_function.rs`).

use super::yield_function::YieldFunction;
use nalgebra::{Matrix4, Vector4};
use schemas::case::frame::{MaterialConfig, SectionConfig};

/// Generalised strains and stress resultants are ordered
/// `[axial ε, shear γy, shear γz, twist κx, curvature κy, curvature κz]` and
/// `[N, Qy, Qz, T, My, Mz]`.
pub type Resultants = [f64; 6];

/// Index of N, My and Mz in [`Resultants`]: the components that enter the yield function.
pub const YIELDING: [usize; 3] = [0, 4, 5];

/// Shear coefficient of a solid rectangle (the reference data's value).
const RECTANGLE_SHEAR_COEFFICIENT: f64 = 5.0 / 6.0;

/// Properties of one section made of the frame's material.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Section {
    pub area: f64,
    pub iy: f64,
    pub iz: f64,
    /// Elastic section stiffness `[EA, kGA_y, kGA_z, GJ, EIy, EIz]`.
    pub stiffness: Resultants,
    /// Fully plastic `[N0, My0, Mz0]` = σ_y · (A, Zp_y, Zp_z).
    pub plastic: [f64; 3],
    /// Projected width for drag [m].
    pub width: f64,
    /// Radius of the contact particles: half the larger side (rectangle) or half the width [m].
    pub contact_radius: f64,
    /// The interaction of N, My and Mz at full plasticity.
    pub yield_kind: YieldFunction,
}

/// Largest iterations of each stage of the general return ([`Section::return_to_surface`]).
const RETURN_ITERATIONS: usize = 50;
/// Residual (scaled resultants, f) at which the general return stops.
const RETURN_TOLERANCE: f64 = 1e-13;
/// Bisections that put the trial state's ray on the surface (the start of the general return).
const RADIAL_BISECTIONS: usize = 60;
/// Step of the central differences of the yield function's Hessian, in scaled resultants.
const HESSIAN_STEP: f64 = 1e-4;

impl Section {
    /// Builds a validated section config into properties.
    pub fn new(cfg: &SectionConfig, material: &MaterialConfig) -> Section {
        let e = material.young_modulus;
        let g = e / (2.0 * (1.0 + material.poisson));
        let sy = material.yield_stress;
        let (area, iy, iz, j, asy, asz, zy, zz, width, contact_radius) = match (cfg.width, cfg.depth) {
            (Some(b), Some(h)) if cfg.kind == "rectangle" => {
                let area = b * h;
                let k = RECTANGLE_SHEAR_COEFFICIENT;
                (
                    area,
                    b * h.powi(3) / 12.0,
                    h * b.powi(3) / 12.0,
                    rectangle_torsion_constant(b, h),
                    k * area,
                    k * area,
                    b * h * h / 4.0,
                    h * b * b / 4.0,
                    b,
                    0.5 * b.max(h),
                )
            }
            _ => {
                let v = |x: Option<f64>| x.unwrap_or(0.0);
                let area = v(cfg.area);
                let width = cfg.width.unwrap_or_else(|| area.sqrt());
                (
                    area,
                    v(cfg.iy),
                    v(cfg.iz),
                    v(cfg.j),
                    v(cfg.shear_area_y),
                    v(cfg.shear_area_z),
                    v(cfg.plastic_modulus_y),
                    v(cfg.plastic_modulus_z),
                    width,
                    0.5 * width,
                )
            }
        };
        Section {
            area,
            iy,
            iz,
            stiffness: [e * area, g * asy, g * asz, g * j, e * iy, e * iz],
            plastic: [sy * area, sy * zy, sy * zz],
            width,
            contact_radius,
            yield_kind: YieldFunction::from_name(cfg.yield_function.as_deref()),
        }
    }

    /// The section's full-plastic yield function at these resultants ([`YieldFunction`]).
    pub fn yield_function(&self, n: f64, my: f64, mz: f64) -> f64 {
        let [n0, my0, mz0] = self.plastic;
        self.yield_kind.value(n / n0, my / my0, mz / mz0)
    }

    /// Gradient a = ∂f/∂σ of the yield function in [`Resultants`] order (zero for Q and T).
    pub fn yield_gradient(&self, sigma: &Resultants) -> Resultants {
        let [n0, my0, mz0] = self.plastic;
        if self.yield_kind == YieldFunction::Quadratic {
            // 2 σᵢ / σᵢ0², rounded as before the other surfaces came
            return [
                2.0 * sigma[0] / (n0 * n0),
                0.0,
                0.0,
                0.0,
                2.0 * sigma[4] / (my0 * my0),
                2.0 * sigma[5] / (mz0 * mz0),
            ];
        }
        let [gn, gy, gz] = self
            .yield_kind
            .gradient(sigma[0] / n0, sigma[4] / my0, sigma[5] / mz0);
        [gn / n0, 0.0, 0.0, 0.0, gy / my0, gz / mz0]
    }

    /// Closest-point return of a trial state outside the yield surface (associated flow, backward
    /// Euler): `σᵢ = σᵢ,trial / (1 + 2 Dᵢ Δλ / σᵢ0²)` for N, My, Mz with Δλ ≥ 0 such that f(σ) = 0.
    pub fn return_to_surface(&self, sigma: &mut Resultants) {
        if self.yield_kind != YieldFunction::Quadratic {
            self.return_by_closest_point(sigma);
            return;
        }
        let trial = [sigma[0], sigma[4], sigma[5]];
        let d = [self.stiffness[0], self.stiffness[4], self.stiffness[5]];
        let c2 = self.plastic.map(|c| c * c);
        let at = |lambda: f64| -> (f64, f64) {
            let mut g = -1.0;
            let mut dg = 0.0;
            for i in 0..3 {
                let q = 1.0 + 2.0 * d[i] * lambda / c2[i];
                let x = trial[i] * trial[i] / (c2[i] * q * q);
                g += x;
                dg += -2.0 * x * (2.0 * d[i] / c2[i]) / q;
            }
            (g, dg)
        };
        if at(0.0).0 <= 0.0 {
            return;
        }
        // g(Δλ) is convex and decreasing: Newton from Δλ = 0 approaches the root from below
        let mut lambda = 0.0;
        for _ in 0..100 {
            let (g, dg) = at(lambda);
            if g.abs() < 1e-13 || dg == 0.0 {
                break;
            }
            lambda -= g / dg;
        }
        for (k, i) in YIELDING.into_iter().enumerate() {
            sigma[i] = trial[k] / (1.0 + 2.0 * d[k] * lambda / c2[k]);
        }
    }
}

impl Section {
    /// Closest-point return (associated flow, backward Euler) of a trial state outside one of the
    /// other surfaces: `σ = σ_trial − Δλ D a(σ)`, `f(σ) = 0`, solved by Newton's method on (σ, Δλ)
    /// in scaled resultants with the Hessian of f by central differences of its gradient, damped
    /// (halved while the residual does not fall), from the trial state scaled onto the surface.
    fn return_by_closest_point(&self, sigma: &mut Resultants) {
        let kind = self.yield_kind;
        let scale = self.plastic;
        let trial = [sigma[0] / scale[0], sigma[4] / scale[1], sigma[5] / scale[2]];
        if kind.value(trial[0], trial[1], trial[2]) <= 0.0 {
            return;
        }
        // D in scaled resultants, and its largest entry, which scales Δλ to μ = Δλ · max D
        let d = [0, 4, 5].map(|i| self.stiffness[i]);
        let d = [0, 1, 2].map(|k| d[k] / (scale[k] * scale[k]));
        let d_max = d.iter().fold(0.0_f64, |m, x| m.max(*x));
        let d = d.map(|x| x / d_max);
        if let Some(apex) = self.apex_return(&trial, &d) {
            for (k, i) in YIELDING.into_iter().enumerate() {
                sigma[i] = apex[k] * scale[k];
            }
            return;
        }
        // start: the trial state scaled onto the surface (bisection along the ray from the origin,
        // inside every surface), with the Δλ that fits the flow there best
        let (mut inside, mut outside) = (0.0, 1.0);
        for _ in 0..RADIAL_BISECTIONS {
            let t = 0.5 * (inside + outside);
            if kind.value(t * trial[0], t * trial[1], t * trial[2]) < 0.0 {
                inside = t;
            } else {
                outside = t;
            }
        }
        let mut x = trial.map(|c| inside * c);
        let g = kind.gradient(x[0], x[1], x[2]);
        let flow = [0, 1, 2].map(|k| d[k] * g[k]);
        let flow_norm: f64 = flow.iter().map(|c| c * c).sum();
        let mut mu = if flow_norm > 0.0 {
            (0..3).map(|k| (trial[k] - x[k]) * flow[k]).sum::<f64>() / flow_norm
        } else {
            0.0
        };
        let residual = |x: &[f64; 3], mu: f64| {
            let g = kind.gradient(x[0], x[1], x[2]);
            let mut r = Vector4::zeros();
            for k in 0..3 {
                r[k] = x[k] - trial[k] + mu * d[k] * g[k];
            }
            r[3] = kind.value(x[0], x[1], x[2]);
            r
        };
        for _ in 0..RETURN_ITERATIONS {
            let r = residual(&x, mu);
            if r.amax() < RETURN_TOLERANCE {
                break;
            }
            let g = kind.gradient(x[0], x[1], x[2]);
            let mut j = Matrix4::zeros();
            for c in 0..3 {
                let mut up = x;
                let mut down = x;
                up[c] += HESSIAN_STEP;
                down[c] -= HESSIAN_STEP;
                let (gu, gd) = (
                    kind.gradient(up[0], up[1], up[2]),
                    kind.gradient(down[0], down[1], down[2]),
                );
                for k in 0..3 {
                    j[(k, c)] = mu * d[k] * (gu[k] - gd[k]) / (2.0 * HESSIAN_STEP);
                }
                j[(c, c)] += 1.0;
                j[(c, 3)] = d[c] * g[c];
                j[(3, c)] = g[c];
            }
            let Some(dy) = j.lu().solve(&r) else {
                break;
            };
            // damped: halve the Newton step while it does not reduce the residual
            let mut step = 1.0;
            loop {
                let trial_x = [0, 1, 2].map(|k| x[k] - step * dy[k]);
                let trial_mu = mu - step * dy[3];
                if residual(&trial_x, trial_mu).norm() < r.norm() || step < 1e-6 {
                    (x, mu) = (trial_x, trial_mu);
                    break;
                }
                step *= 0.5;
            }
        }
        for (k, i) in YIELDING.into_iter().enumerate() {
            sigma[i] = x[k] * scale[k];
        }
    }
}

impl Section {
    /// The apex `(sign n, 0, 0)` (scaled) when it is the closest point of the plastic set to a
    /// scaled trial state beyond the squash load (`d` the scaled stiffnesses of N, My, Mz): its
    /// normal cone holds `w = D⁻¹ (trial − apex)` ([`YieldFunction::apex_support`]).
    fn apex_return(&self, trial: &[f64; 3], d: &[f64; 3]) -> Option<[f64; 3]> {
        if trial[0].abs() <= 1.0 {
            return None;
        }
        let sign = trial[0].signum();
        let outward = (trial[0] - sign) * sign / d[0];
        let support = self.yield_kind.apex_support(trial[1] / d[1], trial[2] / d[2])?;
        (support <= outward).then_some([sign, 0.0, 0.0])
    }

    /// Whether `sigma` sits at the apex of the surface (the squash load, no moment), where a
    /// hinge carries no increment of N, My or Mz (the return keeps a trial state in the apex's
    /// normal cone there): set exactly by [`Section::apex_return`].
    pub fn at_apex(&self, sigma: &Resultants) -> bool {
        self.yield_kind != YieldFunction::Quadratic
            && sigma[4] == 0.0
            && sigma[5] == 0.0
            && sigma[0].abs() == self.plastic[0]
    }
}

/// Saint-Venant torsion constant of a solid rectangle, `J = a b³ (1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴)))`
/// with a ≥ b (Roark's Formulas, table 10.7).
fn rectangle_torsion_constant(w: f64, h: f64) -> f64 {
    let (a, b) = if w >= h { (w, h) } else { (h, w) };
    a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))))
}
