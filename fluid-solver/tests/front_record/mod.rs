//! The validation records of a dam-break front test (docs/validation.md): the errors of
//! `front_common::front_errors` against both experiments, with the bounds the test asserts.

use crate::front_common::FrontErrors;

/// How a front test names its two validation records (`<method>-front-koshizuka-oka-<scale>` and
/// `<method>-front-martin-moyce-<scale>`) and what they say beside the errors.
pub struct FrontRecord<'a> {
    /// Id tag of the method, e.g. "emps", "isph-symmetric", "gpu".
    pub method: &'a str,
    /// Id tag of the resolution, e.g. "l10".
    pub scale: &'a str,
    /// What is validated, e.g. "ISPH dam-break front, symmetric gradient".
    pub capability: &'a str,
    /// Method and resolution in words.
    pub resolution: &'a str,
    /// The test, "fluid-solver/tests/FILE.rs::NAME".
    pub source: &'a str,
    /// The bounds the test asserts: against Koshizuka & Oka, against Martin & Moyce.
    pub bounds: [f64; 2],
    /// Where the bounds come from.
    pub bound_source: &'a str,
    pub run_time_s: f64,
    /// The machine when the test names more than `record` fills in (its GPU); else empty.
    pub machine: String,
}

/// Records the run's errors against both experiments (before the test asserts them).
pub fn record(e: &FrontErrors, r: &FrontRecord) {
    use schemas::validation::{record, Record};
    let row = |reference: &str, tag: &str, value: f64, bound: f64, measure: &str| Record {
        id: format!("{}-front-{tag}-{}", r.method, r.scale),
        capability: r.capability.into(),
        reference: reference.into(),
        case: "cases/dam-break-koshizuka: water column L × 2L (L = 0.146 m), tank 4L long".into(),
        resolution: r.resolution.into(),
        measure: measure.into(),
        value,
        bound: Some(bound),
        bound_source: r.bound_source.into(),
        unit: String::new(),
        source: r.source.into(),
        run_time_s: r.run_time_s,
        machine: r.machine.clone(),
        ..Default::default()
    };
    record(row(
        "Koshizuka & Oka (1996) experiment",
        "koshizuka-oka",
        e.koshizuka_oka,
        r.bounds[0],
        "RMS of the surge-front position Z = z/L at the data's times T = t √(2g/L)",
    ));
    record(row(
        "Martin & Moyce (1952) experiment, n² = 2, a = 2.25 in",
        "martin-moyce",
        e.martin_moyce,
        r.bounds[1],
        "RMS of the surge-front position Z = z/L at the data's times, after the best time shift in [−0.3, 0.3]",
    ));
}
