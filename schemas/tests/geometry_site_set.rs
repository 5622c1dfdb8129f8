//! Tests of `schemas::geometry::site_set`.

use schemas::geometry::lattice::Lattice;
use schemas::geometry::site_set::*;

fn lattice(n: [usize; 3]) -> Lattice {
    Lattice {
        origin: [0.0; 3],
        spacing: 1.0,
        n,
    }
}

#[test]
fn insert_all_is_the_union_and_leaves_a_set_of_another_lattice_out() {
    let l = lattice([3, 2, 70]);
    let (mut a, mut b) = (SiteSet::empty(&l), SiteSet::empty(&l));
    a.insert(0, 0, 1);
    b.insert(2, 1, 65);
    b.insert(0, 0, 1);
    a.insert_all(&b);
    assert_eq!(a.iter().collect::<Vec<_>>(), vec![[0, 0, 1], [2, 1, 65]]);
    let mut other = SiteSet::empty(&lattice([3, 2, 69]));
    other.insert(1, 1, 1);
    a.insert_all(&other);
    assert_eq!(a.count(), 2);
}

/// The skin by brute force: inside sites with an outside site (or, with `beyond`, a site
/// beyond the lattice) within Chebyshev distance `layers`.
fn brute_skin(set: &SiteSet, layers: usize, beyond: bool) -> Vec<[usize; 3]> {
    let n = set.lattice().n;
    let l = layers as i64;
    set.iter()
        .filter(|s| {
            let mut near = false;
            for di in -l..=l {
                for dj in -l..=l {
                    for dk in -l..=l {
                        let p = [s[0] as i64 + di, s[1] as i64 + dj, s[2] as i64 + dk];
                        let within = (0..3).all(|a| p[a] >= 0 && p[a] < n[a] as i64);
                        near |= if within {
                            !set.contains(p[0] as usize, p[1] as usize, p[2] as usize)
                        } else {
                            beyond
                        };
                    }
                }
            }
            near
        })
        .collect()
}

#[test]
fn insert_contains_count_iter() {
    let mut s = SiteSet::empty(&lattice([3, 2, 130]));
    assert!(s.insert(2, 1, 129) && s.insert(0, 0, 0) && s.insert(1, 1, 64));
    assert!(!s.insert(3, 0, 0) && !s.insert(0, 0, 130));
    assert!(s.contains(2, 1, 129) && !s.contains(2, 1, 128) && !s.contains(9, 9, 9));
    assert_eq!(s.count(), 3);
    assert_eq!(
        s.iter().collect::<Vec<_>>(),
        vec![[0, 0, 0], [1, 1, 64], [2, 1, 129]]
    );
}

#[test]
fn the_skin_matches_brute_force() {
    // an irregular blob crossing word boundaries along z and touching the lattice's faces
    let mut s = SiteSet::empty(&lattice([9, 8, 140]));
    for i in 0..9 {
        for j in 0..8 {
            for k in 0..140 {
                let inside = (i * 7 + j * 3 + k) % 11 != 0 && (k + i) % 37 > 2 && !(i == 4 && j == 4);
                if inside {
                    s.insert(i, j, k);
                }
            }
        }
    }
    for layers in [0, 1, 2, 3, 5] {
        for beyond in [false, true] {
            let fast: Vec<_> = s.within_layers_of_outside(layers, beyond).iter().collect();
            assert_eq!(
                fast,
                brute_skin(&s, layers, beyond),
                "layers {layers}, beyond {beyond}"
            );
        }
    }
}

#[test]
fn set_bits_sets_exactly_the_range() {
    for (lo, hi) in [(0, 0), (0, 1), (3, 64), (63, 65), (0, 192), (70, 191), (5, 500)] {
        let mut column = vec![0u64; 3];
        set_bits(&mut column, lo..hi);
        let set: Vec<usize> = (0..192).filter(|k| column[k / 64] >> (k % 64) & 1 == 1).collect();
        assert_eq!(set, (lo..hi.min(192)).collect::<Vec<_>>());
    }
}

#[test]
fn dilation_along_z_reaches_across_words() {
    let mut column = vec![0u64; 4];
    column[1] = 1 << 10; // bit 74
    dilate_bits(&mut column, 70);
    let set: Vec<usize> = (0..256).filter(|k| column[k / 64] >> (k % 64) & 1 == 1).collect();
    assert_eq!(set, (4..=144).collect::<Vec<_>>());
}
