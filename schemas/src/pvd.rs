//! ParaView's time series file (`.pvd`): a collection listing each frame file with its time. It is
//! rewritten atomically after every frame, so it is valid at any moment of a run, also after a crash.

use std::io;
use std::path::PathBuf;

/// A `.pvd` file and the frames it lists.
#[derive(Debug, Clone)]
pub struct Collection {
    path: PathBuf,
    frames: Vec<(f64, String)>,
}

impl Collection {
    /// A series written to `path`; frame files are named relative to its folder.
    pub fn new(path: PathBuf) -> Collection {
        Collection {
            path,
            frames: Vec::new(),
        }
    }

    /// A series that continues `frames` (a resumed run): the `.pvd` is rewritten to list them.
    pub fn resumed(path: PathBuf, frames: Vec<(f64, String)>) -> io::Result<Collection> {
        let c = Collection { path, frames };
        c.rewrite()?;
        Ok(c)
    }

    /// Time and file of each frame listed so far.
    pub fn frames(&self) -> &[(f64, String)] {
        &self.frames
    }

    /// Frames listed so far.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Whether no frame is listed yet.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Adds the frame file `file` (relative to the `.pvd`'s folder) at `time` and rewrites the `.pvd`.
    pub fn add(&mut self, time: f64, file: &str) -> io::Result<()> {
        self.frames.push((time, file.to_string()));
        self.rewrite()
    }

    /// Writes the `.pvd` listing the frames.
    fn rewrite(&self) -> io::Result<()> {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
             <Collection>\n",
        );
        for (t, f) in &self.frames {
            s.push_str(&format!(
                "<DataSet timestep=\"{t}\" group=\"\" part=\"0\" file=\"{f}\"/>\n"
            ));
        }
        s.push_str("</Collection>\n</VTKFile>\n");
        crate::atomic_file::write(&self.path, s)
    }
}
