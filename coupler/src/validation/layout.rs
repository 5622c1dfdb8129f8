//! Where the validation page and its data live, relative to the workspace root.

use std::path::{Path, PathBuf};

/// The files `coupler validation` reads and writes, under one workspace root.
#[derive(Debug, Clone)]
pub struct Layout {
    pub root: PathBuf,
}

/// A `coupler report` fragment the page includes: its file under docs/validation/ and its heading.
pub struct Fragment {
    pub file: &'static str,
    pub title: &'static str,
}

/// The report's fragments, in the page's order: CI-sized and `--full` accuracy, then stability.
pub const FRAGMENTS: [Fragment; 4] = [
    Fragment {
        file: "report-accuracy.md",
        title: "Accuracy (CI-sized ladders)",
    },
    Fragment {
        file: "report-accuracy-full.md",
        title: "Accuracy (`--full` ladders)",
    },
    Fragment {
        file: "report-stability.md",
        title: "Stability (CI-sized families)",
    },
    Fragment {
        file: "report-stability-full.md",
        title: "Stability (`--full` families)",
    },
];

impl Layout {
    pub fn new(root: &Path) -> Layout {
        Layout {
            root: root.to_path_buf(),
        }
    }

    /// docs/: the folder the page and its figures' links are relative to.
    pub fn docs(&self) -> PathBuf {
        self.root.join("docs")
    }

    /// docs/validation.md, the generated page.
    pub fn page(&self) -> PathBuf {
        self.docs().join("validation.md")
    }

    /// docs/validation/: the page's data.
    pub fn data(&self) -> PathBuf {
        self.docs().join("validation")
    }

    /// docs/validation/records/: one `<id>.toml` per row.
    pub fn records(&self) -> PathBuf {
        self.data().join("records")
    }

    /// docs/validation/groups.toml: the capability groups and which records each holds.
    pub fn groups(&self) -> PathBuf {
        self.data().join("groups.toml")
    }

    /// The report fragment `file` (one of [`FRAGMENTS`]).
    pub fn fragment(&self, file: &str) -> PathBuf {
        self.data().join(file)
    }

    /// The folder the report's figures are copied to: docs/img/report or docs/img/report-full.
    pub fn figures(&self, full: bool) -> PathBuf {
        self.docs().join(Self::figures_link(full))
    }

    /// The figures' folder as the page links it (relative to docs/).
    pub fn figures_link(full: bool) -> &'static str {
        if full {
            "img/report-full"
        } else {
            "img/report"
        }
    }

    /// README.md, whose summary table is rewritten between its markers.
    pub fn readme(&self) -> PathBuf {
        self.root.join("README.md")
    }
}
