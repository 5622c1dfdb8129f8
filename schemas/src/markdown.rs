//! Markdown for the generated pages (the case-file reference, the validation page): the anchor
//! GitHub gives a heading, so a page can link to its own sections, and the text of a table cell.

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

/// `s` as a table cell: on one line (runs of white space, line ends included, become one
/// space) with `|` escaped.
pub fn table_cell(s: &str) -> String {
    s.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}
