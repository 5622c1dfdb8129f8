//! Tests of `schemas::geometry::height_grid`.

use schemas::geometry::height_grid::*;

fn plane(x: f64, y: f64) -> f64 {
    1.5 + 0.25 * x - 0.75 * y
}

fn grid() -> HeightGrid {
    HeightGrid::from_fn(5, 4, [10.0, -3.0], [0.5, 2.0], plane).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn bilinear_is_exact_on_a_plane() {
    let g = grid();
    for (x, y) in [
        (10.0, -3.0),
        (12.0, 3.0),
        (10.3, 1.7),
        (11.999, -2.5),
        (11.0, 0.0),
    ] {
        let h = g.height_at(x, y).unwrap_or_else(|| panic!("({x}, {y}) outside"));
        assert!(
            (h - plane(x, y)).abs() < 1e-13,
            "({x}, {y}): {h} against {}",
            plane(x, y)
        );
    }
    // x·y is bilinear too: exact as well
    let g = HeightGrid::from_fn(3, 3, [0.0; 2], [1.0; 2], |x, y| x * y).unwrap_or_else(|e| panic!("{e}"));
    assert!((g.height_at(0.5, 1.5).unwrap_or(f64::NAN) - 0.75).abs() < 1e-15);
}

#[test]
fn outside_the_centres_hull_there_is_no_height() {
    let g = grid();
    assert_eq!(g.centres_extent(), ([10.0, -3.0], [12.0, 3.0]));
    assert_eq!(g.extent(), ([9.75, -4.0], [12.25, 4.0]));
    assert_eq!(g.height_at(9.99, 0.0), None);
    assert_eq!(g.height_at(12.01, 0.0), None);
    assert_eq!(g.height_at(11.0, 3.1), None);
    assert_eq!(g.height_at(f64::NAN, 0.0), None);
    assert!(g.height_at(12.0 + 1e-12, 3.0).is_some());
    assert_eq!(g.min_height(), plane(10.0, 3.0));
    assert_eq!(g.max_height(), plane(12.0, -3.0));
}

#[test]
fn bad_grids_are_refused() {
    let e = HeightGrid::from_fn(3, 3, [0.0; 2], [0.0, 1.0], plane)
        .err()
        .map(|e| e.to_string());
    assert!(e.unwrap_or_default().contains("cell size"));
    let e = HeightGrid::new(2, 2, [0.0; 2], [1.0; 2], vec![0.0; 3])
        .err()
        .map(|e| e.to_string());
    assert!(e.unwrap_or_default().contains("need 4 heights, got 3"));
    let e = HeightGrid::from_fn(2, 2, [0.0; 2], [1.0; 2], |x, y| {
        if x > 0.5 && y > 0.5 {
            f64::NAN
        } else {
            0.0
        }
    })
    .err()
    .map(|e| e.to_string())
    .unwrap_or_default();
    assert!(e.contains("column 1, row 1") && e.contains("x = 1, y = 1"), "{e}");
}
