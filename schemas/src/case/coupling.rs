//! `[coupling]`: windows, scheme, acceleration and the interface laws between participants.

use super::drag::DragLink;
use super::error::check;
use super::{Case, FieldError};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How a window's exchange is iterated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Scheme {
    /// Serial explicit (staggered): one sweep per window; the first participant sees its
    /// partners' data of the last window end held constant.
    Explicit,
    /// Serial implicit: the window is repeated from checkpoints until the interface converges.
    Implicit,
}

/// Acceleration of the implicit fixed-point iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AccelerationKind {
    /// Plain fixed-point iteration with constant relaxation `initial_relaxation`.
    Constant,
    /// Aitken's dynamic under-relaxation (the default without resolved bodies).
    Aitken,
    /// Interface quasi-Newton, inverse least squares (IQN-ILS).
    IqnIls,
}

/// How the data of a window are first estimated from the windows before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Predictor {
    /// The last window's end values held over the window (preCICE's default).
    Constant,
    /// The line through the last two samples of the last window, extended over the window.
    #[default]
    Linear,
}

/// `[[coupling.spring]]`: a linear spring between two points of two participants,
/// `f_a = k (u_b − u_a)`, `f_b = −f_a` (u: displacements of the points).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpringLink {
    /// `participant/point`.
    pub a: String,
    /// `participant/point`.
    pub b: String,
    /// Stiffness [N/m].
    pub stiffness: f64,
}

/// `[[coupling.body]]`: a resolved rigid body, its particles in a fluid participant and its
/// dynamics in a structure participant. The fluid's `body_force` goes to the structure; the
/// structure's `body_pose` and `body_velocity` go to the fluid.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyLink {
    /// `fluid-participant/body`.
    pub fluid: String,
    /// `structure-participant/body`.
    pub structure: String,
}

/// `[coupling]`.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CouplingConfig {
    /// Coupling window Δt_c [s]; every solver lands exactly on each window end.
    pub window: f64,
    /// How a window's exchange is iterated.
    pub scheme: Scheme,
    /// Serial order of the participants (default: fluid participants, then structure ones).
    #[serde(default)]
    pub order: Vec<String>,
    /// Interface samples per window (≥ 1): data are exchanged at this many equally spaced
    /// times in each window and interpolated in between (linear for 1, quadratic for 2, a local cubic through the four nearest for 3 or more).
    #[serde(default = "default_samples")]
    pub samples: u32,
    /// First estimate of a window's data: the explicit scheme's data, the implicit scheme's first iterate.
    #[serde(default)]
    pub predictor: Predictor,
    /// Implicit only: the acceleration of the fixed-point iteration; default `"aitken"`, or
    /// `"iqn-ils"` when the case has resolved bodies ([`CouplingConfig::acceleration`]).
    #[serde(default, rename = "acceleration")]
    pub acceleration_given: Option<AccelerationKind>,
    /// Implicit only: relaxation of the first iteration (and of every iteration with
    /// `"constant"`) [–].
    #[serde(default = "default_relaxation")]
    pub initial_relaxation: f64,
    /// Implicit only: convergence, the relative interface residual ‖H(x) − x‖ / ‖H(x)‖ per
    /// field [–].
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Implicit only: iterations per window before the run stops with a report.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: u32,
    /// IQN-ILS only: windows whose secant pairs are reused.
    #[serde(default = "default_reuse")]
    pub reuse_windows: u32,
    /// Largest allowed relative action–reaction residual of the ledger [–]; default 1e-12
    /// ([`CPU_BALANCE_TOLERANCE`]), or 1e-5 ([`GPU_BALANCE_TOLERANCE`]) when a fluid runs on
    /// the GPU.
    #[serde(default, rename = "balance_tolerance")]
    pub balance_tolerance_given: Option<f64>,
    /// Net energy the coupling may create at the interface, as a multiple of the run's physical
    /// energy scale [–], before the coupler stops the run as unstable (the coupler's `stability`
    /// module; default 10; a run warns above 1).
    #[serde(default = "default_created_energy_limit")]
    pub created_energy_limit: f64,
    /// Wall-clock time a participant may go without showing progress before it is taken as hung
    /// [s]: neither an answer nor a progress report comes for this long. A window may take longer
    /// as long as its participant keeps reporting its steps and the bytes it writes (both solvers
    /// do, every quarter of this timeout or every 5 s, whichever is shorter, also while writing
    /// frames, checkpoints and the last outputs); it must exceed the longest single solver step,
    /// and the longest whole answer of a participant that does not report its progress.
    #[serde(default = "default_timeout")]
    pub timeout: f64,
    /// Simulated time between checkpoints [s] (a whole number of windows; none by default): at
    /// each such window end every participant and the coupler write their full state to
    /// `OUT/checkpoint/`, and `coupler run CASE --resume OUT` continues from the last one.
    #[serde(default)]
    pub checkpoint_interval: Option<f64>,
    /// Springs between points of two participants.
    #[serde(default)]
    pub spring: Vec<SpringLink>,
    /// Resolved rigid bodies: particles in a fluid, dynamics in a structure.
    #[serde(default)]
    pub body: Vec<BodyLink>,
    /// `[[coupling.drag]]`: unresolved drag and buoyancy on thin frame members (S2).
    #[serde(default)]
    pub drag: Vec<DragLink>,
}

fn default_samples() -> u32 {
    1
}
fn default_relaxation() -> f64 {
    0.5
}
fn default_tolerance() -> f64 {
    1e-8
}
fn default_max_iterations() -> u32 {
    50
}
fn default_reuse() -> u32 {
    0
}
/// The ledger's default tolerance: the CPU paths sum both sides in f64 (measured ≤ 6e-15).
pub const CPU_BALANCE_TOLERANCE: f64 = 1e-12;

/// The ledger's default tolerance when a fluid runs on the GPU: there the loads (summed by body
/// particle) and the reaction (summed by fluid particle) are two f32 sums of the same pair
/// forces in different orders, each off by at most (depth ≈ 80: a gather's ≤ 60 neighbours, two
/// trees of 256, three exchanges) · 2⁻²⁴ ≈ 5e-6 of Σ|pair forces| (`fluid-solver`'s
/// `tests/gpu_bodies.rs`); 1e-5 of the net forces holds while Σ|pair forces| stays within
/// about twice the net force in the worst case and 20 times it with random rounding. Measured on
/// the floating box (`tests/tests/gpu_floating.rs`): at most 5e-8.
pub const GPU_BALANCE_TOLERANCE: f64 = 1e-5;
fn default_created_energy_limit() -> f64 {
    10.0
}
fn default_timeout() -> f64 {
    120.0
}

impl CouplingConfig {
    /// The acceleration of implicit windows: the one asked for, else IQN-ILS when resolved
    /// bodies are coupled and Aitken otherwise. Aitken's one relaxation factor for the whole
    /// interface does not converge on a floating body (the CI floating box, 395 kg/m³, stopped
    /// unconverged at t = 0.016 s): the fluid's force answers a change of the body's pose of 1e-6
    /// of its size with a change of order one, so the factor fitted to the force's residuals
    /// (negative, or up to 24) throws the pose about, although the map contracts by ~1e-6 per
    /// sweep in the pose; IQN-ILS fits each direction (4–10 sweeps a window there).
    pub fn acceleration(&self) -> AccelerationKind {
        self.acceleration_given.unwrap_or(if self.body.is_empty() {
            AccelerationKind::Aitken
        } else {
            AccelerationKind::IqnIls
        })
    }

    /// The ledger's tolerance: `balance_tolerance` when given, else the default for a case whose
    /// fluids run on the GPU (`gpu`) or not.
    pub fn balance_tolerance(&self, gpu: bool) -> f64 {
        self.balance_tolerance_given.unwrap_or(if gpu {
            GPU_BALANCE_TOLERANCE
        } else {
            CPU_BALANCE_TOLERANCE
        })
    }

    /// Windows between checkpoints (`checkpoint_interval` / `window`), when checkpoints are asked for.
    pub fn checkpoint_windows(&self) -> Option<u64> {
        self.checkpoint_interval
            .map(|i| (i / self.window).round().max(1.0) as u64)
    }

    /// `checkpoint_interval` must be a whole number of windows.
    fn check_checkpoints(&self, interval: f64) -> Result<(), FieldError> {
        const KEY: &str = "coupling.checkpoint_interval";
        check::positive(KEY, interval)?;
        let windows = interval / self.window;
        let whole = windows.round().max(1.0);
        if (windows - whole).abs() > 1e-9 * whole {
            return Err(FieldError::new(
                KEY,
                format!(
                    "{interval} s is not a whole number of coupling windows ({} s); use {} s ({whole} windows)",
                    self.window,
                    whole * self.window
                ),
            ));
        }
        Ok(())
    }

    /// Checks the section against the case's participants.
    pub fn validate(&self, case: &Case) -> Result<(), FieldError> {
        check::positive("coupling.window", self.window)?;
        if self.window > case.info.end_time {
            return Err(FieldError::new(
                "coupling.window",
                format!(
                    "the window {} s is longer than case.end_time {} s; it must be ≤ end_time",
                    self.window, case.info.end_time
                ),
            ));
        }
        if !(1..=64).contains(&self.samples) {
            return Err(FieldError::new(
                "coupling.samples",
                format!("must be 1 … 64, got {}", self.samples),
            ));
        }
        check::within("coupling.initial_relaxation", self.initial_relaxation, 1e-6, 1.0)?;
        check::within("coupling.tolerance", self.tolerance, 1e-15, 0.5)?;
        if self.max_iterations == 0 {
            return Err(FieldError::new("coupling.max_iterations", "must be ≥ 1, got 0"));
        }
        if let Some(t) = self.balance_tolerance_given {
            check::positive("coupling.balance_tolerance", t)?;
        }
        if !(self.created_energy_limit.is_finite() && self.created_energy_limit >= 1.0) {
            return Err(FieldError::new(
                "coupling.created_energy_limit",
                format!(
                    "must be a number ≥ 1 (a multiple of the run's physical energy scale; default 10), got {}",
                    self.created_energy_limit
                ),
            ));
        }
        check::positive("coupling.timeout", self.timeout)?;
        if let Some(interval) = self.checkpoint_interval {
            self.check_checkpoints(interval)?;
        }
        let names = case.participants();
        for (i, name) in self.order.iter().enumerate() {
            if case.kind_of(name).is_none() {
                return Err(FieldError::new(
                    format!("coupling.order[{i}]"),
                    format!(
                        "`{name}` is not a participant; participants are: {}",
                        super::list(&names)
                    ),
                ));
            }
        }
        for (i, name) in self.order.iter().enumerate() {
            if let Some(first) = self.order[..i].iter().position(|n| n == name) {
                return Err(FieldError::new(
                    format!("coupling.order[{i}]"),
                    format!(
                        "`{name}` is listed twice (also at coupling.order[{first}]); list every participant once: {}",
                        super::list(&names)
                    ),
                ));
            }
        }
        if !self.order.is_empty() && self.order.len() != names.len() {
            return Err(FieldError::new(
                "coupling.order",
                format!("must list every participant once: {}", super::list(&names)),
            ));
        }
        for (i, s) in self.spring.iter().enumerate() {
            let key = format!("coupling.spring[{i}]");
            check::positive(&format!("{key}.stiffness"), s.stiffness)?;
            let a = point_ref(case, &format!("{key}.a"), &s.a)?;
            let b = point_ref(case, &format!("{key}.b"), &s.b)?;
            if a.0 == b.0 {
                return Err(FieldError::new(
                    key,
                    format!("both ends are in participant `{}`; a coupling spring joins two participants (a spring inside one participant belongs in its own section)", a.0),
                ));
            }
        }
        for (i, link) in self.body.iter().enumerate() {
            let key = format!("coupling.body[{i}]");
            body_ref(case, &format!("{key}.fluid"), &link.fluid, true)?;
            body_ref(case, &format!("{key}.structure"), &link.structure, false)?;
            for (j, other) in self.body[..i].iter().enumerate() {
                if other.fluid == link.fluid || other.structure == link.structure {
                    return Err(FieldError::new(
                        key,
                        format!("couples a body that coupling.body[{j}] couples already; each body is coupled once"),
                    ));
                }
            }
        }
        for (i, link) in self.drag.iter().enumerate() {
            link.validate(case, &format!("coupling.drag[{i}]"))?;
        }
        if self.drag.len() > 1 {
            return Err(FieldError::new(
                "coupling.drag",
                format!(
                    "{} drag links given; one [[coupling.drag]] per case is supported (one fluid, one frame)",
                    self.drag.len()
                ),
            ));
        }
        for (name, fluid) in &case.fluid {
            for body in fluid.body_names() {
                let full = format!("{name}/{body}");
                if case.participants().len() > 1 && !self.body.iter().any(|l| l.fluid == full) {
                    return Err(FieldError::new(
                        "coupling.body",
                        format!(
                            "fluid body `{full}` has no [[coupling.body]] giving it a structure to move with"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Participants in serial order.
    pub fn serial_order(&self, case: &Case) -> Vec<String> {
        if self.order.is_empty() {
            case.participants().into_iter().map(|(n, _)| n).collect()
        } else {
            self.order.clone()
        }
    }
}

/// Splits and checks `participant/point` against the structure participants' point masses.
pub fn point_ref<'a>(case: &Case, key: &str, text: &'a str) -> Result<(&'a str, &'a str), FieldError> {
    let Some((participant, point)) = text.split_once('/') else {
        return Err(FieldError::new(
            key,
            format!("must be `participant/point`, got `{text}`"),
        ));
    };
    let Some(cfg) = case.structure.get(participant) else {
        let names: Vec<&String> = case.structure.keys().collect();
        return Err(FieldError::new(
            key,
            format!("`{participant}` is not a structure participant; structure participants are: {names:?}"),
        ));
    };
    let points = cfg.point_names();
    if !points.contains(&point) {
        return Err(FieldError::new(
            key,
            format!(
                "participant `{participant}` has no point mass `{point}`; its point masses are: {points:?}"
            ),
        ));
    }
    Ok((participant, point))
}

/// Splits and checks `participant/body` against the fluid (or structure) participants' bodies.
pub fn body_ref<'a>(
    case: &Case,
    key: &str,
    text: &'a str,
    fluid: bool,
) -> Result<(&'a str, &'a str), FieldError> {
    let Some((participant, body)) = text.split_once('/') else {
        return Err(FieldError::new(
            key,
            format!("must be `participant/body`, got `{text}`"),
        ));
    };
    let (kind, bodies) = if fluid {
        ("fluid", case.fluid.get(participant).map(|c| c.body_names()))
    } else {
        (
            "structure",
            case.structure.get(participant).map(|c| c.body_names()),
        )
    };
    let Some(bodies) = bodies else {
        return Err(FieldError::new(
            key,
            format!("`{participant}` is not a {kind} participant"),
        ));
    };
    if !bodies.contains(&body) {
        return Err(FieldError::new(
            key,
            format!("{kind} participant `{participant}` has no body `{body}`; its bodies are: {bodies:?}"),
        ));
    }
    Ok((participant, body))
}
