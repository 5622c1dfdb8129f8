//! [`VtuSeries`]: frame snapshots `frame-NNNNN.vtu` (written by the frame) and the ParaView
//! collection `frame.pvd` that lists them with their times.

use crate::frame::Frame;
use std::io;
use std::path::{Path, PathBuf};

/// Snapshots written so far.
pub struct VtuSeries {
    dir: PathBuf,
    entries: Vec<(f64, String)>,
}

impl VtuSeries {
    pub fn new(dir: &Path) -> Self {
        Self {
            dir: dir.to_path_buf(),
            entries: Vec::new(),
        }
    }

    /// Writes the frame at time `t` and rewrites the `.pvd` so that it is valid after every call.
    pub fn write(&mut self, frame: &Frame, t: f64) -> io::Result<()> {
        let name = format!("frame-{:05}.vtu", self.entries.len());
        frame.write_vtu(&self.dir.join(&name))?;
        self.entries.push((t, name));
        let mut pvd = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
        );
        for (t, file) in &self.entries {
            pvd.push_str(&format!(
                "<DataSet timestep=\"{t}\" part=\"0\" file=\"{file}\"/>\n"
            ));
        }
        pvd.push_str("</Collection>\n</VTKFile>\n");
        std::fs::write(self.dir.join("frame.pvd"), pvd)
    }
}
