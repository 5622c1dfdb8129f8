//! [`SolitaryWave`]: the first-order (Boussinesq) solitary wave of height H on still water of
//! depth d, travelling along +x:
//!
//! - η(x, t) = H sech²(k (x − c t − x₀)), with k = √(3H / (4d³)) and c = √(g (d + H)) — the
//!   profile and celerity Goring (1978, Caltech report KH-R-38, §2) generates with a piston;
//!   Synolakis (1987, J. Fluid Mech. 185) writes the same k as γ/d with γ = √(3H / (4d));
//! - the depth-averaged velocity u = c η / (d + η), from mass conservation in the frame of the
//!   wave (∂η/∂t + ∂(u (d + η))/∂x = 0 with η and u functions of x − c t; Goring 1978, §2).
//!
//! It is the wave a [`super::goring::GoringSolitary`] paddle makes, and the reference the tests of a
//! generated wave compare against. x is measured from the paddle's rest position, into the tank.

/// The Boussinesq solitary wave of height H on depth d under gravity g, crest at x₀ when t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolitaryWave {
    height: f64,
    depth: f64,
    gravity: f64,
    crest_x0: f64,
    wavenumber: f64,
    celerity: f64,
}

impl SolitaryWave {
    /// The wave of `height` H (m) on `depth` d (m) under `gravity` g (m/s²), crest at x = 0 at
    /// t = 0; refuses values that are not finite and > 0.
    pub fn new(height: f64, depth: f64, gravity: f64) -> Result<Self, String> {
        for (name, v) in [
            ("wave height H", height),
            ("depth d", depth),
            ("gravity g", gravity),
        ] {
            if !v.is_finite() || v <= 0.0 {
                return Err(format!(
                    "the solitary wave's {name} must be finite and > 0, got {v}"
                ));
            }
        }
        Ok(Self {
            height,
            depth,
            gravity,
            crest_x0: 0.0,
            wavenumber: (3.0 * height / (4.0 * depth.powi(3))).sqrt(),
            celerity: (gravity * (depth + height)).sqrt(),
        })
    }

    /// The same wave with its crest at x = `x0` when t = 0.
    pub fn with_crest_at(self, x0: f64) -> Self {
        Self { crest_x0: x0, ..self }
    }

    /// H, m.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// d, m.
    pub fn depth(&self) -> f64 {
        self.depth
    }

    /// g, m/s².
    pub fn gravity(&self) -> f64 {
        self.gravity
    }

    /// x₀: the crest's position at t = 0, m.
    pub fn crest_x0(&self) -> f64 {
        self.crest_x0
    }

    /// k = √(3H / (4d³)), 1/m (Goring 1978, §2; γ/d in Synolakis 1987).
    pub fn wavenumber(&self) -> f64 {
        self.wavenumber
    }

    /// c = √(g (d + H)), m/s (the celerity of Goring 1978, §2).
    pub fn celerity(&self) -> f64 {
        self.celerity
    }

    /// The phase θ = k (x − c t − x₀) at (x, t).
    pub fn phase(&self, x: f64, t: f64) -> f64 {
        self.wavenumber * (x - self.celerity * t - self.crest_x0)
    }

    /// η(x, t) = H sech²(k (x − c t − x₀)), m.
    pub fn elevation(&self, x: f64, t: f64) -> f64 {
        self.height * sech_squared(self.phase(x, t))
    }

    /// u(x, t) = c η / (d + η), m/s: the depth-averaged horizontal velocity under the wave.
    pub fn depth_averaged_velocity(&self, x: f64, t: f64) -> f64 {
        self.velocity_under(self.elevation(x, t))
    }

    /// u = c η / (d + η) for a given elevation η (m), m/s.
    pub fn velocity_under(&self, eta: f64) -> f64 {
        self.celerity * eta / (self.depth + eta)
    }

    /// ∂η/∂x at (x, t) = −2 k H sech² θ tanh θ, –.
    pub fn slope(&self, x: f64, t: f64) -> f64 {
        let theta = self.phase(x, t);
        -2.0 * self.wavenumber * self.height * sech_squared(theta) * theta.tanh()
    }

    /// The velocity (u, w) at (x, t) a height `above_floor` over the floor, m/s: u = c η / (d + η)
    /// over the whole depth, and w = −z c d η_x / (d + η)² from continuity (∂w/∂z = −∂u/∂x, w = 0
    /// at the floor); at the surface it is (u − c) η_x, the kinematic condition of a profile
    /// moving at c (derived here).
    pub fn velocity_at(&self, x: f64, above_floor: f64, t: f64) -> [f64; 2] {
        let eta = self.elevation(x, t);
        let total = self.depth + eta;
        [
            self.velocity_under(eta),
            -above_floor * self.celerity * self.depth * self.slope(x, t) / (total * total),
        ]
    }

    /// u at the crest, c H / (d + H), m/s: the largest depth-averaged velocity.
    pub fn crest_velocity(&self) -> f64 {
        self.velocity_under(self.height)
    }

    /// ∫ η dx = 2H / k, m² per metre of crest (∫ sech² = 2): the water the wave carries.
    pub fn volume_per_width(&self) -> f64 {
        2.0 * self.height / self.wavenumber
    }

    /// The length over which η ≥ `fraction` · H, (2 / k) arcosh(1 / √fraction), m: an effective
    /// wavelength. Goring's (1978) duration uses the phases |θ| ≤ 3.8 ([`GORING_PHASE`]), where
    /// η = sech²(3.8) H ≈ 0.002 H. `fraction` must lie in (0, 1].
    pub fn width_above(&self, fraction: f64) -> f64 {
        2.0 * (1.0 / fraction.sqrt()).acosh() / self.wavenumber
    }

    /// The time the part of the wave with η ≥ `fraction` · H takes to pass a fixed point, s.
    pub fn passage_time(&self, fraction: f64) -> f64 {
        self.width_above(fraction) / self.celerity
    }
}

/// The phase |θ| = 3.8 at which Goring (1978) cuts the wave for the duration of the paddle's
/// motion, T = 2 (3.8 + H/d) / (k c) ([`super::goring::GoringSolitary::goring_duration`]).
pub const GORING_PHASE: f64 = 3.8;

/// sech² θ = 1 / cosh² θ, 0 once cosh θ overflows (|θ| > 710).
pub fn sech_squared(theta: f64) -> f64 {
    let c = theta.cosh();
    1.0 / (c * c)
}
