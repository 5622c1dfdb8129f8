//! Fracture of a fully plastic section (S2-17).

use super::section::Resultants;
use schemas::case::frame::MaterialConfig;

/// Critical strains of S2-17; a term whose critical value is not given is left out.
#[derive(Debug, Clone, Copy)]
pub struct FractureCriterion {
    /// `[axial ε, γy, γz, twist (never checked), κy, κz]`; infinity where not checked.
    critical: Resultants,
}

impl FractureCriterion {
    /// The criterion from the material's optional `fracture_*` keys; `None` when none is given.
    pub fn new(material: &MaterialConfig) -> Option<FractureCriterion> {
        let inf = f64::INFINITY;
        let [ky, kz] = material.fracture_curvature.unwrap_or([inf, inf]);
        let [gy, gz] = material.fracture_shear_strain.unwrap_or([inf, inf]);
        let ea = material.fracture_axial_strain.unwrap_or(inf);
        let critical = [ea, gy, gz, inf, ky, kz];
        critical
            .iter()
            .any(|c| c.is_finite())
            .then_some(FractureCriterion { critical })
    }

    /// S2-17: `(χy/χy_c)² + (χz/χz_c)² + (ε/ε_c)² + (γy/γy_c)² + (γz/γz_c)² ≥ 1`.
    pub fn is_reached(&self, strain: &Resultants) -> bool {
        strain
            .iter()
            .zip(&self.critical)
            .map(|(e, c)| (e / c).powi(2))
            .sum::<f64>()
            >= 1.0
    }
}
