//! `coupler report --readme`: the README's accuracy and stability sections are the latest
//! report's own Markdown, put between marker comments, with its figures copied beside the README.

use std::path::Path;

pub const ACCURACY: (&str, &str) = ("<!-- report:accuracy:start -->", "<!-- report:accuracy:end -->");
pub const STABILITY: (&str, &str) = ("<!-- report:stability:start -->", "<!-- report:stability:end -->");

/// Replaces the text between `markers` in `text` with `body`; None when the markers are missing.
pub fn replace_between(text: &str, markers: (&str, &str), body: &str) -> Option<String> {
    let start = text.find(markers.0)? + markers.0.len();
    let end = start + text[start..].find(markers.1)?;
    Some(format!("{}\n{}\n{}", &text[..start], body.trim(), &text[end..]))
}

/// Puts `report_dir`'s `accuracy.md` and `stability.md` (those that exist) into `readme`
/// between their markers, copying the PNGs they show into `figures` (relative to the README)
/// and pointing the links there.
pub fn update(readme: &Path, report_dir: &Path, figures: &str) -> Result<Vec<String>, String> {
    let mut text =
        std::fs::read_to_string(readme).map_err(|e| format!("cannot read {}: {e}", readme.display()))?;
    let base = readme.parent().unwrap_or(Path::new("."));
    let mut done = Vec::new();
    for (file, markers) in [("accuracy.md", ACCURACY), ("stability.md", STABILITY)] {
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
}
