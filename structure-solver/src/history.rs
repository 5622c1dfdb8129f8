//! [`HistoryWriter`]: the CSV histories of standalone mode, one file per declared point mass
//! (`point-NAME.csv`), body (`body-NAME.csv`) and frame node (`node-ID.csv`: position, velocity,
//! angular velocity and the rotation vector from the initial orientation), one row per output
//! time.

use crate::frame::Frame;
use crate::structure::Structure;
use schemas::case::structure::HistoryConfig;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// What one history file follows.
enum Source {
    Point(usize),
    Body(usize),
    Node(usize),
}

/// Open history files.
pub struct HistoryWriter {
    files: Vec<(Source, BufWriter<File>)>,
}

impl HistoryWriter {
    /// Creates the files in `dir` with their header rows. Names were validated with the case;
    /// an unknown one here is an error all the same.
    pub fn create(dir: &Path, cfg: &HistoryConfig, s: &Structure) -> Result<Self, String> {
        Self::open(dir, cfg, s, false)
    }

    /// Continues the files of a resumed run in `dir` (their header and earlier rows are there).
    pub fn append(dir: &Path, cfg: &HistoryConfig, s: &Structure) -> Result<Self, String> {
        Self::open(dir, cfg, s, true)
    }

    fn open(dir: &Path, cfg: &HistoryConfig, s: &Structure, append: bool) -> Result<Self, String> {
        let mut files = Vec::new();
        let open = |name: String, header: &str| -> Result<BufWriter<File>, String> {
            let path = dir.join(name);
            if append {
                return schemas::checkpoint::append(&path)
                    .map(BufWriter::new)
                    .map_err(|e| format!("cannot continue {}: {e}", path.display()));
            }
            let mut w = BufWriter::new(
                File::create(&path).map_err(|e| format!("cannot create {}: {e}", path.display()))?,
            );
            writeln!(w, "{header}").map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            Ok(w)
        };
        for p in &cfg.points {
            let i = s
                .point_index(p)
                .ok_or_else(|| format!("history: `{p}` is not a point mass"))?;
            files.push((
                Source::Point(i),
                open(format!("point-{p}.csv"), "t,ux,uy,uz,vx,vy,vz")?,
            ));
        }
        for b in &cfg.bodies {
            let i = s
                .body_index(b)
                .ok_or_else(|| format!("history: `{b}` is not a body"))?;
            let header = "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held";
            files.push((Source::Body(i), open(format!("body-{b}.csv"), header)?));
        }
        for &id in &cfg.nodes {
            let i = s
                .frame_node_index(id)
                .ok_or_else(|| format!("history: frame node {id} does not exist"))?;
            files.push((
                Source::Node(i),
                open(format!("node-{id}.csv"), "t,x,y,z,vx,vy,vz,wx,wy,wz,rx,ry,rz")?,
            ));
        }
        Ok(Self { files })
    }

    /// Appends one row per file for the current state of `s`.
    pub fn record(&mut self, s: &Structure) -> io::Result<()> {
        let t = s.time();
        let (pu, pv) = (s.point_displacement(), s.point_velocity());
        let (pose, vel) = (s.body_pose(), s.body_velocity());
        let (np, nv) = (s.node_position(), s.node_velocity());
        let nr = s.frame().map(Frame::node_rotations).unwrap_or_default();
        for (source, w) in &mut self.files {
            let row: Vec<f64> = match *source {
                Source::Point(i) => pu[3 * i..3 * i + 3]
                    .iter()
                    .chain(&pv[3 * i..3 * i + 3])
                    .copied()
                    .collect(),
                Source::Body(i) => {
                    let held = if s.is_held(i) { 1.0 } else { 0.0 };
                    pose[7 * i..7 * i + 7]
                        .iter()
                        .chain(&vel[6 * i..6 * i + 6])
                        .copied()
                        .chain([held])
                        .collect()
                }
                Source::Node(i) => np[3 * i..3 * i + 3]
                    .iter()
                    .chain(&nv[6 * i..6 * i + 6])
                    .chain(&nr[3 * i..3 * i + 3])
                    .copied()
                    .collect(),
            };
            let mut line = t.to_string();
            for v in row {
                line.push_str(&format!(",{v}"));
            }
            line.push('\n');
            w.write_all(line.as_bytes())?;
        }
        // Each row reaches the file whole as it is written, so a run that ends abnormally keeps
        // every row before its end and never a partial one.
        self.flush()
    }

    /// Flushes every file.
    pub fn flush(&mut self) -> io::Result<()> {
        self.files.iter_mut().try_for_each(|(_, w)| w.flush())
    }
}
