//! Cross-section properties, the elastic section stiffness and the full-plastic yield function (S2 §3).

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
#[derive(Debug, Clone)]
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
}

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
        }
    }

    /// Full-plastic interaction yield function `f = (N/N0)² + (My/My0)² + (Mz/Mz0)² − 1`
    /// (physics.md §5; torsion does not enter).
    pub fn yield_function(&self, n: f64, my: f64, mz: f64) -> f64 {
        let [n0, my0, mz0] = self.plastic;
        (n / n0).powi(2) + (my / my0).powi(2) + (mz / mz0).powi(2) - 1.0
    }

    /// Gradient a = ∂f/∂σ of the yield function in [`Resultants`] order (zero for Q and T).
    pub fn yield_gradient(&self, sigma: &Resultants) -> Resultants {
        let [n0, my0, mz0] = self.plastic;
        [
            2.0 * sigma[0] / (n0 * n0),
            0.0,
            0.0,
            0.0,
            2.0 * sigma[4] / (my0 * my0),
            2.0 * sigma[5] / (mz0 * mz0),
        ]
    }

    /// Closest-point return of a trial state outside the yield surface (associated flow, backward
    /// Euler): `σᵢ = σᵢ,trial / (1 + 2 Dᵢ Δλ / σᵢ0²)` for N, My, Mz with Δλ ≥ 0 such that f(σ) = 0.
    pub fn return_to_surface(&self, sigma: &mut Resultants) {
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

/// Saint-Venant torsion constant of a solid rectangle, `J = a b³ (1/3 − 0.21 (b/a)(1 − b⁴/(12 a⁴)))`
/// with a ≥ b (Roark's Formulas, table 10.7).
fn rectangle_torsion_constant(w: f64, h: f64) -> f64 {
    let (a, b) = if w >= h { (w, h) } else { (h, w) };
    a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))))
}
