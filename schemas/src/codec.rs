//! The one bincode configuration used for messages and recordings.

use bincode::config::{Configuration, Limit, LittleEndian, Varint};

/// Largest message or frame accepted when decoding (untrusted bytes must not allocate unbounded).
pub const MAX_MESSAGE_BYTES: usize = 1 << 31;

/// Standard bincode 2 encoding (little endian, variable-length integers) with a decode limit.
pub fn config() -> Configuration<LittleEndian, Varint, Limit<MAX_MESSAGE_BYTES>> {
    bincode::config::standard().with_limit::<MAX_MESSAGE_BYTES>()
}
