//! The error of a finished run against its case's `[reference]`: the compared output series,
//! the reference at the same times, and the declared measure (largest or RMS difference, or the
//! integral of the difference; optionally relative to the reference).

use schemas::case::reference::{read_data, Against, Measure, ReferenceConfig, Solution};
use schemas::case::Case;
use schemas::message::FromParticipant;
use schemas::recording::{Message, Recording};
use std::collections::BTreeMap;
use std::path::Path;

/// The error of the run whose output folder is `out`; `finer` is the finer (or resolved) run's
/// output folder when the reference is one.
pub fn error(
    case: &Case,
    reference: &ReferenceConfig,
    out: &Path,
    finer: Option<&Path>,
) -> Result<f64, String> {
    let pairs = match reference.solution {
        Some(Solution::TwoMassOscillator) => {
            oscillator_pairs(&out.join("recording.rec"), &reference.participants)?
        }
        _ => {
            let run = output_series(case, reference, out)?;
            let window = |t: f64| {
                reference.from.is_none_or(|f| t >= f - 1e-12)
                    && reference.until.is_none_or(|u| t <= u + 1e-12)
            };
            match reference.against {
                Against::Exact => {
                    let value = reference.value.unwrap_or_default();
                    run.iter()
                        .filter(|(t, _)| window(*t))
                        .map(|&(t, v)| (t, v, value))
                        .collect()
                }
                Against::Experiment => {
                    let path = case.resolve(reference.data.as_deref().unwrap_or(Path::new("")));
                    let data = read_data(
                        &path,
                        reference.data_time.as_deref().unwrap_or(""),
                        reference.data_value.as_deref().unwrap_or(""),
                    )?;
                    data.iter()
                        .map(|&(t, v)| (t * reference.time_scale, v * reference.value_scale))
                        .filter(|(t, _)| window(*t))
                        .filter_map(|(t, v)| interpolate(&run, t).map(|m| (t, m, v)))
                        .collect()
                }
                Against::FinerRun | Against::ResolvedRun => {
                    let finer = finer.ok_or("the reference run did not finish")?;
                    let fine = output_series(case, reference, finer)?;
                    run.iter()
                        .filter(|(t, _)| window(*t))
                        .filter_map(|&(t, v)| interpolate(&fine, t).map(|f| (t, v, f)))
                        .collect()
                }
            }
        }
    };
    measure(&pairs, reference.measure, reference.relative)
}

/// The declared measure of (time, computed, reference) triples, sorted by time.
pub fn measure(pairs: &[(f64, f64, f64)], how: Measure, relative: bool) -> Result<f64, String> {
    if pairs.is_empty() {
        return Err("no output rows fall within the reference's times".into());
    }
    let diffs = pairs.iter().map(|(_, a, b)| (a - b).abs());
    let e = match how {
        Measure::Max => diffs.fold(0.0, |m: f64, d| if d.is_nan() { f64::NAN } else { m.max(d) }),
        Measure::Rms => (diffs.map(|d| d * d).sum::<f64>() / pairs.len() as f64).sqrt(),
        Measure::Integral => trapezoid(pairs, |a, b| a - b).abs(),
    };
    let scale = match how {
        Measure::Integral => trapezoid(pairs, |_, b| b).abs(),
        _ => pairs.iter().map(|(_, _, b)| b.abs()).fold(0.0, f64::max),
    };
    match relative {
        true if scale > 0.0 => Ok(e / scale),
        true => Err("the reference is zero over the compared rows; a relative error is undefined".into()),
        false => Ok(e),
    }
}

/// ∫ f(computed, reference) dt by trapezoids over the rows' times.
fn trapezoid(rows: &[(f64, f64, f64)], f: impl Fn(f64, f64) -> f64) -> f64 {
    rows.windows(2)
        .map(|w| 0.5 * (f(w[0].1, w[0].2) + f(w[1].1, w[1].2)) * (w[1].0 - w[0].0))
        .sum()
}

/// The compared column of a run's output, as (time, value); the time is the `t` or `time`
/// column (else the first).
fn output_series(case: &Case, r: &ReferenceConfig, out: &Path) -> Result<Vec<(f64, f64)>, String> {
    let file = r.file.as_deref().unwrap_or_default();
    let path = match (&case.coupling, &r.participant) {
        (Some(_), Some(participant)) => out.join(participant).join(file),
        _ => out.join(file),
    };
    let column = r.column.as_deref().unwrap_or_default();
    let text = std::fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let col = header.iter().position(|h| *h == column).ok_or_else(|| {
        format!(
            "{} has no column `{column}`; its columns are {header:?}",
            path.display()
        )
    })?;
    let time = header.iter().position(|h| *h == "t" || *h == "time").unwrap_or(0);
    Ok(lines
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f.get(i).map(|s| s.trim().parse::<f64>().unwrap_or(f64::NAN));
            Some((num(time)?, num(col)?))
        })
        .collect())
}

/// Linear interpolation of a series sorted by time at `t`; None outside its times.
fn interpolate(series: &[(f64, f64)], t: f64) -> Option<f64> {
    let i = series.partition_point(|&(s, _)| s < t);
    let tol = 1e-9;
    match (i.checked_sub(1).and_then(|j| series.get(j)), series.get(i)) {
        (_, Some(&(s, v))) if (s - t).abs() <= tol => Some(v),
        (Some(&(s, v)), _) if (s - t).abs() <= tol => Some(v),
        (Some(&(t0, v0)), Some(&(t1, v1))) => Some(v0 + (v1 - v0) * (t - t0) / (t1 - t0)),
        _ => None,
    }
}

/// Exact two-mass oscillator: u1 = ½(cos 2πt + cos 6πt), u2 = ½(cos 2πt − cos 6πt).
pub fn oscillator_exact(t: f64) -> (f64, f64) {
    use std::f64::consts::PI;
    let (a, b) = ((2.0 * PI * t).cos(), (6.0 * PI * t).cos());
    (0.5 * (a + b), 0.5 * (a - b))
}

/// (time, computed, exact) displacement of both masses at every window end: the outputs of the
/// last (converged) sweep of each window.
fn oscillator_pairs(recording: &Path, participants: &[String]) -> Result<Vec<(f64, f64, f64)>, String> {
    let rec = Recording::read(recording).map_err(|e| e.to_string())?;
    let mut ends: BTreeMap<(u64, usize), (f64, f64)> = BTreeMap::new();
    for f in &rec.frames {
        let Some(mass) = participants.iter().position(|p| *p == f.participant) else {
            continue;
        };
        if let Message::From(FromParticipant::Advanced { header, outputs, .. }) = &f.message {
            let u = outputs
                .last()
                .and_then(|o| o.point_displacement.first().copied())
                .unwrap_or(f64::NAN);
            ends.insert((header.window, mass), (header.time, u));
        }
    }
    Ok(ends
        .iter()
        .map(|(&(_, mass), &(t, u))| {
            let (e1, e2) = oscillator_exact(t);
            (t, u, if mass == 0 { e1 } else { e2 })
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn measures_and_interpolation() {
        let pairs = [(0.0, 1.0, 0.0), (1.0, 0.0, 2.0)];
        assert_eq!(measure(&pairs, Measure::Max, false), Ok(2.0));
        assert!((measure(&pairs, Measure::Rms, false).unwrap() - 2.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(measure(&pairs, Measure::Max, true), Ok(1.0));
        // ∫ (a − b) dt = ½ (1 + (−2)) = −0.5; ∫ b dt = 1
        assert_eq!(measure(&pairs, Measure::Integral, false), Ok(0.5));
        assert_eq!(measure(&pairs, Measure::Integral, true), Ok(0.5));
        let s = [(0.0, 0.0), (1.0, 2.0)];
        assert_eq!(interpolate(&s, 0.25), Some(0.5));
        assert_eq!(interpolate(&s, 1.0), Some(2.0));
        assert_eq!(interpolate(&s, 1.5), None);
    }
}
