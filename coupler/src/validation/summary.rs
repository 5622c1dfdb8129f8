//! The README's validation summary: one row per capability group with its headline error and a
//! link into docs/validation.md, between marker comments the README's author places.

use super::cells;
use super::groups::Group;
use schemas::markdown::{github_anchor as anchor, table_cell};
use schemas::validation::Record;

pub const MARKERS: (&str, &str) = (
    "<!-- validation:summary:start -->",
    "<!-- validation:summary:end -->",
);

/// The summary table, one row per group, each linking to `page#group` (`page` "" on the page itself).
pub fn table(groups: &[(Group, Vec<Record>)], page: &str) -> String {
    let mut table =
        String::from("| capability | rows | headline comparison | error | bound |\n|---|---|---|---|---|\n");
    for (group, rows) in groups {
        table.push_str(&format!(
            "| [{}]({page}#{}) | {} | {} |\n",
            group.title,
            anchor(&group.title),
            rows.len(),
            headline(group, rows)
        ));
    }
    table
}

/// The cells of `group`'s headline record: its comparison, error and bound.
fn headline(group: &Group, rows: &[Record]) -> String {
    match rows.iter().find(|r| r.id == group.headline) {
        Some(r) => format!(
            "{}, against {} | {} | {}",
            table_cell(&r.capability),
            table_cell(&r.reference),
            cells::error(r),
            r.bound.map_or("–".into(), |b| cells::quantity(b, &r.unit))
        ),
        None => format!("(no record `{}` yet) | | ", table_cell(&group.headline)),
    }
}

/// `text` with what lies between `markers` replaced by `body`; None when the markers are missing.
pub fn replace_between(text: &str, markers: (&str, &str), body: &str) -> Option<String> {
    let start = text.find(markers.0)? + markers.0.len();
    let end = start + text[start..].find(markers.1)?;
    Some(format!("{}\n{}\n{}", &text[..start], body.trim(), &text[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_only_between_markers() {
        let text = format!("a\n{}\nold\n{}\nb\n", MARKERS.0, MARKERS.1);
        let new = replace_between(&text, MARKERS, "new\n");
        assert_eq!(new, Some(format!("a\n{}\nnew\n{}\nb\n", MARKERS.0, MARKERS.1)));
        assert!(replace_between("no markers", MARKERS, "x").is_none());
    }
}
