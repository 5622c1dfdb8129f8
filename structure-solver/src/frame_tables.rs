//! [`FrameTables`]: the frame's CSV tables of a structure run — `section-forces.csv` (one row per
//! element end at every history time: `t, member, element, end, node, N, Vy, Vz, T, My, Mz`, local
//! axes of the element, N in tension positive) and `hinge-events.csv` (one row per hinge forming or
//! closing and per fracture, written as they are reached: `t, event, member, element, node, N, Vy,
//! Vz, T, My, Mz, f`, f the yield function there or S2-17's left side for a fracture) and, with a
//! history, `energy.csv` (one row per history time: `t, kinetic, strain, plastic, shift, damping,
//! algorithmic, external, residual` in J; the columns and their equations in `frame/energy.rs`).
//!
//! Every row reaches its file whole as it is written (one write and a flush: a hinge event, an
//! energy row, or all the section-force rows of one history time together), so a run that ends
//! abnormally, even killed, leaves whole rows up to its last history time.

use crate::frame::Frame;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The open frame tables.
pub struct FrameTables {
    section_forces: Option<BufWriter<File>>,
    hinge_events: BufWriter<File>,
    /// `energy.csv`, when the frame keeps its energy account.
    energy: Option<BufWriter<File>>,
    /// Hinge events written so far.
    events_written: usize,
}

impl FrameTables {
    /// Creates the tables in `dir` (`section-forces.csv` only with `section_forces`).
    pub fn create(dir: &Path, section_forces: bool, energy: bool) -> io::Result<Self> {
        let open = |name: &str, header: &str| -> io::Result<BufWriter<File>> {
            let mut w = BufWriter::new(File::create(dir.join(name))?);
            // on disk at once: a run that ends (or is checkpointed) before the first row has it
            writeln!(w, "{header}")?;
            w.flush()?;
            Ok(w)
        };
        Ok(Self {
            section_forces: section_forces
                .then(|| open("section-forces.csv", "t,member,element,end,node,N,Vy,Vz,T,My,Mz"))
                .transpose()?,
            hinge_events: open(
                "hinge-events.csv",
                "t,event,member,element,node,N,Vy,Vz,T,My,Mz,f",
            )?,
            energy: energy
                .then(|| {
                    open(
                        "energy.csv",
                        "t,kinetic,strain,plastic,shift,damping,algorithmic,external,residual",
                    )
                })
                .transpose()?,
            events_written: 0,
        })
    }

    /// Continues the tables of a resumed run in `dir` (cut back to their length at the checkpoint),
    /// `events_written` hinge events being in `hinge-events.csv` already.
    pub fn append(dir: &Path, section_forces: bool, energy: bool, events_written: usize) -> io::Result<Self> {
        let open = |name: &str| -> io::Result<BufWriter<File>> {
            Ok(BufWriter::new(schemas::checkpoint::append(&dir.join(name))?))
        };
        Ok(Self {
            section_forces: section_forces.then(|| open("section-forces.csv")).transpose()?,
            hinge_events: open("hinge-events.csv")?,
            energy: energy.then(|| open("energy.csv")).transpose()?,
            events_written,
        })
    }

    /// Hinge events written so far.
    pub fn events_written(&self) -> usize {
        self.events_written
    }

    /// Writes the section forces of `frame` at time `t` (a history row) and its new hinge events.
    pub fn record(&mut self, frame: &Frame, t: f64, history_row: bool) -> io::Result<()> {
        let events = frame.hinge_events();
        for e in events.iter().skip(self.events_written) {
            let mut row = format!(
                "{},{},{},{},{}",
                e.time,
                e.kind.name(),
                e.member,
                e.element,
                e.node
            );
            for f in e.forces {
                row.push_str(&format!(",{f}"));
            }
            row.push_str(&format!(",{}\n", e.function));
            self.hinge_events.write_all(row.as_bytes())?;
            self.hinge_events.flush()?;
            self.events_written += 1;
        }
        if let (Some(w), Some(r), true) = (&mut self.energy, frame.energy(), history_row) {
            // one write and a flush per row: a run that ends abnormally leaves whole rows only
            let row = format!(
                "{t},{},{},{},{},{},{},{},{}\n",
                r.kinetic, r.strain, r.plastic, r.shift, r.damping, r.algorithmic, r.external, r.residual
            );
            w.write_all(row.as_bytes())?;
            w.flush()?;
        }
        let Some(w) = self.section_forces.as_mut().filter(|_| history_row) else {
            return Ok(());
        };
        // the rows of this history time in one write (a write and a flush per row would cost a
        // system call per element end)
        let nodes = frame.element_nodes();
        let mut rows = String::new();
        for (i, (forces, (member, _))) in frame
            .section_forces()
            .iter()
            .zip(frame.element_members())
            .enumerate()
        {
            for (end, f) in forces.iter().enumerate() {
                rows.push_str(&format!("{t},{member},{i},{end},{}", nodes[i][end]));
                for x in f {
                    rows.push_str(&format!(",{x}"));
                }
                rows.push('\n');
            }
        }
        w.write_all(rows.as_bytes())?;
        w.flush()
    }

    pub fn flush(&mut self) -> io::Result<()> {
        if let Some(w) = &mut self.energy {
            w.flush()?;
        }
        if let Some(w) = &mut self.section_forces {
            w.flush()?;
        }
        self.hinge_events.flush()
    }
}
