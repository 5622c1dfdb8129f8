//! Implicit coupling that cannot change a fluid's answer: one fluid step per window.
//!
//! The fluid reads its coupled inputs (a resolved body's pose and velocity, the drag law's point
//! reactions) at the start of each of its steps, from the window's interpolation, and its
//! explicit step advances from that state. With one step per window the only instant it reads
//! is the window start, whose sample is the last window's accepted end: implicit iterations
//! change the samples after the start only (`crate::state::flatten` skips sample 0), so every
//! sweep hands the fluid the same inputs and gets the same answer. The converged window is then
//! the explicit scheme's, bit for bit (measured on the floating box: explicit and IQN-ILS
//! histories identical at 2.9 sweeps per window), and the iterations cost time for nothing.
//! With two or more steps per window the later steps read the iterated samples.

use schemas::case::Case;

/// The `warning: ` line for a case whose implicit coupling has a fluid taking one step (or
/// fewer) per window with a resolved body; None otherwise. (The drag law is left out: there the
/// structure reads the fluid's samples at the window end from the iterate, so its answer, though
/// not the fluid's, does change with the iterations.)
pub fn warning(case: &Case) -> Option<String> {
    let coupling = case.coupling.as_ref()?;
    if coupling.scheme != schemas::case::coupling::Scheme::Implicit {
        return None;
    }
    let fluids = coupling
        .body
        .iter()
        .map(|b| b.fluid.split('/').next().unwrap_or_default().to_string());
    let one_step: Vec<String> = fluids
        .filter_map(|name| {
            let fluid = case.fluid.get(&name)?;
            (coupling.window <= fluid.time_step * (1.0 + 1e-9))
                .then(|| format!("`{name}` (time_step {} s)", fluid.time_step))
        })
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    if one_step.is_empty() {
        return None;
    }
    Some(format!(
        "warning: coupling: implicit iterations cannot change the answer of fluid {}: with coupling.window = {} s \
         it takes one step per window and reads the body motion at that step's start, the window start, which the \
         iterations do not change; the result is the explicit scheme's at the cost of the extra sweeps. Use coupling.scheme = \"explicit\", or a window of two or more fluid steps for the iterations to act",
        one_step.join(", "),
        coupling.window
    ))
}
