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
use mpi::datatype::PartitionMut;
use mpi::request::WaitGuard;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use mpi::Tag;

/// Message tags of rank 0's orders to the other ranks and of the texts they send it back
/// (a step's exchanges use 1 and 2).
const ORDER: Tag = 3;
const TEXT: Tag = 4;

/// The longest sleep between two probes of a rank waiting for an order: what an order may wait
/// on top of its own transfer.
const ORDER_POLL_MAX: std::time::Duration = std::time::Duration::from_millis(5);

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

    /// The element-wise sum of `values` (equally long on every rank) over the ranks, on every
    /// rank (f64 loads, u64 counts).
    pub fn sum_each<T: Equivalence + Default + Clone>(&self, values: &[T]) -> Vec<T> {
        let mut total = vec![T::default(); values.len()];
        if !values.is_empty() {
            self.world
                .all_reduce_into(values, &mut total[..], SystemOperation::sum());
        }
        total
    }

    /// Every rank's `bytes` (of any length), by rank, on every rank.
    pub fn all_bytes(&self, bytes: &[u8]) -> Vec<Vec<u8>> {
        let lengths: Vec<u64> = self
            .all_rows(&[bytes.len() as f64])
            .iter()
            .map(|r| r[0] as u64)
            .collect();
        let counts: Vec<mpi::Count> = lengths.iter().map(|&n| n as mpi::Count).collect();
        let displs: Vec<mpi::Count> = counts
            .iter()
            .scan(0, |at, &n| {
                let start = *at;
                *at += n;
                Some(start)
            })
            .collect();
        let mut all = vec![0u8; lengths.iter().sum::<u64>() as usize];
        {
            let mut parts = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
            self.world.all_gather_varcount_into(bytes, &mut parts);
        }
        counts
            .iter()
            .zip(&displs)
            .map(|(&n, &d)| all[d as usize..(d + n) as usize].to_vec())
            .collect()
    }

    /// Rank 0 sends `bytes` to every other rank (an order they wait for with
    /// [`RankLink::next_order`]).
    pub fn send_order(&self, bytes: &[u8]) {
        for r in 1..self.size() {
            self.world.process_at_rank(r as i32).send_with_tag(bytes, ORDER);
        }
    }

    /// On a rank other than 0: the next order rank 0 sends, waited for without spinning (OpenMPI's
    /// blocking receive polls at full speed: this one probes, then sleeps, up to
    /// [`ORDER_POLL_MAX`] between probes). `None` when `stop()` says to stop waiting (a
    /// signal came).
    pub fn next_order(&self, stop: impl Fn() -> bool) -> Option<Vec<u8>> {
        let root = self.world.process_at_rank(0);
        let mut pause = std::time::Duration::from_micros(50);
        loop {
            if root.immediate_probe_with_tag(ORDER).is_some() {
                return Some(root.receive_vec_with_tag::<u8>(ORDER).0);
            }
            if stop() {
                return None;
            }
            std::thread::sleep(pause);
            pause = (pause * 2).min(ORDER_POLL_MAX);
        }
    }

    /// Every rank's `text` (empty for none), by rank, on rank 0; empty on the others. Every rank
    /// calls it (after a step that failed on some rank, to bring each rank's diagnostic to the
    /// one that reports).
    pub fn texts_at_root(&self, text: &str) -> Vec<String> {
        if self.rank() != 0 {
            self.world.process_at_rank(0).send_with_tag(text.as_bytes(), TEXT);
            return Vec::new();
        }
        let mut all = vec![text.to_string()];
        for r in 1..self.size() {
            let (bytes, _) = self
                .world
                .process_at_rank(r as i32)
                .receive_vec_with_tag::<u8>(TEXT);
            all.push(String::from_utf8_lossy(&bytes).into_owned());
        }
        all
    }

    /// Every rank's `result` made one: as it is when it is `Ok` on every rank, else an error on
    /// every rank, rank 0's naming each rank that failed with its message. Every rank calls it
    /// (so it is a barrier too).
    pub fn agree<T>(&self, result: Result<T, String>) -> Result<T, String> {
        let failed = self.max(if result.is_err() { 1.0 } else { 0.0 });
        if failed == 0.0 {
            return result;
        }
        let mine = result.as_ref().err().cloned().unwrap_or_default();
        Err(self.failures_at_root(&mine))
    }

    /// After a failure every rank knows of: rank 0 gets `rank R: MESSAGE` for every rank whose
    /// `mine` is not empty, joined by `; `; the others get their own message (or that another
    /// rank failed). Every rank calls it.
    pub fn failures_at_root(&self, mine: &str) -> String {
        let texts = self.texts_at_root(mine);
        match self.rank() {
            0 => {
                // each message once, with the ranks that gave it
                let mut said: Vec<(Vec<usize>, &str)> = Vec::new();
                for (r, t) in texts.iter().enumerate().filter(|(_, t)| !t.is_empty()) {
                    match said.iter_mut().find(|(_, s)| s == t) {
                        Some((ranks, _)) => ranks.push(r),
                        None => said.push((vec![r], t)),
                    }
                }
                said.iter()
                    .map(|(ranks, t)| match ranks.len() {
                        n if n == texts.len() && n > 1 => format!("every rank: {t}"),
                        1 => format!("rank {}: {t}", ranks[0]),
                        _ => format!("ranks {ranks:?}: {t}"),
                    })
                    .collect::<Vec<_>>()
                    .join("; ")
            }
            r if mine.is_empty() => format!("rank {r}: another rank failed (rank 0 reports it)"),
            _ => mine.to_string(),
        }
    }

    /// Stops every rank at once with `code` (after one rank's error, so the others do not wait
    /// for it in an exchange).
    pub fn abort(&self, code: i32) -> ! {
        self.world.abort(code)
    }
}
