//! Mesh solids and terrains (`[[solid]]`, `[[terrain]]`) on the device. Their skins are fixed wall
//! particles of the initial state, uploaded and stepped like the tank's walls; what the device
//! adds is the instability detector's "inside a solid" check
//! ([`crate::particles::solid_sites::SolidSites::deep_inside`]), which reads one bit per site of
//! the tank's lattice (`shaders/solids.wgsl`). A mesh body's sites take the same form
//! ([`super::body_inside`]).

use schemas::geometry::SiteSet;

/// The solid sites as the device holds them: the lattice's origin, spacing and sites per axis,
/// and one bit per site, site (i, j, k) at bit i + n_x (j + n_y k) of the words.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidBits {
    pub origin: [f64; 3],
    pub spacing: f64,
    pub n: [u32; 3],
    pub words: Vec<u32>,
}

impl SolidBits {
    /// The device's bits of `solid` (skin and buried sites); an error naming `whose` sites
    /// (e.g. "the mesh solids' and terrains'") when the lattice has more sites than a u32 numbers.
    pub fn of(solid: &SiteSet, whose: &str) -> Result<SolidBits, String> {
        let l = solid.lattice();
        let too_many = || {
            format!(
                "{whose} lattice of {} × {} × {} sites is more than the GPU path numbers (2³² sites); use a coarser spacing or backend = \"cpu\"",
                l.n[0], l.n[1], l.n[2]
            )
        };
        let n: Vec<u32> =
            l.n.iter()
                .map(|&v| u32::try_from(v))
                .collect::<Result<_, _>>()
                .map_err(|_| too_many())?;
        let sites = n
            .iter()
            .try_fold(1u32, |acc, &v| acc.checked_mul(v))
            .ok_or_else(too_many)?;
        let (nx, ny) = (l.n[0], l.n[1]);
        let mut words = vec![0u32; sites.div_ceil(32) as usize];
        for [i, j, k] in solid.iter() {
            let bit = i + nx * (j + ny * k);
            words[bit / 32] |= 1 << (bit % 32);
        }
        Ok(SolidBits {
            origin: l.origin,
            spacing: l.spacing,
            n: [n[0], n[1], n[2]],
            words,
        })
    }
}
