//! Tests of `schemas::geometry::lattice`.

use schemas::geometry::lattice::*;

#[test]
fn indices_within_include_sites_on_the_bounds() {
    let l = Lattice {
        origin: [0.1, 0.0, -1.0],
        spacing: 0.1,
        n: [10, 1, 1],
    };
    assert_eq!(l.indices_within(0, l.coordinate(0, 2), l.coordinate(0, 5)), 2..6);
    assert_eq!(
        l.indices_within(0, l.coordinate(0, 2) + 1e-12, l.coordinate(0, 5) - 1e-12),
        3..5
    );
    assert_eq!(l.indices_within(0, -5.0, 50.0), 0..10);
    assert_eq!(l.indices_within(0, 5.0, 50.0), 10..10);
    assert_eq!(l.indices_within(0, -5.0, -4.0), 0..0);
    assert_eq!(l.indices_within(0, f64::NAN, 1.0), 0..0);
    assert_eq!(l.indices_within(0, 0.42, 0.38), 0..0);
    assert_eq!(l.site_count(), 10);
    assert!((l.upper_corner()[0] - 1.1).abs() < 1e-15);
}
