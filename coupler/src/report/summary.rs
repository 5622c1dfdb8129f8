//! The one-paragraph summary of a case's ladders: the cheapest setting that reaches the case's
//! stated error, and which method is cheapest at each decade of accuracy.

use super::table::{sci, Row};

/// The paragraph for one case's measured rows.
pub fn paragraph(rows: &[&Row], target: f64, error_name: &str) -> String {
    let ok: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| r.status == "ok" && r.error.is_finite())
        .collect();
    if ok.is_empty() {
        return "No rung finished with an error, so there is nothing to compare.".into();
    }
    let setting = |r: &Row| format!("{} at {} = {}", r.ladder, r.parameter, r.value);
    let cheapest = |level: f64| {
        ok.iter()
            .copied()
            .filter(|r| r.error <= level)
            .min_by(|a, b| a.wall.total_cmp(&b.wall))
    };
    let mut s = match cheapest(target) {
        Some(r) => format!(
            "The cheapest setting reaching {error_name} ≤ {} is {} ({}, {:.3} s wall).",
            sci(target),
            setting(r),
            sci(r.error),
            r.wall
        ),
        None => {
            let best = ok.iter().min_by(|a, b| a.error.total_cmp(&b.error)).copied();
            format!(
                "No setting reaches {error_name} ≤ {}; the smallest error is {} ({}).",
                sci(target),
                best.map_or("–".into(), |r| sci(r.error)),
                best.map_or(String::new(), setting)
            )
        }
    };
    // Decades from the largest error down to the smallest one reached.
    let hi = ok.iter().map(|r| r.error).fold(0.0, f64::max);
    let lo = ok
        .iter()
        .map(|r| r.error)
        .fold(f64::INFINITY, f64::min)
        .max(1e-16);
    let mut level = 10f64.powf(hi.log10().ceil());
    let mut winners: Vec<(f64, String)> = Vec::new();
    while level >= lo * 0.999 && winners.len() < 20 {
        if let Some(r) = cheapest(level) {
            match winners.last_mut() {
                Some((_, w)) if *w == r.ladder => {}
                _ => winners.push((level, r.ladder.clone())),
            }
        }
        level /= 10.0;
    }
    if !winners.is_empty() {
        let parts: Vec<String> = winners
            .iter()
            .map(|(level, w)| format!("from {} down, {w}", sci(*level)))
            .collect();
        s.push_str(&format!(" Cheapest for a given error: {}.", parts.join("; ")));
    }
    s
}
