//! `[fluid.NAME.isph]`: the settings of the ISPH method (Ohinata et al., S2).

use crate::case::error::check;
use crate::case::FieldError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How ISPH walls act on the velocity tangential to them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WallSlip {
    /// Slip rate 1.0 (S2, Table 1): walls take no part in the viscous term.
    #[default]
    FreeSlip,
    /// Walls and bodies enter the viscous term with their own velocity.
    NoSlip,
}

/// Which solver the ISPH pressure Poisson equation uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PpeSolver {
    /// Jacobi-preconditioned conjugate gradient on the neighbour list, warm-started from the last
    /// pressure (the default until the two-level one was measured faster: docs/notes/isph-ppe-preconditioner.md).
    JacobiPcg,
    /// faer's sparse Cholesky factorisation of the assembled matrix, every step.
    FaerCholesky,
    /// Conjugate gradient preconditioned by symmetric Gauss–Seidel within fixed blocks of rows
    /// (block Jacobi between them), warm-started from the last pressure.
    SgsPcg,
    /// Conjugate gradient preconditioned by a two-level V(1,1) cycle: damped Jacobi smoothing and
    /// an exact coarse correction on aggregates of neighbour-search cells, warm-started from the
    /// last pressure (the default until the additive form was measured faster).
    TwoLevelPcg,
    /// Conjugate gradient preconditioned by Jacobi plus the same coarse correction, added
    /// (`D⁻¹ + P A_c⁻¹ Pᵀ`), warm-started from the last pressure: more iterations than the cycle,
    /// a third of its products with the matrix each (the fastest measured, before and after a dam
    /// break's impact: docs/notes/isph-ppe-preconditioner.md).
    #[default]
    AdditiveTwoLevelPcg,
}

/// The pressure gradient of ISPH's momentum equation (see
/// `fluid_solver::isph::operators::pressure_gradient` for both equations and the measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PressureGradient {
    /// S2-8's difference form `Σ_j V (p_j − p_i) ∇W_ij` corrected by the moment matrix (Bonet &
    /// Lok 1999), the seed's own; bodies loaded by the face law of
    /// `fluid_solver::isph::pair_laws::body_faces`. Its pair terms do not cancel, so momentum does
    /// not close (kept by name to compare with S2).
    CorrectedDifference,
    /// The uncorrected symmetric form `Σ_j V (p_i + p_j) ∇W_ij` (walls `V (2p_i + Δp_ij) ∇W_ij`),
    /// whose pair term is also the walls' load; with a body neighbour the pair term is the body's
    /// face-law share: momentum closes pair by pair. Accepted only with `influence_radius` in
    /// [`SYMMETRIC_SUPPORT`]; measured to hold the hydrostatic tank at 2.0 (docs/notes/isph-symmetric-gradient-and-shifting.md).
    Symmetric,
    /// The symmetric form of `"symmetric"` with the pressure Poisson equation built from it: the
    /// PPE's divergence is the adjoint of the gradient (`D = −Gᵀ`) and its matrix is `GᵀG`, so
    /// the projection removes the divergence it measures and the pressure force is
    /// antisymmetric pair by pair; the lattice's checkerboard, which `G` does not see, is held by
    /// a small share of S2-9's Laplacian (`fluid_solver::isph::exact_projection`). A body
    /// completes the kernel sums of the water beside it (`fluid_solver::isph::body_completion`),
    /// so its load does not depend on where it stands on the lattice. Accepted with
    /// `influence_radius` in [`SYMMETRIC_SUPPORT`], as `"symmetric"`. The default.
    #[default]
    Conservative,
}

impl PressureGradient {
    /// Whether the fluid's gradient is the symmetric form (`"symmetric"` and `"conservative"`).
    pub fn is_symmetric(self) -> bool {
        matches!(self, PressureGradient::Symmetric | PressureGradient::Conservative)
    }
}

/// The kernel-gradient correction of ISPH's symmetric forms (`fluid_solver::isph::kernel_correction`
/// has the equation and the measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum KernelCorrection {
    /// Each pair's term takes the plain kernel gradient `V ∇W_ij`.
    None,
    /// Each pair's kernel gradient is corrected by the moment matrices of both particles,
    /// `½ (L_i + L_j) V ∇W_ij` (a solid's `L_i V ∇W_iw`), `L = m⁻¹` in the water's interior
    /// away from bodies (neither the particle nor a fluid neighbour on the free surface or beside
    /// a body, λ_min > 0.9) and the
    /// identity elsewhere: the pair terms stay antisymmetric, so momentum still closes, and a
    /// hydrostatic pressure is read without the sideways force that a sheared lattice gives the
    /// plain form (a standing wave kept 0.76 A at its first swing with it, 0.98 A corrected).
    /// Only with the symmetric forms (`pressure_gradient = "symmetric"` or `"conservative"`).
    Moment,
}

/// Particle shifting of ISPH (`fluid_solver::isph::shifting` has the equation, the
/// free-surface and wall treatment and the measurements).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shifting {
    /// Particles move with their velocity only.
    #[default]
    Off,
    /// Lind, Xu, Stansby & Rogers (2012): `δr = −D Σ_j V ∇W_ij` after each position update, with
    /// `D = A h |u|_max Δt` after Skillen et al. (2013) (A = `shifting_coefficient`); the water
    /// in a resolved body's support is not shifted. Smoothest with `pressure_gradient =
    /// "symmetric"` at `influence_radius = 2.0` (docs/notes/isph-settings-at-a-glance.md).
    Lind,
}

/// `[fluid.NAME.isph]`: settings of the ISPH method (all optional).
///
/// ```toml
/// [fluid.tank.isph]
/// alpha_d = 5e-3            # α_d of S2-5 (density relaxation)
/// influence_radius = 2.0    # kernel support in spacings (by default 2.0; 2.4 with "corrected-difference", S2 Table 1)
/// ppe_tolerance = 1e-6      # relative residual |r|/|b| the PPE must reach every step
/// ppe_max_iterations = 1000 # beyond this the run stops with the residual
/// ppe_solver = "additive-two-level-pcg" # or "two-level-pcg", "jacobi-pcg", "faer-cholesky", "sgs-pcg"
/// wall_slip = "free-slip"   # or "no-slip"
/// pressure_gradient = "conservative" # or "corrected-difference" (S2-8), "symmetric"
/// shifting = "off"          # or "lind" (particle shifting)
/// kernel_correction = "moment" # or "none": the symmetric forms' pairs corrected by the moment matrices, or plain (by default "moment" with "conservative")
/// shifting_coefficient = 0.5 # A of D = A h |u|_max Δt (Skillen et al. 2013), with "lind"
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct IsphConfig {
    /// α_d of S2-5, the relaxation of the density towards ρ0 [–]. Range: [0, 1].
    #[serde(default = "default_alpha_d")]
    pub alpha_d: f64,
    /// Kernel support in spacings [Δs]: by default 2.4 with `pressure_gradient =
    /// "corrected-difference"` (S2, Table 1) and 2.0 with `"symmetric"` or `"conservative"`
    /// ([`IsphConfig::support`]). Range: [1.5, wall_layers − 0.5]; [1.95, 2.15] with
    /// `"symmetric"` or `"conservative"`.
    #[serde(default)]
    pub influence_radius: Option<f64>,
    /// Relative residual |r|/|b| the pressure Poisson equation must reach every step [–].
    /// Range: (0, 1).
    #[serde(default = "default_ppe_tolerance")]
    pub ppe_tolerance: f64,
    /// Iterations of the PPE solver per step; beyond them the run stops with the residual.
    /// Range: ≥ 1.
    #[serde(default = "default_ppe_max_iterations")]
    pub ppe_max_iterations: u32,
    #[serde(default)]
    pub ppe_solver: PpeSolver,
    #[serde(default)]
    pub wall_slip: WallSlip,
    #[serde(default)]
    pub pressure_gradient: PressureGradient,
    #[serde(default)]
    pub shifting: Shifting,
    /// The symmetric forms' kernel-gradient correction: by default `"moment"` with
    /// `pressure_gradient = "conservative"` and `"none"` with `"symmetric"` (the option as it was
    /// measured) and `"corrected-difference"` ([`IsphConfig::kernel_correction`]).
    #[serde(default)]
    pub kernel_correction: Option<KernelCorrection>,
    /// A of `D = A h |u|_max Δt` (Skillen et al. 2013) [–], read with `shifting = "lind"`.
    /// Range: (0, 6].
    #[serde(default = "default_shifting_coefficient")]
    pub shifting_coefficient: f64,
}

/// The kernel supports (spacings) at which `pressure_gradient = "symmetric"` is accepted: where
/// a column or a plane of the particle lattice sliding along itself is pushed back by the
/// symmetric form's zero-order term (both lattice sums κ ≥ 0.02 /Δs²,
/// `fluid-solver/tests/isph_lattice_modes.rs`; the tank held at 2.0, failed at 2.4 and 3.0).
pub const SYMMETRIC_SUPPORT: (f64, f64) = (1.95, 2.15);

impl Default for IsphConfig {
    fn default() -> IsphConfig {
        IsphConfig {
            alpha_d: default_alpha_d(),
            influence_radius: None,
            ppe_tolerance: default_ppe_tolerance(),
            ppe_max_iterations: default_ppe_max_iterations(),
            ppe_solver: PpeSolver::default(),
            wall_slip: WallSlip::default(),
            pressure_gradient: PressureGradient::default(),
            shifting: Shifting::default(),
            kernel_correction: None,
            shifting_coefficient: default_shifting_coefficient(),
        }
    }
}

fn default_alpha_d() -> f64 {
    5.0e-3
}
fn default_ppe_tolerance() -> f64 {
    1.0e-6
}
fn default_ppe_max_iterations() -> u32 {
    1000
}
/// A in `D = A h |u|_max Δt` (Skillen, Lind, Stansby & Rogers 2013, Comput. Methods Appl. Mech.
/// Engrg. 265, 163–173, who used A = 2 with each particle's own |u|): measured on the L/20 dam
/// break with the symmetric gradient at 2.0 Δs (docs/notes/isph-symmetric-gradient-and-shifting.md), A = 2 and 6 were stopped by the detector (at 0.29 and 0.06 s), 1 and 0.5 ran to
/// 0.6 s with the same probe roughness; 0.5 keeps a margin of 4 from the first failure.
fn default_shifting_coefficient() -> f64 {
    0.5
}

/// Largest `shifting_coefficient`: the top of the range 1 … 6 Skillen et al. (2013) tried.
pub const MAX_SHIFTING_COEFFICIENT: f64 = 6.0;

impl IsphConfig {
    /// The kernel support in spacings: `influence_radius`, or by default 2.4 with S2-8's
    /// gradient (S2, Table 1) and 2.0 with the symmetric ones, the middle of
    /// [`SYMMETRIC_SUPPORT`].
    pub fn support(&self) -> f64 {
        self.influence_radius.unwrap_or(match self.pressure_gradient {
            PressureGradient::CorrectedDifference => 2.4,
            PressureGradient::Symmetric | PressureGradient::Conservative => 2.0,
        })
    }

    /// The kernel correction: `kernel_correction`, or by default `"moment"` with the exact
    /// projection, none with `"symmetric"` (the option as measured before the correction) and
    /// with S2-8's gradient (corrected by its own moment matrix).
    pub fn kernel_correction(&self) -> KernelCorrection {
        self.kernel_correction.unwrap_or(match self.pressure_gradient {
            PressureGradient::Conservative => KernelCorrection::Moment,
            PressureGradient::CorrectedDifference | PressureGradient::Symmetric => KernelCorrection::None,
        })
    }

    /// Checks every key; `key` is the section's dotted path.
    pub fn validate(&self, key: &str, wall_layers: u32) -> Result<(), FieldError> {
        let k = |s: &str| format!("{key}.{s}");
        check::non_negative(&k("alpha_d"), self.alpha_d)?;
        if self.alpha_d > 1.0 {
            return Err(FieldError::new(
                k("alpha_d"),
                format!("must be in [0, 1], got {}", self.alpha_d),
            ));
        }
        let layers = f64::from(wall_layers);
        let support = self.support();
        if !(support >= 1.5 && support <= layers - 0.5) {
            return Err(FieldError::new(
                k("influence_radius"),
                format!(
                    "must be in [1.5, wall_layers − 0.5 = {}] spacings (a fluid particle half a spacing off a wall must see only wall particles behind it), got {}",
                    layers - 0.5,
                    support
                ),
            ));
        }
        let (lo, hi) = SYMMETRIC_SUPPORT;
        if self.pressure_gradient.is_symmetric() && !(support >= lo && support <= hi) {
            return Err(FieldError::new(
                k("influence_radius"),
                format!(
                    "must be in [{lo}, {hi}] spacings with pressure_gradient = \"symmetric\" or \"conservative\" (outside it a sliding column or plane of particles is not pushed back and a tank at rest comes apart: at S2's 2.4 the 1 s tank's edge columns rose at 0.12 m/s), got {}; set influence_radius = 2.0 (or leave it out) or use pressure_gradient = \"corrected-difference\"",
                    support
                ),
            ));
        }
        if self.kernel_correction() == KernelCorrection::Moment && !self.pressure_gradient.is_symmetric() {
            return Err(FieldError::new(
                k("kernel_correction"),
                "\"moment\" corrects the symmetric forms' pairs, and pressure_gradient = \"corrected-difference\" is corrected by its own moment matrix already; leave kernel_correction out (or \"none\") with it, or use pressure_gradient = \"conservative\" or \"symmetric\"",
            ));
        }
        if !(self.ppe_tolerance > 0.0 && self.ppe_tolerance < 1.0) {
            return Err(FieldError::new(
                k("ppe_tolerance"),
                format!("must be in (0, 1), got {}", self.ppe_tolerance),
            ));
        }
        if self.ppe_max_iterations == 0 {
            return Err(FieldError::new(k("ppe_max_iterations"), "must be at least 1"));
        }
        if !(self.shifting_coefficient > 0.0 && self.shifting_coefficient <= MAX_SHIFTING_COEFFICIENT) {
            return Err(FieldError::new(
                k("shifting_coefficient"),
                format!(
                    "must be in (0, {MAX_SHIFTING_COEFFICIENT}] (A of D = A h |u|_max Δt, Skillen et al. 2013), got {}",
                    self.shifting_coefficient
                ),
            ));
        }
        Ok(())
    }
}
