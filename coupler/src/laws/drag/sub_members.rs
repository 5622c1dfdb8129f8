//! Members cut into sub-members of length about the fluid particle size (S2 §4(1)c): each member
//! of the frame's geometry is cut into `n = ⌈L / d⌉` equal pieces (so each piece is at most `d`
//! long), fixed in element coordinates when the geometry is declared; the pieces stretch with
//! the member as it deforms.

use schemas::message::Geometry;

/// One sub-member: where it sits in its member and the member's section.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SubMember {
    /// The member's end nodes (frame node indices).
    pub nodes: [usize; 2],
    /// Centroid in element coordinates, ξ ∈ (−1, 1) (S2-22, S2-23).
    pub xi: f64,
    /// Share of the member's length: the piece is `fraction × L` long.
    pub fraction: f64,
    /// Projected width D of the member [m] (S2-19).
    pub width: f64,
    /// Cross-section area A of the member [m²] (S2-21).
    pub area: f64,
}

/// Cuts every member of `geometry` (node positions `positions`, 3 per node) into pieces at most
/// `length` long. Members whose nodes are not in `positions` are refused.
pub fn cut(geometry: &Geometry, positions: &[f64], length: f64) -> Result<Vec<SubMember>, String> {
    let nodes = positions.len() / 3;
    let mut pieces = Vec::new();
    for (m, pair) in geometry.member_nodes.chunks_exact(2).enumerate() {
        let (a, b) = (pair[0] as usize, pair[1] as usize);
        if a >= nodes || b >= nodes {
            return Err(format!(
                "member {m} joins nodes {a} and {b}, but the structure reports {nodes} node positions"
            ));
        }
        let (Some(&width), Some(&area)) = (geometry.member_width.get(m), geometry.member_area.get(m)) else {
            return Err(format!("member {m} has no width or area in the geometry"));
        };
        let span: f64 = (0..3)
            .map(|c| (positions[3 * b + c] - positions[3 * a + c]).powi(2))
            .sum::<f64>()
            .sqrt();
        let n = (span / length - 1e-9).ceil().max(1.0) as usize;
        for i in 0..n {
            pieces.push(SubMember {
                nodes: [a, b],
                xi: -1.0 + (2 * i + 1) as f64 / n as f64,
                fraction: 1.0 / n as f64,
                width,
                area,
            });
        }
    }
    Ok(pieces)
}
