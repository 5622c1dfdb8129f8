//! The slabs' transport between MPI ranks (cargo feature `mpi`): rank r steps slab r
//! ([`super::subdomain::Subdomain`]) and trades with ranks r − 1 and r + 1 what
//! [`super::decomposed`] trades between slabs in one process, the same particles in the same
//! order, so a run on N ranks steps as the same case in N slabs of one process.
//!
//! A message is one neighbour's particles encoded by serde into bincode 2 (`standard()`); each
//! rank posts its sends without blocking, then receives from its neighbours (sizes come with the
//! messages), so no pair of ranks waits on each other's send.

use super::subdomain::ToNeighbours;
use crate::particles::Particles;
use mpi::collective::SystemOperation;
use mpi::request::WaitGuard;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use mpi::Tag;

/// This process's place among the ranks and its link to them.
pub struct RankLink {
    world: SimpleCommunicator,
    /// Bytes this rank has sent its neighbours in [`RankLink::exchange`] so far.
    sent_bytes: std::cell::Cell<u64>,
    /// Finalizes MPI when dropped, after `world`.
    _universe: mpi::environment::Universe,
}

impl RankLink {
    /// Initializes MPI (once per process); an error when it is already initialized or the
    /// launcher's environment is broken.
    pub fn initialize() -> Result<RankLink, String> {
        let universe = mpi::initialize().ok_or("MPI was already initialized in this process")?;
        let world = universe.world();
        Ok(RankLink {
            world,
            sent_bytes: std::cell::Cell::new(0),
            _universe: universe,
        })
    }

    /// This rank, from 0.
    pub fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    /// Bytes this rank has sent its neighbours in exchanges so far (encoded particles).
    pub fn sent_bytes(&self) -> u64 {
        self.sent_bytes.get()
    }

    /// How many ranks run the case.
    pub fn size(&self) -> usize {
        self.world.size() as usize
    }

    /// Sends `sent[0]` to the rank on the left (r − 1) and `sent[1]` to the one on the right
    /// (r + 1) and returns what they sent this rank: `[from the left, from the right]`, empty at
    /// the ends. `phase` tags the messages of one exchange (messages between two ranks with one
    /// tag arrive in the order they were sent).
    pub fn exchange(&self, sent: &ToNeighbours, phase: Tag) -> Result<ToNeighbours, String> {
        let (rank, size) = (self.rank(), self.size());
        let left = (rank > 0).then(|| rank - 1);
        let right = (rank + 1 < size).then_some(rank + 1);
        let encode = |p: &Particles| {
            bincode::serde::encode_to_vec(p, bincode::config::standard())
                .map_err(|e| format!("rank {rank}: cannot encode particles for a neighbour: {e}"))
        };
        let outgoing = [
            left.map(|_| encode(&sent[0])).transpose()?,
            right.map(|_| encode(&sent[1])).transpose()?,
        ];
        let bytes: usize = outgoing.iter().flatten().map(Vec::len).sum();
        self.sent_bytes.set(self.sent_bytes.get() + bytes as u64);
        let received = mpi::request::scope(|scope| {
            let _sends: Vec<WaitGuard<'_, [u8], _>> = [left, right]
                .iter()
                .zip(&outgoing)
                .filter_map(|(to, bytes)| Some((to.as_ref()?, bytes.as_ref()?)))
                .map(|(&to, bytes)| {
                    let process = self.world.process_at_rank(to as i32);
                    WaitGuard::from(process.immediate_send_with_tag(scope, &bytes[..], phase))
                })
                .collect();
            [left, right].map(|from| {
                from.map(|r| {
                    let (bytes, _) = self
                        .world
                        .process_at_rank(r as i32)
                        .receive_vec_with_tag::<u8>(phase);
                    bytes
                })
            })
        });
        let decode = |bytes: Option<Vec<u8>>, from: &str| -> Result<Particles, String> {
            let Some(bytes) = bytes else {
                return Ok(Particles::default());
            };
            bincode::serde::decode_from_slice(&bytes, bincode::config::standard())
                .map(|(p, _)| p)
                .map_err(|e| format!("rank {rank}: the particles from the {from} neighbour are damaged: {e}"))
        };
        let [from_left, from_right] = received;
        Ok([decode(from_left, "left")?, decode(from_right, "right")?])
    }

    /// The sum of `value` over the ranks, on every rank (f64 energies, u64 counts).
    pub fn sum<T: Equivalence + Default>(&self, value: T) -> T {
        let mut total = T::default();
        self.world
            .all_reduce_into(&value, &mut total, SystemOperation::sum());
        total
    }

    /// The largest `value` over the ranks, on every rank.
    pub fn max(&self, value: f64) -> f64 {
        let mut largest = 0.0;
        self.world
            .all_reduce_into(&value, &mut largest, SystemOperation::max());
        largest
    }

    /// Waits until every rank has come here.
    pub fn barrier(&self) {
        self.world.barrier();
    }

    /// Every rank's `row` (all of one length), by rank, on every rank.
    pub fn all_rows(&self, row: &[f64]) -> Vec<Vec<f64>> {
        let mut all = vec![0.0; row.len() * self.size()];
        self.world.all_gather_into(row, &mut all[..]);
        match row.len() {
            0 => vec![Vec::new(); self.size()],
            n => all.chunks(n).map(<[f64]>::to_vec).collect(),
        }
    }

    /// Stops every rank at once with `code` (after one rank's error, so the others do not wait
    /// for it in an exchange).
    pub fn abort(&self, code: i32) -> ! {
        self.world.abort(code)
    }
}
