//! The first message each side sends once the peer's ports exist: proves both subscribers are attached
//! (so later bursts cannot be dropped), checks that the peer speaks this link protocol from the other
//! side, and tells each side the other's pid.

use super::{LinkError, Side};

/// `b"TSUNAMI\0"` read as a little-endian integer: marks a link hello.
pub const MAGIC: u64 = u64::from_le_bytes(*b"TSUNAMI\0");
/// Bumped whenever the link's wire behaviour changes.
pub const PROTOCOL_VERSION: u32 = 1;

/// The hello message of [`super::Link::wait_for_peer`].
#[derive(bincode::Encode, bincode::Decode, Debug, Clone, PartialEq, Eq)]
pub struct Hello {
    /// [`MAGIC`]: marks a link hello.
    pub magic: u64,
    /// The sender's [`PROTOCOL_VERSION`].
    pub version: u32,
    /// Whether the sender is the coupler's side.
    pub from_coupler: bool,
    /// The sender's process id.
    pub pid: u32,
}

impl Hello {
    /// The hello this process sends from `side`.
    pub fn new(side: Side) -> Hello {
        Hello {
            magic: MAGIC,
            version: PROTOCOL_VERSION,
            from_coupler: side == Side::Coupler,
            pid: std::process::id(),
        }
    }

    /// Checks a hello received by `side`; returns the peer's pid.
    pub fn accept(&self, side: Side) -> Result<u32, LinkError> {
        if self.magic != MAGIC {
            return Err(LinkError::Decode(
                "the first message from the peer is not a link hello (another program on this service?)"
                    .into(),
            ));
        }
        if self.version != PROTOCOL_VERSION {
            return Err(LinkError::Decode(format!(
                "the peer speaks link protocol {} but this process speaks {PROTOCOL_VERSION}: \
                 rebuild coupler and solvers from the same sources",
                self.version
            )));
        }
        if self.from_coupler == (side == Side::Coupler) {
            return Err(LinkError::Decode(format!(
                "the peer (pid {}) opened the same side ({side:?}) of the link",
                self.pid
            )));
        }
        Ok(self.pid)
    }
}
