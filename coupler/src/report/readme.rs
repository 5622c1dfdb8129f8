//! `coupler report --readme`: the README's accuracy and stability sections are the latest
//! report's own Markdown, put between marker comments, with its figures copied beside the README.
//! A `--full` report goes between its own markers (`report:accuracy-full`,
//! `report:stability-full`), its figures into a `full` folder beside the CI-sized ones.

use std::path::Path;

pub const ACCURACY: (&str, &str) = ("<!-- report:accuracy:start -->", "<!-- report:accuracy:end -->");
pub const STABILITY: (&str, &str) = ("<!-- report:stability:start -->", "<!-- report:stability:end -->");
pub const ACCURACY_FULL: (&str, &str) = (
    "<!-- report:accuracy-full:start -->",
    "<!-- report:accuracy-full:end -->",
);
pub const STABILITY_FULL: (&str, &str) = (
    "<!-- report:stability-full:start -->",
    "<!-- report:stability-full:end -->",
);

/// Replaces the text between `markers` in `text` with `body`; None when the markers are missing.
pub fn replace_between(text: &str, markers: (&str, &str), body: &str) -> Option<String> {
    let start = text.find(markers.0)? + markers.0.len();
    let end = start + text[start..].find(markers.1)?;
    Some(format!("{}\n{}\n{}", &text[..start], body.trim(), &text[end..]))
}

/// Puts `report_dir`'s `accuracy.md` and `stability.md` (those that exist) into `readme`
/// between their markers (those of a `full` report when it is one), copying the PNGs they show
/// into `figures` (relative to the README) and pointing the links there.
pub fn update(readme: &Path, report_dir: &Path, figures: &str, full: bool) -> Result<Vec<String>, String> {
    let mut text =
        std::fs::read_to_string(readme).map_err(|e| format!("cannot read {}: {e}", readme.display()))?;
    let base = readme.parent().unwrap_or(Path::new("."));
    let mut done = Vec::new();
    let markers = match full {
        true => [ACCURACY_FULL, STABILITY_FULL],
        false => [ACCURACY, STABILITY],
    };
    for (file, markers) in ["accuracy.md", "stability.md"].into_iter().zip(markers) {
        let Ok(body) = std::fs::read_to_string(report_dir.join(file)) else {
            continue;
        };
        let body = relink(&demote(&body), report_dir, &base.join(figures), figures)?;
        text = replace_between(&text, markers, &body).ok_or_else(|| {
            format!(
                "{} has no `{}` … `{}` markers for {file}; add them where the section goes",
                readme.display(),
                markers.0,
                markers.1
            )
        })?;
        done.push(file.to_string());
    }
    if done.is_empty() {
        return Err(format!(
            "{} holds no accuracy.md or stability.md: run `coupler report CASE… --out {}` first",
            report_dir.display(),
            report_dir.display()
        ));
    }
    std::fs::write(readme, text).map_err(|e| format!("cannot write {}: {e}", readme.display()))?;
    Ok(done)
}

/// Headings one level deeper: the report's `###` sections sit under the README's `###` headings.
fn demote(body: &str) -> String {
    body.lines()
        .map(|l| {
            if l.starts_with('#') {
                format!("#{l}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Copies every `](NAME.png)` the Markdown shows from `from` to `to` and links it as `prefix/NAME.png`.
fn relink(body: &str, from: &Path, to: &Path, prefix: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = body;
    while let Some(i) = rest.find("](") {
        let (head, tail) = rest.split_at(i + 2);
        out.push_str(head);
        let end = tail.find(')').unwrap_or(tail.len());
        let link = &tail[..end];
        if link.ends_with(".png") && !link.contains('/') {
            std::fs::create_dir_all(to).map_err(|e| format!("cannot create {}: {e}", to.display()))?;
            std::fs::copy(from.join(link), to.join(link)).map_err(|e| {
                format!(
                    "cannot copy {} to {}: {e}",
                    from.join(link).display(),
                    to.display()
                )
            })?;
            out.push_str(&format!("{prefix}/{link}"));
        } else {
            out.push_str(link);
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_only_between_markers() {
        let text = format!("a\n{}\nold\n{}\nb\n", ACCURACY.0, ACCURACY.1);
        let new = replace_between(&text, ACCURACY, "new").unwrap();
        assert_eq!(new, format!("a\n{}\nnew\n{}\nb\n", ACCURACY.0, ACCURACY.1));
        assert!(replace_between("no markers", ACCURACY, "x").is_none());
    }

    #[test]
    fn a_full_report_goes_between_its_own_markers() {
        let dir = std::env::temp_dir().join(format!("readme-full-{}", std::process::id()));
        let report = dir.join("report");
        std::fs::create_dir_all(&report).unwrap();
        std::fs::write(report.join("stability.md"), "### family\n\n![map](map.png)\n").unwrap();
        std::fs::write(report.join("accuracy.md"), "### case\n\nfull ladder\n").unwrap();
        std::fs::write(report.join("map.png"), b"png").unwrap();
        let readme = dir.join("README.md");
        let ci = format!("{}\nci\n{}", STABILITY.0, STABILITY.1);
        let full = format!("{}\n{}", STABILITY_FULL.0, STABILITY_FULL.1);
        let accuracy_full = format!("{}\n{}", ACCURACY_FULL.0, ACCURACY_FULL.1);
        std::fs::write(&readme, format!("{ci}\n{accuracy_full}\n{full}\n")).unwrap();
        let done = update(&readme, &report, "docs/full", true).unwrap();
        assert_eq!(done, vec!["accuracy.md".to_string(), "stability.md".to_string()]);
        let text = std::fs::read_to_string(&readme).unwrap();
        assert!(text.starts_with(&ci), "the CI-sized section stays: {text}");
        assert!(text.contains("#### family\n\n![map](docs/full/map.png)\n<!-- report:stability-full:end -->"));
        assert!(text.contains(&format!(
            "{}\n#### case\n\nfull ladder\n{}",
            ACCURACY_FULL.0, ACCURACY_FULL.1
        )));
        assert!(dir.join("docs/full/map.png").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
