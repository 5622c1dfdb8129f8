//! Full-plastic interaction of the axial force and the two bending moments of a section (S2 §3,
//! docs/physics.md §5), in the resultants scaled by their fully plastic values, n = N/N0, my = My/My0,
//! mz = Mz/Mz0; torsion and shear do not enter. `f < 0` inside, `f = 0` on the surface. The flow at
//! a hinge is normal to the chosen surface (`a = ∂f/∂σ`, [`YieldFunction::gradient`]).

/// Exponent of the biaxial moment term of [`YieldFunction::Rectangle`]. The exact fully plastic
/// states of a solid rectangle (stress ±σy on either side of a straight neutral axis, integrated on
/// a 400 × 400 grid at axis angles 0°…90° and axial shares 0 and 0.2–0.26) lie at most 1.7 % of
/// the moment outside this surface and on it where one moment is zero; an exponent of 2 overstates
/// the capacity by up to 5.7 % (at 45° and n = 0 the exact moments are 0.667 of Mp, the circle
/// gives 0.707).
const RECTANGLE_BIAXIAL_EXPONENT: f64 = 1.7;

/// Step of the central differences of the I section's gradient, in scaled resultants: ε^(1/3), where
/// truncation and round-off errors (both ~ε^(2/3) ≈ 4e-11) balance.
const GRADIENT_STEP: f64 = 6e-6;

/// Coefficients of the I section's capacities next to the squash load, per unit of t = 1 − |n|:
/// strong axis `1.18 t`, weak axis `1.19 (1 − n²) → 2.38 t` (see [`YieldFunction::ISection`]).
const I_SECTION_APEX_SLOPES: [f64; 2] = [1.18, 2.38];

/// Golden-section steps of the I section's apex support (interval 0.618ⁿ: 1e-16 after 77).
const APEX_SEARCH_STEPS: usize = 80;

/// Which interaction a section yields by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum YieldFunction {
    /// The solid rectangle's exact `|m| + n² = 1` about either axis, biaxial
    /// `(|my|^1.7 + |mz|^1.7)^(1/1.7) + n² − 1` (see [`RECTANGLE_BIAXIAL_EXPONENT`]).
    Rectangle,
    /// A wide-flange I section with its web along local z: `|my| ≤ 1.18 (1 − |n|)` (strong axis)
    /// and `|mz| ≤ 1.19 (1 − n²)` (weak axis), each capped at 1 (Chen & Atsuta, Theory of
    /// Beam-Columns, 1976: the plastic-design formulas for W shapes), biaxial
    /// `(my/νy)² + (|mz|/νz)^max(1, 5|n|) − 1` with the exponents of EN 1993-1-1 §6.2.9.1(6).
    ISection,
    /// `n² + my² + mz² − 1` (the form S2 and docs/physics.md §5 write): 0.866 Mp at n = 0.5 where a
    /// solid rectangle carries 0.75 Mp and an I section about 0.59 Mp.
    Quadratic,
}

impl YieldFunction {
    /// From a section's `yield_function` (validated), `"rectangle"` when absent.
    pub fn from_name(name: Option<&str>) -> YieldFunction {
        match name {
            Some("i_section") => YieldFunction::ISection,
            Some("quadratic") => YieldFunction::Quadratic,
            _ => YieldFunction::Rectangle,
        }
    }

    /// `f(n, my, mz)` in scaled resultants.
    pub fn value(self, n: f64, my: f64, mz: f64) -> f64 {
        match self {
            YieldFunction::Quadratic => n * n + my * my + mz * mz - 1.0,
            YieldFunction::Rectangle => {
                let p = RECTANGLE_BIAXIAL_EXPONENT;
                (my.abs().powf(p) + mz.abs().powf(p)).powf(1.0 / p) + n * n - 1.0
            }
            YieldFunction::ISection => {
                let beyond = n.abs();
                let n = beyond.min(1.0);
                let strong = (1.18 * (1.0 - n)).min(1.0);
                let weak = (1.19 * (1.0 - n * n)).min(1.0);
                if strong <= 0.0 || weak <= 0.0 {
                    // |N| ≥ N0: no moment is left; zero at the apex, growing with the moments and
                    // the axial force beyond the squash load
                    return my * my + mz * mz + beyond - 1.0;
                }
                (my / strong).powi(2) + (mz.abs() / weak).powf((5.0 * n).max(1.0)) - 1.0
            }
        }
    }

    /// The surface's apex at the squash load (|n| = 1, no moment), where its normal is not unique:
    /// the support function h(wy, wz) = max (wy my + wz mz) over the moments the section carries at
    /// |n| = 1 − t, per unit of t, as t → 0. The apex is the closest point (in the energy norm) of a
    /// trial state with `w = D⁻¹ (σ_trial − σ_apex)` iff `h(wy, wz) ≤ sign(n) wn` (w in the normal
    /// cone: the polar of the surface's tangent cone there). `None` for [`YieldFunction::Quadratic`],
    /// smooth at n = ±1.
    /// - rectangle: `|m|_p ≤ 1 − n² → 2t`, so h = 2 ‖w‖_q, 1/p + 1/q = 1 (the dual norm);
    /// - I section: `(my/1.18t)² + (|mz|/2.38t)⁵ ≤ 1`, so h = max over b ∈ [0, 1] of
    ///   `1.18 |wy| √(1 − b⁵) + 2.38 |wz| b` (concave in b: a golden-section search).
    pub fn apex_support(self, wy: f64, wz: f64) -> Option<f64> {
        match self {
            YieldFunction::Quadratic => None,
            YieldFunction::Rectangle => {
                let q = RECTANGLE_BIAXIAL_EXPONENT / (RECTANGLE_BIAXIAL_EXPONENT - 1.0);
                Some(2.0 * (wy.abs().powf(q) + wz.abs().powf(q)).powf(1.0 / q))
            }
            YieldFunction::ISection => {
                let [sy, sz] = I_SECTION_APEX_SLOPES;
                let along = |b: f64| sy * wy.abs() * (1.0 - b.powi(5)).max(0.0).sqrt() + sz * wz.abs() * b;
                let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
                let (mut lo, mut hi) = (0.0, 1.0);
                for _ in 0..APEX_SEARCH_STEPS {
                    let (b1, b2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
                    if along(b1) < along(b2) {
                        lo = b1;
                    } else {
                        hi = b2;
                    }
                }
                Some(along(0.5 * (lo + hi)).max(along(0.0)).max(along(1.0)))
            }
        }
    }

    /// `∂f/∂(n, my, mz)`: exact for [`YieldFunction::Quadratic`] and [`YieldFunction::Rectangle`]
    /// (zero moment slope where both moments are zero), central differences for
    /// [`YieldFunction::ISection`] (whose caps and exponent make kinks, where either side's slope
    /// is as good).
    pub fn gradient(self, n: f64, my: f64, mz: f64) -> [f64; 3] {
        match self {
            YieldFunction::Quadratic => return [2.0 * n, 2.0 * my, 2.0 * mz],
            YieldFunction::Rectangle => {
                let p = RECTANGLE_BIAXIAL_EXPONENT;
                let r = (my.abs().powf(p) + mz.abs().powf(p)).powf(1.0 / p);
                let slope = |m: f64| {
                    if r > 0.0 {
                        m.signum() * (m.abs() / r).powf(p - 1.0)
                    } else {
                        0.0
                    }
                };
                return [2.0 * n, slope(my), slope(mz)];
            }
            YieldFunction::ISection => {}
        }
        let h = GRADIENT_STEP;
        let d = |dn: f64, dy: f64, dz: f64| {
            (self.value(n + dn, my + dy, mz + dz) - self.value(n - dn, my - dy, mz - dz)) / (2.0 * h)
        };
        [d(h, 0.0, 0.0), d(0.0, h, 0.0), d(0.0, 0.0, h)]
    }
}
