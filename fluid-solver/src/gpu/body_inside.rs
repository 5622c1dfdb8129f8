//! The instability detector's "inside a body" check on the device (`shaders/body_inside.wgsl`):
//! the rule of [`BodyInterior`] at each body's present pose, which the device holds already
//! (`BODY_KIN`). Its data sit in the solid sites' buffer after the tank's sites (the kernels bind
//! [`super::device::STORAGE_BUFFERS`] storage buffers, near what some devices allow): a table of
//! [`ENTRY`] words per body, then each mesh body's sites, one bit per site of the block of the
//! tank's lattice that holds them ([`SolidBits`]).
//!
//! Body `b`'s entry, at word `table + ENTRY b`: its kind ([`BOX`] or [`SITES`]); for a box body
//! its half extents less half a spacing (three f32), for a mesh body its sites' lattice origin
//! less its initial centre (three f32), that lattice's sites per axis (three u32) and the word
//! where its bits start.

use super::solids::SolidBits;
use crate::particles::body_interior::BodyInterior;

/// Words per body in the table.
pub const ENTRY: usize = 8;
/// Kind of a box body's entry (`BODY_BOX` in the shader).
pub const BOX: u32 = 0;
/// Kind of a mesh body's entry.
pub const SITES: u32 = 1;

/// The table and the mesh bodies' bits for `bodies`, to be written from word `table` of the
/// buffer on; an error when a body's sites are more than a u32 numbers.
pub fn words(bodies: &[BodyInterior], table: usize) -> Result<Vec<u32>, String> {
    let mut head = Vec::with_capacity(ENTRY * bodies.len());
    let mut bits: Vec<u32> = Vec::new();
    let f32_bits = |v: f64| (v as f32).to_bits();
    for (b, body) in bodies.iter().enumerate() {
        match body {
            BodyInterior::Box(half) => {
                head.push(BOX);
                head.extend(half.map(f32_bits));
                head.extend([0; 4]);
            }
            BodyInterior::Sites { sites, centre } => {
                let s = SolidBits::of(sites, &format!("body {b}'s"))?;
                let start = u32::try_from(table + ENTRY * bodies.len() + bits.len())
                    .map_err(|_| format!("body {b}'s sites start past the GPU path's 2³² words; use a coarser spacing or backend = \"cpu\""))?;
                head.push(SITES);
                head.extend((0..3).map(|a| f32_bits(s.origin[a] - centre[a])));
                head.extend(s.n);
                head.push(start);
                bits.extend(s.words);
            }
        }
    }
    head.extend(bits);
    Ok(head)
}
