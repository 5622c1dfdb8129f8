//! The iceoryx2 link between the coupler and one participant.
//!
//! [`Link::open`] opens one end ([`Side`]) of a channel pair named after the run id and the
//! participant; [`Link::wait_for_peer`] waits until the other end exists; [`Link::send`] and
//! [`Link::recv`] move bincode 2 messages ([`bincode_config`]) through shared memory, waking the
//! receiver with an event instead of polling, and checking a liveness closure between timed waits
//! (see [`process_alive`]).

mod channel;
mod codec;
mod error;
mod handshake;
mod iceoryx_config;
mod liveness;
mod names;

pub use channel::{Link, MAX_WAIT};
pub use codec::{
    bincode_config, decode_exact, encode_into_uninit, encoded_len, LinkConfig, MAX_MESSAGE_BYTES,
};
pub use error::LinkError;
pub use handshake::{Hello, PROTOCOL_VERSION};
pub use iceoryx_config::{INITIAL_MAX_SLICE_LEN, SUBSCRIBER_BUFFER};
pub use liveness::process_alive;
pub use names::{ServiceNames, Side, MAX_NAME_LEN};
