//! The physical parameters of a fluid participant, shared by both methods.

/// ρ0, ν, g and (E-MPS only) the sound speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Physics {
    /// ρ0 [kg/m³].
    pub density: f64,
    /// ν [m²/s].
    pub viscosity: f64,
    /// Whether ν∇²u is computed (S1-10, S2-3).
    pub viscosity_term: bool,
    /// g [m/s²].
    pub gravity: [f64; 3],
    /// c [m/s] (S1-16; E-MPS only, ISPH has no sound speed).
    pub sound_speed: f64,
}

impl Physics {
    /// Whether the viscous term is computed at all (on, and ν > 0).
    pub fn viscous(&self) -> bool {
        self.viscosity_term && self.viscosity > 0.0
    }
}
