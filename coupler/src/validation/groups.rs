//! The page's capability groups (docs/validation/groups.toml): each names the records it holds
//! by id patterns (`*` matches any run of characters), in the order its rows are shown, and the
//! record whose error heads the README's summary.

use schemas::validation::Record;
use serde::Deserialize;
use std::path::Path;

/// One capability group: a section of the page and a row of the summary.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Group {
    /// The section's heading, e.g. "E-MPS fluid".
    pub title: String,
    /// A sentence shown under the heading.
    #[serde(default)]
    pub about: String,
    /// The id of the record whose error the summary shows.
    pub headline: String,
    /// Id patterns of the group's records, in the order they are shown.
    pub records: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GroupsFile {
    group: Vec<Group>,
}

/// The groups of `path`, in the page's order.
pub fn load(path: &Path) -> Result<Vec<Group>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let file: GroupsFile = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(file.group)
}

/// The records of each group, in its patterns' order (then by id), and the records no group
/// holds. A record that two groups claim is an error naming both.
pub fn assign<'a>(
    groups: &[Group],
    records: &'a [Record],
) -> Result<(Vec<Vec<&'a Record>>, Vec<&'a Record>), String> {
    let mut members: Vec<Vec<(usize, &Record)>> = vec![Vec::new(); groups.len()];
    let mut orphans = Vec::new();
    for record in records {
        let claims: Vec<(usize, usize)> = groups
            .iter()
            .enumerate()
            .filter_map(|(g, group)| {
                let p = group.records.iter().position(|p| matches(p, &record.id))?;
                Some((g, p))
            })
            .collect();
        match claims[..] {
            [] => orphans.push(record),
            [(g, p)] => members[g].push((p, record)),
            [(a, _), (b, _), ..] => {
                return Err(format!(
                "record `{}` matches the groups `{}` and `{}`: make their patterns in groups.toml exclusive",
                record.id, groups[a].title, groups[b].title
            ))
            }
        }
    }
    let members = members
        .into_iter()
        .map(|mut m| {
            m.sort_by(|a, b| (a.0, &a.1.id).cmp(&(b.0, &b.1.id)));
            m.into_iter().map(|(_, r)| r).collect()
        })
        .collect();
    Ok((members, orphans))
}

/// Whether `id` matches `pattern`, where `*` stands for any run of characters.
pub fn matches(pattern: &str, id: &str) -> bool {
    let mut parts = pattern.split('*');
    let first = parts.next().unwrap_or_default();
    let Some(mut rest) = id.strip_prefix(first) else {
        return false;
    };
    let parts: Vec<&str> = parts.collect();
    let Some((last, middle)) = parts.split_last() else {
        return rest.is_empty();
    };
    for part in middle {
        match rest.find(part) {
            Some(i) => rest = &rest[i + part.len()..],
            None => return false,
        }
    }
    rest.len() >= last.len() && rest.ends_with(last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_match_exactly_or_around_their_stars() {
        assert!(matches("emps-front", "emps-front"));
        assert!(!matches("emps-front", "emps-front-l10"));
        assert!(matches("emps-*", "emps-front-l10"));
        assert!(matches("*-gpu-*", "oneoff-gpu-front"));
        assert!(matches("a*b*c", "a-x-b-y-c"));
        assert!(!matches("a*b*c", "a-x-c"));
        assert!(!matches("ab*ba", "aba"));
    }

    #[test]
    fn records_go_to_the_group_that_names_them_in_its_order() {
        let group = |title: &str, records: &[&str]| Group {
            title: title.into(),
            about: String::new(),
            headline: String::new(),
            records: records.iter().map(|s| s.to_string()).collect(),
        };
        let record = |id: &str| Record {
            id: id.into(),
            ..Default::default()
        };
        let records = [record("emps-a"), record("emps-b"), record("isph-a"), record("x")];
        let groups = [group("E-MPS", &["emps-b", "emps-*"]), group("ISPH", &["isph-*"])];
        let (members, orphans) = assign(&groups, &records).unwrap_or_else(|e| panic!("{e}"));
        let ids = |m: &[&Record]| m.iter().map(|r| r.id.clone()).collect::<Vec<_>>();
        assert_eq!(ids(&members[0]), ["emps-b", "emps-a"]);
        assert_eq!(ids(&members[1]), ["isph-a"]);
        assert_eq!(ids(&orphans), ["x"]);
        let overlapping = [group("E-MPS", &["emps-*"]), group("all", &["*"])];
        let err = assign(&overlapping, &records).expect_err("two groups claim emps-a");
        assert!(err.contains("`emps-a`"), "{err}");
    }
}
