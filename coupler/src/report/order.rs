//! Observed order of convergence between consecutive rungs of a ladder:
//! p = ln(e₁/e₂) / ln(h₁/h₂) for errors e at parameter values h.

use super::table::Row;

/// Errors below this are round-off: an order measured from them means nothing.
pub const ROUND_OFF: f64 = 1e-13;

/// The observed order between each pair of consecutive rungs (None where either error is
/// missing, at round-off, or the parameter did not change).
pub fn observed(rows: &[&Row]) -> Vec<Option<f64>> {
    rows.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let usable = |e: f64| e.is_finite() && e > ROUND_OFF;
            let ratio = a.value / b.value;
            (usable(a.error) && usable(b.error) && ratio > 0.0 && (ratio - 1.0).abs() > 1e-12)
                .then(|| (a.error / b.error).ln() / ratio.ln())
        })
        .collect()
}

/// Every defined order is negative (at least one is): the error grows as the parameter is refined.
pub fn grows_with_refinement(orders: &[Option<f64>]) -> bool {
    let defined: Vec<f64> = orders.iter().flatten().copied().collect();
    !defined.is_empty() && defined.iter().all(|&p| p < 0.0)
}

/// The orders as text: `1.30, 1.15` (`–` for an undefined one).
pub fn describe(orders: &[Option<f64>]) -> String {
    if orders.is_empty() {
        return "– (one rung)".into();
    }
    orders
        .iter()
        .map(|o| o.map_or("–".into(), |p| format!("{p:.2}")))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cantilever's CI ladder (docs/validation.md) (orders −0.28, −0.55): flagged; a converging or a
    /// mixed ladder, or one whose orders are all undefined, is not.
    #[test]
    fn a_ladder_whose_error_grows_with_refinement_is_flagged() {
        assert!(grows_with_refinement(&[Some(-0.28), Some(-0.55)]));
        assert!(grows_with_refinement(&[None, Some(-3.86)]));
        assert!(!grows_with_refinement(&[Some(1.07), Some(0.98)]));
        assert!(!grows_with_refinement(&[Some(-0.2), Some(1.0)]));
        assert!(!grows_with_refinement(&[None, None]));
        assert!(!grows_with_refinement(&[]));
    }
}
