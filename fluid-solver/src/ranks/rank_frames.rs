//! The frames of a fluid on MPI ranks: each rank writes its piece of frame k,
//! `NAME_kkkkk_rRRRR.vtu`, and once every piece is whole rank 0 writes the frame's index
//! `NAME_kkkkk.pvtu` and adds it to the PVD series, which ParaView opens as one data set. A run
//! stopped at any moment leaves no index naming a piece that is missing or cut.

use super::mpi_link::RankLink;
use crate::output::vtu;
use crate::particles::Particles;
use schemas::participant::DiscardProgress;
use schemas::pvd::Collection;
use std::path::{Path, PathBuf};

/// A fluid's frames on ranks: where, and the frame due next.
pub struct RankFrames {
    dir: PathBuf,
    name: String,
    /// Rank 0's series of indexes (the other ranks keep theirs empty).
    series: Collection,
    next: u64,
}

impl RankFrames {
    /// Frames of fluid `name` in `dir`, from frame 0.
    pub fn new(dir: &Path, name: &str) -> RankFrames {
        RankFrames {
            dir: dir.to_path_buf(),
            name: name.to_string(),
            series: Collection::new(dir.join(format!("{name}.pvd"))),
            next: 0,
        }
    }

    /// Continues after `next` frames, rank 0's `series` (time, index) already written: rank 0
    /// writes the PVD again with them (the others never touch it).
    pub fn continue_after(
        &mut self,
        link: &RankLink,
        next: u64,
        series: Vec<(f64, String)>,
    ) -> Result<(), String> {
        self.next = next;
        if link.rank() != 0 {
            return Ok(());
        }
        let pvd = self.dir.join(format!("{}.pvd", self.name));
        self.series = Collection::resumed(pvd.clone(), series)
            .map_err(|e| format!("cannot continue {}: {e}", pvd.display()))?;
        Ok(())
    }

    /// The frame written next (frames written so far).
    pub fn next(&self) -> u64 {
        self.next
    }

    /// Rank 0's series (time, index file).
    pub fn series(&self) -> &[(f64, String)] {
        self.series.frames()
    }

    /// Writes this rank's `piece` of the frame at `time`, then (rank 0, once every rank's piece
    /// is written) its index and series entry. Every rank calls it; an error on any rank is an
    /// error on every rank, rank 0's naming the rank ([`RankLink::agree`]).
    pub fn write(&mut self, link: &RankLink, time: f64, piece: &Particles) -> Result<(), String> {
        let k = self.next;
        let piece_name = |r: usize| format!("{}_{k:05}_r{r:04}.vtu", self.name);
        let path = self.dir.join(piece_name(link.rank()));
        let written = vtu::write_vtu(&path, piece, &mut DiscardProgress)
            .map_err(|e| format!("cannot write {}: {e}", path.display()));
        link.agree(written)?;
        if link.rank() == 0 {
            let index = format!("{}_{k:05}.pvtu", self.name);
            let pieces: Vec<String> = (0..link.size()).map(piece_name).collect();
            let path = self.dir.join(&index);
            vtu::write_pvtu(&path, &pieces).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            self.series.add(time, &index).map_err(|e| {
                format!(
                    "cannot write {}: {e}",
                    self.dir.join(format!("{}.pvd", self.name)).display()
                )
            })?;
        }
        self.next += 1;
        Ok(())
    }
}
