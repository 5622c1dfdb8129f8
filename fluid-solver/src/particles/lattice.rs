//! Geometry of any extent on the particle lattice: the case's tank, water blocks, gates, wall
//! boxes, bodies and the wave maker's paddle are moved to the nearest lattice faces `tank.min + k Δs`, and every face
//! that moved is reported with how far.
//!
//! A particle stands for the cube of side Δs around its site `tank.min + (k + ½) Δs`, so a box
//! built of particles always has faces on lattice faces. The tank keeps its `min` corner and gets
//! the whole number of layers nearest to its extent (`max` moves by at most Δs/2). A box takes
//! the sites whose centres it contains, which is the same as rounding each face to the nearest
//! lattice face (each face moves by at most Δs/2; the box's volume changes by the moved slabs).

use schemas::case::fluid::{Aabb, FluidConfig};

/// Faces that moved less than this fraction of Δs are on the lattice already (round-off).
const ON_LATTICE: f64 = 1e-6;

/// `cfg` with every box on the lattice, and one message per box whose faces moved.
pub fn snap(cfg: &FluidConfig) -> (FluidConfig, Vec<String>) {
    let mut out = cfg.clone();
    let mut notes = Vec::new();
    let ds = cfg.spacing;
    let origin = cfg.tank.min;
    let tank = cfg.tank.inner();
    let snapped_tank = Aabb {
        min: tank.min,
        max: std::array::from_fn(|a| {
            let n = ((tank.max[a] - tank.min[a]) / ds).round().max(1.0);
            tank.min[a] + n * ds
        }),
    };
    note_moves("tank", &tank, &snapped_tank, ds, &mut notes);
    out.tank.max = snapped_tank.max;
    let snap_box = |b: &Aabb| Aabb {
        min: std::array::from_fn(|a| origin[a] + ((b.min[a] - origin[a]) / ds).round() * ds),
        max: std::array::from_fn(|a| origin[a] + ((b.max[a] - origin[a]) / ds).round() * ds),
    };
    for (what, boxes) in [
        ("block", &mut out.block),
        ("gate", &mut out.gate),
        ("wall", &mut out.wall),
    ] {
        for (i, b) in boxes.iter_mut().enumerate() {
            let s = snap_box(b);
            note_moves(&format!("{what}[{i}]"), b, &s, ds, &mut notes);
            *b = s;
        }
    }
    for b in &mut out.body {
        // a mesh body is not moved: its sites are those inside the mesh
        let Some(raw) = b.box_bounds() else { continue };
        let s = snap_box(&raw);
        note_moves(&format!("body `{}`", b.name), &raw, &s, ds, &mut notes);
        (b.min, b.max) = (Some(s.min), Some(s.max));
    }
    if let Some(w) = &mut out.wave_maker {
        let raw = w.paddle();
        let s = snap_box(&raw);
        note_moves("wave_maker's paddle", &raw, &s, ds, &mut notes);
        (w.min, w.max) = (s.min, s.max);
    }
    (out, notes)
}

/// Appends a message when a face of `what` moved from `raw` to `snapped` by more than round-off.
fn note_moves(what: &str, raw: &Aabb, snapped: &Aabb, ds: f64, notes: &mut Vec<String>) {
    let mut moves = Vec::new();
    for a in 0..3 {
        for (side, from, to) in [
            ("min", raw.min[a], snapped.min[a]),
            ("max", raw.max[a], snapped.max[a]),
        ] {
            if (to - from).abs() > ON_LATTICE * ds {
                let um = |v: f64| (v * 1e6).round() / 1e6;
                moves.push(format!(
                    "{side}.{} {} → {} m ({:+.2} mm)",
                    ["x", "y", "z"][a],
                    um(from),
                    um(to),
                    1e3 * (to - from)
                ));
            }
        }
    }
    if !moves.is_empty() {
        notes.push(format!(
            "{what} rounded to the particle lattice (spacing {ds} m, faces at tank.min + k·spacing): {}",
            moves.join(", ")
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_move_to_the_nearest_lattice_face_by_at_most_half_a_spacing() {
        let b = Aabb {
            min: [0.013, 0.0, 0.0],
            max: [0.161, 0.55, 0.3],
        };
        let ds = 0.02;
        let s = Aabb {
            min: std::array::from_fn(|a| (b.min[a] / ds).round() * ds),
            max: std::array::from_fn(|a| (b.max[a] / ds).round() * ds),
        };
        assert!((s.min[0] - 0.02).abs() < 1e-12 && (s.max[0] - 0.16).abs() < 1e-12);
        assert!(
            (s.max[1] - 0.56).abs() < 1e-12,
            "0.55 is 27.5 spacings: rounds up"
        );
        let mut notes = Vec::new();
        note_moves("block[0]", &b, &s, ds, &mut notes);
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].contains("+7.00 mm") && notes[0].contains("-1.00 mm"),
            "{}",
            notes[0]
        );
    }
}
