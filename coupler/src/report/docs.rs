//! `coupler report --docs`: the latest report's accuracy and stability Markdown become fragments of
//! docs/validation.md (`docs/validation/report-*.md`, included by `coupler validation`), with the
//! figures they show copied to docs/img/report/ (a `--full` report: its own fragments and
//! docs/img/report-full/).

use crate::validation::layout::Layout;
use std::path::Path;

/// Writes `report_dir`'s `accuracy.md` and `stability.md` (those that exist) as the fragments of
/// `layout` (those of a `full` report when it is one), copying the PNGs they show into the
/// figures' folder and pointing the links there. Returns the fragments written.
pub fn update(layout: &Layout, report_dir: &Path, full: bool) -> Result<Vec<String>, String> {
    let mut done = Vec::new();
    for report in ["accuracy", "stability"] {
        let Ok(body) = std::fs::read_to_string(report_dir.join(format!("{report}.md"))) else {
            continue;
        };
        let body = relink(
            &body,
            report_dir,
            &layout.figures(full),
            Layout::figures_link(full),
        )?;
        let file = fragment_name(report, full);
        let path = layout.fragment(&file);
        std::fs::create_dir_all(layout.data())
            .map_err(|e| format!("cannot create {}: {e}", layout.data().display()))?;
        schemas::atomic_file::write(&path, body.trim().to_string() + "\n")
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        done.push(file);
    }
    if done.is_empty() {
        return Err(format!(
            "{} holds no accuracy.md or stability.md: run `coupler report CASE… --out {}` first",
            report_dir.display(),
            report_dir.display()
        ));
    }
    Ok(done)
}

/// The fragment a report of kind `report` ("accuracy" or "stability") goes to.
pub fn fragment_name(report: &str, full: bool) -> String {
    match full {
        true => format!("report-{report}-full.md"),
        false => format!("report-{report}.md"),
    }
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
    fn a_full_report_goes_to_its_own_fragments_and_figures() {
        let dir = std::env::temp_dir().join(format!("report-docs-{}", std::process::id()));
        let report = dir.join("report");
        std::fs::create_dir_all(&report).unwrap_or_else(|e| panic!("{e}"));
        let write = |name: &str, text: &str| {
            std::fs::write(report.join(name), text).unwrap_or_else(|e| panic!("{e}"))
        };
        write("stability.md", "### family\n\n![map](map.png)\n");
        write("accuracy.md", "### case\n\nfull ladder\n");
        write("map.png", "png");
        let layout = Layout::new(&dir.join("root"));
        let done = update(&layout, &report, true).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(done, ["report-accuracy-full.md", "report-stability-full.md"]);
        let read = |name: &str| std::fs::read_to_string(layout.fragment(name)).unwrap_or_default();
        assert_eq!(
            read("report-stability-full.md"),
            "### family\n\n![map](img/report-full/map.png)\n"
        );
        assert_eq!(read("report-accuracy-full.md"), "### case\n\nfull ladder\n");
        assert!(dir.join("root/docs/img/report-full/map.png").exists());
        assert!(
            !layout.fragment("report-accuracy.md").exists(),
            "the CI-sized fragment is not touched"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_report_folder_without_markdown_is_an_error() {
        let layout = Layout::new(Path::new("/nonexistent-root"));
        let err = update(&layout, Path::new("/nonexistent-report"), false).expect_err("nothing to put");
        assert!(err.contains("run `coupler report CASE…"), "{err}");
    }
}
