//! What can go wrong on the coupler <-> participant link, worded for the person running the case.

use std::fmt;

/// A failure of the iceoryx2 link between the coupler and one participant.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LinkError {
    /// iceoryx2 refused an operation (shared memory, service or port); the text says which and why.
    Iceoryx(String),
    /// The deadline passed before the peer connected or before the next message arrived.
    Timeout,
    /// The peer process is gone (killed, crashed or exited) while this side was waiting for it.
    PeerGone(String),
    /// A message could not be encoded (e.g. it is larger than the link's size limit).
    Encode(String),
    /// Received bytes are not a valid message of the expected type (or exceed the size limit).
    Decode(String),
    /// The link was used before [`super::Link::wait_for_peer`] connected it.
    NotConnected(String),
    /// A run id or participant name that cannot be part of a service name.
    InvalidName(String),
}

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinkError::Iceoryx(msg) => write!(f, "shared-memory link (iceoryx2) failed: {msg}"),
            LinkError::Timeout => write!(
                f,
                "timed out waiting for the other process on the shared-memory link \
                 (it did not start, connect or answer in time)"
            ),
            LinkError::PeerGone(msg) => write!(f, "the other process of the link is gone: {msg}"),
            LinkError::Encode(msg) => write!(f, "could not encode a message for the link: {msg}"),
            LinkError::Decode(msg) => write!(
                f,
                "could not decode a message from the link (coupler and participant built from \
                 different versions?): {msg}"
            ),
            LinkError::NotConnected(msg) => write!(f, "the link is not connected yet: {msg}"),
            LinkError::InvalidName(msg) => write!(f, "invalid link name: {msg}"),
        }
    }
}

impl std::error::Error for LinkError {}
