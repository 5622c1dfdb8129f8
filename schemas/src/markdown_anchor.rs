//! The anchor GitHub gives a Markdown heading (lowercase; spaces become `-`; punctuation but
//! `-` and `_` dropped), so the generated pages (case-file reference, validation) can link to
//! their own sections.

/// The anchor of the heading `title`: "Structure: rigid bodies" → "structure-rigid-bodies".
pub fn github_anchor(title: &str) -> String {
    title
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::github_anchor;

    #[test]
    fn anchors_are_githubs() {
        assert_eq!(github_anchor("E-MPS fluid"), "e-mps-fluid");
        assert_eq!(github_anchor("Structure: rigid bodies"), "structure-rigid-bodies");
        assert_eq!(github_anchor("Frames (ASI-Gauss)"), "frames-asi-gauss");
        assert_eq!(github_anchor("`[[fluid.NAME.block]]`"), "fluidnameblock");
    }
}
