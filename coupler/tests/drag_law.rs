//! The drag law alone (issue 13): one member in a uniform stream sampled by hand-made fluid
//! outputs. Every expected value is S2-19 … S2-23 evaluated by hand, so the tolerance is
//! round-off (1e-12 relative: a few dozen additions of doubles).

use coupler::laws::drag::{Drag, DragSettings};
use coupler::laws::{Instant, Law};
use schemas::case::drag::square_prism_drag;
use schemas::message::{Fields, Geometry};
use schemas::validation::{largest_abs, record, Record};
use schemas::F64s;

const RHO: f64 = 1000.0;
const G: f64 = 9.8;
/// Sub-member length d (the fluid particle size) [m].
const D_SUB: f64 = 0.005;
/// Member width D and area A [m, m²].
const WIDTH: f64 = 0.002;
const AREA: f64 = WIDTH * WIDTH;
const FLUID: usize = 0;
const STRUCTURE: usize = 1;
const ROUND_OFF: f64 = 1e-12;

fn settings(axial: bool, section_axis: Option<[f64; 3]>) -> DragSettings {
    DragSettings {
        density: RHO,
        gravity: [0.0, 0.0, -G],
        width: None,
        sub_member_length: D_SUB,
        initial_flow: Some([1.0, 0.0, 0.0]),
        section_axis,
        axial_drag: axial,
        drag_coefficient: square_prism_drag(),
    }
}

/// One member from `a` to `b` (two nodes, at rest), cut by a law with `settings`.
fn member(a: [f64; 3], b: [f64; 3], s: DragSettings) -> (Drag, Fields) {
    let mut law = Drag::new(s, FLUID, STRUCTURE, 2);
    let structure = Fields {
        node_position: F64s(a.iter().chain(&b).copied().collect()),
        node_velocity: F64s::zeros(12),
        ..Fields::default()
    };
    let geometry = Geometry {
        member_nodes: vec![0, 1],
        member_width: F64s(vec![WIDTH]),
        member_area: F64s(vec![AREA]),
    };
    law.geometry(STRUCTURE, &geometry, &structure)
        .expect("geometry is consistent");
    (law, structure)
}

/// The fluid's answer: the same velocity and λ_min at every sample point.
fn uniform_flow(law: &Drag, v: [f64; 3], lambda_min: f64) -> Fields {
    let n = law.sub_members().len();
    Fields {
        sampled_velocity: F64s((0..n).flat_map(|_| v).collect()),
        sampled_lambda_min: F64s(vec![lambda_min; n]),
        ..Fields::default()
    }
}

/// Inputs of both sides and the total force on the structure and on the fluid.
fn apply(law: &Drag, structure: &Fields, fluid: &Fields) -> (Fields, Fields, [f64; 3], [f64; 3]) {
    let start = [fluid, structure];
    let at = Instant {
        start: &start,
        current: &start,
    };
    let (mut to_fluid, mut to_structure) = (Fields::default(), Fields::default());
    law.add_inputs(FLUID, at, &mut to_fluid);
    law.add_inputs(STRUCTURE, at, &mut to_structure);
    let fs = law.force_given(STRUCTURE, &to_structure, structure);
    let ff = law.force_given(FLUID, &to_fluid, fluid);
    (to_fluid, to_structure, fs, ff)
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= ROUND_OFF * scale
}

/// Records the drag law's `got` against the hand evaluation `expected` (`what`, of S2's `equation`),
/// relative to `scale` as [`close`] judges it, for the test `test` on the member `case`.
fn record_against_hand(
    id: &str,
    (what, equation): (&str, &str),
    (got, expected, scale): (f64, f64, f64),
    case: &str,
    test: &str,
) {
    record(Record {
        id: format!("drag-law-{id}"),
        capability: "unresolved drag law (S2-18 … S2-24)".into(),
        reference: format!("{what} evaluated by hand: {equation}"),
        case: case.into(),
        resolution: "one 2 × 2 mm member cut into sub-members of d = 5 mm, hand-made fluid samples".into(),
        measure: format!("|law − hand| / scale ({what})"),
        value: (got - expected).abs() / scale,
        bound: Some(ROUND_OFF),
        bound_source: "round-off: a few dozen additions of doubles".into(),
        source: format!("coupler/tests/drag_law.rs::{test}"),
        ..Default::default()
    });
}

#[test]
fn a_member_across_a_uniform_stream_takes_half_cd_rho_v2_d_l_and_buoyancy() {
    let length = 0.1;
    let (law, structure) = member([0.0, 0.0, 0.0], [0.0, 0.0, length], settings(false, None));
    assert_eq!(law.sub_members().len(), 20, "0.1 m cut into pieces of 5 mm");
    let v = 1.7;
    let fluid = uniform_flow(&law, [v, 0.0, 0.0], 1.0);
    let (to_fluid, _, fs, ff) = apply(&law, &structure, &fluid);
    let drag = 0.5 * 2.1 * RHO * v * v * WIDTH * length;
    let buoyancy = RHO * G * AREA * length;
    let test = "a_member_across_a_uniform_stream_takes_half_cd_rho_v2_d_l_and_buoyancy";
    let case = "0.1 m member across a uniform 1.7 m/s stream, fully wet";
    record_against_hand(
        "cross-stream",
        ("drag across the member", "½ C_D ρ v² D l, C_D = 2.1 face-on"),
        (fs[0], drag, drag),
        case,
        test,
    );
    record_against_hand(
        "buoyancy",
        ("buoyancy", "ρ g A l"),
        (fs[2], buoyancy, drag),
        case,
        test,
    );
    let reaction = largest_abs((0..3).map(|c| fs[c] + ff[c]));
    record_against_hand(
        "reaction",
        ("the fluid's reaction", "−f, Newton's third law"),
        (reaction, 0.0, drag),
        case,
        test,
    );
    assert!(
        close(fs[0], drag, drag),
        "drag {} vs ½ C_D ρ v² D l = {drag}",
        fs[0]
    );
    assert!(close(fs[1], 0.0, drag));
    assert!(
        close(fs[2], buoyancy, drag),
        "buoyancy {} vs ρ g A l = {buoyancy}",
        fs[2]
    );
    for c in 0..3 {
        assert!(
            close(fs[c] + ff[c], 0.0, drag),
            "the fluid takes −f: {fs:?} vs {ff:?}"
        );
    }
    assert_eq!(to_fluid.sample_point.len(), 60);
    assert_eq!(to_fluid.reaction.len(), 120);
    // one width per reaction: the member's, over whose footprint the fluid spreads it
    assert_eq!(&to_fluid.reaction_width[..], &[WIDTH; 20]);
}

#[test]
fn each_reaction_carries_the_width_the_case_gives_its_member() {
    let s = DragSettings {
        width: Some(0.05),
        ..settings(false, None)
    };
    let (law, structure) = member([0.0, 0.0, 0.0], [0.0, 0.0, 0.02], s);
    let fluid = uniform_flow(&law, [1.0, 0.0, 0.0], 1.0);
    let (to_fluid, ..) = apply(&law, &structure, &fluid);
    assert_eq!(&to_fluid.reaction_width[..], &[0.05; 4]);
    assert_eq!(to_fluid.reaction.len(), 6 * to_fluid.reaction_width.len());
}

#[test]
fn a_member_along_the_flow_takes_no_normal_drag_and_axial_drag_when_asked() {
    let length = 0.05;
    let v = 2.0;
    let (law, structure) = member([0.0, 0.0, 0.0], [length, 0.0, 0.0], settings(false, None));
    let fluid = uniform_flow(&law, [v, 0.0, 0.0], 1.0);
    let (_, _, fs, _) = apply(&law, &structure, &fluid);
    assert_eq!(fs[0], 0.0, "flow along the axis has no component across it");
    let (law, structure) = member([0.0, 0.0, 0.0], [length, 0.0, 0.0], settings(true, None));
    let (_, _, fs, _) = apply(&law, &structure, &fluid);
    let axial = 0.5 * 2.1 * RHO * v * v * WIDTH * length;
    record_against_hand(
        "axial",
        (
            "axial drag",
            "½ C_D ρ v² D l along the axis (S2 §6: the same C_D as across)",
        ),
        (fs[0], axial, axial),
        "0.05 m member along a uniform 2 m/s stream, axial_drag = true",
        "a_member_along_the_flow_takes_no_normal_drag_and_axial_drag_when_asked",
    );
    assert!(close(fs[0], axial, axial), "axial drag {} vs {axial}", fs[0]);
}

#[test]
fn a_member_above_the_water_takes_nothing_and_a_half_submerged_one_takes_s2_20s_share() {
    let length = 0.04;
    let v = 1.0;
    let (law, structure) = member([0.0, 0.0, 0.0], [0.0, length, 0.0], settings(false, None));
    for dry in [0.0, 0.3, 0.499] {
        let (_, _, fs, ff) = apply(&law, &structure, &uniform_flow(&law, [v, 0.0, 0.0], dry));
        assert_eq!((fs, ff), ([0.0; 3], [0.0; 3]), "λ_min = {dry} < 0.5 is dry");
    }
    // S2-20: l = d (λ − 0.5) / 0.4; λ = 0.7 gives half of each piece.
    let (_, _, fs, _) = apply(&law, &structure, &uniform_flow(&law, [v, 0.0, 0.0], 0.7));
    let full = 0.5 * 2.1 * RHO * v * v * WIDTH * length;
    record_against_hand(
        "half-submerged",
        (
            "the wet share of the drag",
            "S2-20: l = d (λ − 0.5) / 0.4, half of each piece at λ = 0.7",
        ),
        (fs[0], 0.5 * full, full),
        "0.04 m member across a uniform 1 m/s stream, λ_min = 0.7 at every sample",
        "a_member_above_the_water_takes_nothing_and_a_half_submerged_one_takes_s2_20s_share",
    );
    assert!(close(fs[0], 0.5 * full, full), "{} vs half of {full}", fs[0]);
    assert!(close(fs[2], 0.5 * RHO * G * AREA * length, full));
}

#[test]
fn node_shares_follow_s2_22_and_s2_23() {
    // A 5 mm member is one piece with its centroid at ξ = 0: half to each node. A 15 mm member
    // has pieces at ξ = −2/3, 0, 2/3: node 1 gets (5/6 + 1/2 + 1/6)/3 = 1/2 of the total.
    let (law, structure) = member([0.0, 0.0, 0.0], [0.0, 0.0, 0.015], settings(false, None));
    let fluid = uniform_flow(&law, [1.0, 0.0, 0.0], 1.0);
    let (_, to_structure, fs, _) = apply(&law, &structure, &fluid);
    let f = &to_structure.node_force;
    assert!(close(f[0], 0.5 * fs[0], fs[0]) && close(f[6], 0.5 * fs[0], fs[0]));
    // A non-uniform stream: only the top piece wet (λ > 0.9 there, dry below).
    let mut fluid = fluid;
    fluid.sampled_lambda_min = F64s(vec![0.0, 0.0, 1.0]);
    let (_, to_structure, fs, _) = apply(&law, &structure, &fluid);
    let f = &to_structure.node_force;
    let xi: f64 = 2.0 / 3.0;
    record_against_hand(
        "node-shares",
        (
            "node 1's share of the force",
            "S2-22: ½ (1 − ξ) at ξ = 2/3 for the only wet piece",
        ),
        (f[0], 0.5 * (1.0 - xi) * fs[0], fs[0]),
        "15 mm member, only its top 5 mm piece wet",
        "node_shares_follow_s2_22_and_s2_23",
    );
    assert!(
        close(f[0], 0.5 * (1.0 - xi) * fs[0], fs[0]),
        "S2-22: {} vs {}",
        f[0],
        fs[0]
    );
    assert!(close(f[6], 0.5 * (1.0 + xi) * fs[0], fs[0]), "S2-23");
}

#[test]
fn sample_points_sit_one_width_upstream_and_follow_the_accepted_flow() {
    let (mut law, structure) = member([0.0, 0.0, 0.0], [0.0, 0.0, 0.005], settings(false, None));
    let fluid = uniform_flow(&law, [0.0, 3.0, 0.0], 1.0);
    let (to_fluid, _, _, _) = apply(&law, &structure, &fluid);
    let s = &to_fluid.sample_point;
    assert!(
        close(s[0], -WIDTH, WIDTH) && s[1] == 0.0 && close(s[2], 0.0025, WIDTH),
        "initial_flow +x: {s:?}"
    );
    // The window is accepted with a flow along +y: the point moves to −y.
    law.accept(&[vec![fluid.clone()], vec![structure.clone()]]);
    let (to_fluid, _, fs, _) = apply(&law, &structure, &fluid);
    let s = &to_fluid.sample_point;
    assert!(
        s[0] == 0.0 && close(s[1], -WIDTH, WIDTH),
        "after a +y flow: {s:?}"
    );
    assert!(fs[1] > 0.0);
    // A wet sample that is still keeps the direction.
    law.accept(&[vec![uniform_flow(&law, [0.0; 3], 1.0)], vec![structure.clone()]]);
    let (to_fluid, _, _, _) = apply(&law, &structure, &fluid);
    assert!(
        to_fluid.sample_point[0] == 0.0 && close(to_fluid.sample_point[1], -WIDTH, WIDTH),
        "a still, wet sample: {:?}",
        to_fluid.sample_point
    );
    // A dry sample (λ_min below S2-20's λ^surface) returns the direction to the case's
    // initial_flow (+x), even while the member sways in the air (relative velocity −v_member ≠ 0)
    // and a few splashed particles move at the point: a member moving in air is no flow, and a
    // direction kept at a dry point locked the wide prism's sample points in its dry wake.
    let mut swaying = structure.clone();
    swaying.node_velocity = F64s(vec![
        0.0, 0.0, -1e-3, 0.0, 0.0, 0.0, 0.0, 0.0, -2e-3, 0.0, 0.0, 0.0,
    ]);
    law.accept(&[vec![uniform_flow(&law, [-2.0, 0.0, 0.0], 0.3)], vec![swaying]]);
    let (to_fluid, _, _, _) = apply(&law, &structure, &fluid);
    assert!(
        close(to_fluid.sample_point[0], -WIDTH, WIDTH) && to_fluid.sample_point[1] == 0.0,
        "after a dry sample: {:?}",
        to_fluid.sample_point
    );
}

#[test]
fn a_member_carried_with_the_flow_takes_drag_on_the_relative_velocity() {
    let (law, mut structure) = member([0.0, 0.0, 0.0], [0.0, 0.0, 0.01], settings(false, None));
    structure.node_velocity = F64s(vec![0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let (_, _, fs, _) = apply(&law, &structure, &uniform_flow(&law, [2.0, 0.0, 0.0], 1.0));
    let expected = 0.5 * 2.1 * RHO * 1.5 * 1.5 * WIDTH * 0.01;
    record_against_hand(
        "relative-velocity",
        ("drag on the relative velocity", "½ C_D ρ |v − v_member|² D l"),
        (fs[0], expected, expected),
        "10 mm member moving at 0.5 m/s in a 2 m/s stream",
        "a_member_carried_with_the_flow_takes_drag_on_the_relative_velocity",
    );
    assert!(close(fs[0], expected, expected), "{} vs {expected}", fs[0]);
}

#[test]
fn the_attack_angle_picks_the_table_row() {
    // The section's face normal at 45° to the flow: C_D(45°) = 1.6; at 13°: the table's minimum
    // 1.5; both on S2-18's projected width D = side (cos α + sin α) (90° folds onto 0°).
    for (deg, cd) in [(45.0_f64, 1.6), (13.0, 1.5), (0.0, 2.1), (90.0, 2.1)] {
        let a = deg.to_radians();
        let (law, structure) = member(
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.005],
            settings(false, Some([a.cos(), a.sin(), 0.0])),
        );
        let (_, _, fs, _) = apply(&law, &structure, &uniform_flow(&law, [1.0, 0.0, 0.0], 1.0));
        let folded = deg.min(90.0 - deg).to_radians();
        let expected = 0.5 * cd * RHO * WIDTH * (folded.cos() + folded.sin()) * 0.005;
        record_against_hand(
            &format!("attack-angle-{deg}"),
            (
                "drag at an attack angle",
                "C_D from the square-prism table on S2-18's projected width D = side (cos α + sin α)",
            ),
            (fs[0], expected, expected),
            &format!("5 mm member, section face normal at {deg}° to a 1 m/s stream"),
            "the_attack_angle_picks_the_table_row",
        );
        assert!(
            close(fs[0], expected, expected),
            "{deg}°: {} vs {expected}",
            fs[0]
        );
    }
}
