//! The documentation's links and file paths resolve inside the repository: every relative
//! Markdown link in the READMEs and `docs/`, every repository path written in backticks there
//! (`fluid-solver/src/isph/ppe.rs`), and every mention of `physics.md` anywhere (code comments
//! cite it as `docs/physics.md §N`). A moved file or a renamed note fails here, naming the
//! document, the line and the target.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

/// Files under `dir` whose name ends with one of `exts`, skipping build and output folders.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if !matches!(name.as_str(), "target" | "out" | ".git") {
                files(&path, exts, out);
            }
        } else if exts.iter().any(|e| name.ends_with(e)) {
            out.push(path);
        }
    }
}

/// The Markdown documents a reader follows (the report's fragments in docs/validation/ are
/// data that `coupler validation` puts into docs/validation.md, where their links are checked).
fn documents() -> Vec<PathBuf> {
    let mut docs = Vec::new();
    files(&root(), &[".md"], &mut docs);
    let fragments = root().join("docs/validation");
    docs.retain(|d| !d.starts_with(&fragments));
    docs
}

/// Relative link targets `[text](target)` on a line, without their `#anchor`.
fn link_targets(line: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].split('#').next().unwrap_or("").trim();
        if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") {
            targets.push(target.to_string());
        }
        rest = &after[end..];
    }
    targets
}

/// Repository paths in backticks on a line: a crate or top folder, then `/`, ending in a
/// file extension we keep (`.rs`, `.md`, `.toml`, `.wgsl`, `.csv`, `.py`).
fn code_paths(line: &str) -> Vec<String> {
    const TOPS: [&str; 7] = [
        "fluid-solver/",
        "structure-solver/",
        "coupler/",
        "schemas/",
        "tests/",
        "cases/",
        "docs/",
    ];
    const EXTS: [&str; 6] = [".rs", ".md", ".toml", ".wgsl", ".csv", ".py"];
    line.split('`')
        .skip(1)
        .step_by(2)
        .map(|s| s.split("::").next().unwrap_or(s).trim())
        .filter(|s| TOPS.iter().any(|t| s.starts_with(t)) && EXTS.iter().any(|e| s.ends_with(e)))
        .filter(|s| !s.contains(['*', '{', '<', ' ', '…']))
        .map(str::to_string)
        .collect()
}

#[test]
fn every_relative_link_and_backticked_path_in_the_docs_resolves() {
    let root = root();
    let mut broken = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).expect("readable document");
        let dir = doc.parent().expect("a document's folder");
        let mut fenced = false;
        for (n, line) in text.lines().enumerate() {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
                continue;
            }
            if fenced {
                continue;
            }
            for target in link_targets(line) {
                if !dir.join(&target).exists() {
                    broken.push(format!(
                        "{}:{}: link {target}",
                        doc.strip_prefix(&root).unwrap_or(&doc).display(),
                        n + 1
                    ));
                }
            }
            for path in code_paths(line) {
                if !root.join(&path).exists() && !dir.join(&path).exists() {
                    broken.push(format!(
                        "{}:{}: path {path}",
                        doc.strip_prefix(&root).unwrap_or(&doc).display(),
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(
        broken.is_empty(),
        "{} broken links or paths:\n{}",
        broken.len(),
        broken.join("\n")
    );
}

#[test]
fn every_mention_of_physics_md_names_the_file_in_the_repository() {
    let root = root();
    assert!(
        root.join("docs/physics.md").is_file(),
        "docs/physics.md is missing"
    );
    let mut sources = Vec::new();
    files(&root, &[".rs", ".toml", ".wgsl", ".py"], &mut sources);
    let mut stale = Vec::new();
    for file in sources
        .into_iter()
        .filter(|f| !f.ends_with("tests/tests/doc_links.rs"))
    {
        let text = std::fs::read_to_string(&file).unwrap_or_default();
        for (n, line) in text.lines().enumerate() {
            let mut rest = line;
            while let Some(i) = rest.find("physics.md") {
                if !rest[..i].ends_with("docs/") {
                    stale.push(format!(
                        "{}:{}: {}",
                        file.strip_prefix(&root).unwrap_or(&file).display(),
                        n + 1,
                        line.trim()
                    ));
                }
                rest = &rest[i + "physics.md".len()..];
            }
        }
    }
    assert!(
        stale.is_empty(),
        "mentions of physics.md that do not say docs/physics.md:\n{}",
        stale.join("\n")
    );
}
