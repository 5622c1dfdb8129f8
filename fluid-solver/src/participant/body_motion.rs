//! The body motion a fluid substep reads from its window's inputs.
//!
//! In an implicit window (the participant saved or restored a checkpoint for it) a substep reads
//! the pose and velocity at its END, and steps the bodies to that pose (see
//! [`crate::bodies::RigidBodies::set_kinematics`]): at one fluid step per window its start is the
//! window start, which the iterations never change, while its end is the structure's latest
//! iterate, so only this reading lets the iterations act on the fluid.
//!
//! In an explicit window a substep reads its START, as before: the window-end sample is then the
//! coupler's predictor (the line through the last window's samples with `predictor = "linear"`),
//! not the structure's answer, and stepping the bodies to it extrapolates their velocity too,
//! which made the explicit ISPH floating box of `tests/isph_floating.rs` (density ratio 0.4)
//! blow up: thrown to a centre height of 0.296 m within 0.3 s, its band 0.192 … 0.224 m (with the
//! start reading: 0.2000 … 0.2072 m).
//!
//! Between samples: the centre and the velocities (V, ω) by the window's interpolation
//! ([`Waveform::at`]: linear between two samples); the orientation by slerp between the two
//! samples around `t`, q(s) = sin((1 − s)θ)/sin θ q₀ + sin(sθ)/sin θ q₁ with cos θ = q₀·q₁ (q₁'s
//! sign taken so that θ ≤ π/2, the shorter turn), which keeps |q| = 1 where the component-wise
//! interpolation does not.

use schemas::message::Waveform;

/// Pose (7 per body) and velocity (6 per body) of the bodies at time `t` of the window `inputs`
/// (clamped to the window); empty when the window carries no body motion. An error when the
/// window's samples differ in length ([`Waveform::at`]).
pub fn at(inputs: &Waveform, t: f64) -> Result<(Vec<f64>, Vec<f64>), String> {
    let f = inputs.at(t)?;
    let mut pose = f.body_pose.0;
    if pose.is_empty() {
        return Ok((pose, f.body_velocity.0));
    }
    let n = inputs.times.len().min(inputs.samples.len());
    let t = t.clamp(inputs.start(), inputs.end());
    let j = inputs.times[..n]
        .windows(2)
        .position(|w| t <= w[1])
        .unwrap_or(n.saturating_sub(2));
    let (q0s, q1s) = (
        &inputs.samples[j].body_pose,
        &inputs.samples[(j + 1).min(n - 1)].body_pose,
    );
    let span = inputs.times.get(j + 1).map_or(0.0, |t1| t1 - inputs.times[j]);
    let s = if span > 0.0 {
        (t - inputs.times[j]) / span
    } else {
        0.0
    };
    for (b, out) in pose.chunks_exact_mut(7).enumerate() {
        let quaternion = |poses: &[f64]| -> Option<[f64; 4]> {
            let q = poses.get(7 * b + 3..7 * b + 7)?;
            Some([q[0], q[1], q[2], q[3]])
        };
        if let (Some(q0), Some(q1)) = (quaternion(q0s), quaternion(q1s)) {
            out[3..7].copy_from_slice(&slerp(q0, q1, s));
        }
    }
    Ok((pose, f.body_velocity.0))
}

/// Unit quaternion a fraction `s` of the way from `q0` to `q1` along the shorter great arc
/// (both normalised first).
pub fn slerp(q0: [f64; 4], q1: [f64; 4], s: f64) -> [f64; 4] {
    let q0 = normalised(q0);
    let mut q1 = normalised(q1);
    let mut cos = dot(q0, q1);
    if cos < 0.0 {
        q1 = q1.map(|c| -c);
        cos = -cos;
    }
    let theta = cos.min(1.0).acos();
    let (w0, w1) = if theta < 1e-8 {
        (1.0 - s, s)
    } else {
        let sin = theta.sin();
        (((1.0 - s) * theta).sin() / sin, (s * theta).sin() / sin)
    };
    normalised(std::array::from_fn(|c| w0 * q0[c] + w1 * q1[c]))
}

fn dot(a: [f64; 4], b: [f64; 4]) -> f64 {
    (0..4).map(|c| a[c] * b[c]).sum()
}

fn normalised(q: [f64; 4]) -> [f64; 4] {
    let norm = dot(q, q).sqrt();
    if norm > 0.0 {
        q.map(|c| c / norm)
    } else {
        [1.0, 0.0, 0.0, 0.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use schemas::message::Fields;
    use schemas::F64s;

    fn window(poses: [[f64; 7]; 2], velocities: [[f64; 6]; 2]) -> Waveform {
        Waveform {
            times: vec![1.0, 1.5],
            samples: (0..2)
                .map(|k| Fields {
                    body_pose: F64s(poses[k].to_vec()),
                    body_velocity: F64s(velocities[k].to_vec()),
                    ..Fields::default()
                })
                .collect(),
        }
    }

    #[test]
    fn a_turn_about_z_is_split_by_angle_and_the_centre_linearly() {
        // 0° → 90° about z: at a quarter of the window, 22.5°, exactly, and still a unit quaternion
        let h = std::f64::consts::FRAC_PI_4;
        let w = window(
            [
                [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
                [4.0, 0.0, 0.0, h.cos(), 0.0, 0.0, h.sin()],
            ],
            [[0.0; 6], [2.0, 0.0, 0.0, 0.0, 0.0, 1.0]],
        );
        let (pose, velocity) = at(&w, 1.125).unwrap_or_else(|e| panic!("{e}"));
        let angle = 0.25 * std::f64::consts::FRAC_PI_2;
        let expected = [1.0, 0.0, 0.0, (0.5 * angle).cos(), 0.0, 0.0, (0.5 * angle).sin()];
        for (a, b) in pose.iter().zip(expected) {
            assert!((a - b).abs() < 1e-14, "{pose:?} vs {expected:?}");
        }
        assert!((velocity[0] - 0.5).abs() < 1e-14 && (velocity[5] - 0.25).abs() < 1e-14);
        // the window end is its last sample exactly
        let (end, _) = at(&w, 1.5).unwrap_or_else(|e| panic!("{e}"));
        for (a, b) in end.iter().zip(w.samples[1].body_pose.iter()) {
            assert!((a - b).abs() < 1e-15, "{end:?}");
        }
    }

    #[test]
    fn the_shorter_turn_is_taken_whatever_the_sign_of_q1() {
        let h = 0.05_f64;
        let q1 = [-h.cos(), 0.0, -h.sin(), 0.0];
        let mid = slerp([1.0, 0.0, 0.0, 0.0], q1, 0.5);
        assert!((mid[0] - (0.5 * h).cos()).abs() < 1e-14 && (mid[2] - (0.5 * h).sin()).abs() < 1e-14);
    }
}
