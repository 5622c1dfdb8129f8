//! Decoding one recording frame with a bound on what the decoder may allocate.
//!
//! A length read from damaged bytes (a `Vec` claiming 2⁶⁴−1 elements) must not make the reader
//! allocate it. bincode checks every container's `len × size_of::<T>()` against its configured
//! limit before allocating; the limit is a type parameter, so it is picked here from a ladder of
//! four by the frame's length: the smallest of 1 MiB, 16 MiB, 256 MiB and 2 GiB that is at least
//! [`CLAIM_PER_BYTE`] × the frame's length. A frame of `n` bytes thus decodes with at most
//! max(1 MiB, 16 × 64 × n) bytes claimed by containers (a valid frame claims at most about 24 bytes
//! per encoded byte: a 24-byte `Vec` or `String` encoded in one length byte).

use bincode::Decode;

/// Container bytes a frame may claim per byte of its encoding.
pub const CLAIM_PER_BYTE: usize = 64;

/// The limit on bytes claimed while decoding a frame of `frame_len` bytes.
pub fn decode_limit(frame_len: usize) -> usize {
    let need = frame_len.saturating_mul(CLAIM_PER_BYTE);
    [1 << 20, 1 << 24, 1 << 28]
        .into_iter()
        .find(|&limit| need <= limit)
        .unwrap_or(crate::link::MAX_MESSAGE_BYTES)
}

/// Decodes all of `bytes` as one `T` within [`decode_limit`]; bytes left over are an error.
pub fn decode<T: Decode<()>>(bytes: &[u8]) -> Result<T, String> {
    match decode_limit(bytes.len()) {
        l if l == 1 << 20 => decode_within::<T, { 1 << 20 }>(bytes),
        l if l == 1 << 24 => decode_within::<T, { 1 << 24 }>(bytes),
        l if l == 1 << 28 => decode_within::<T, { 1 << 28 }>(bytes),
        _ => decode_within::<T, { crate::link::MAX_MESSAGE_BYTES }>(bytes),
    }
}

fn decode_within<T: Decode<()>, const LIMIT: usize>(bytes: &[u8]) -> Result<T, String> {
    let config = bincode::config::standard()
        .with_little_endian()
        .with_variable_int_encoding()
        .with_limit::<LIMIT>();
    let (value, used) =
        bincode::decode_from_slice(bytes, config).map_err(|e| format!("cannot decode: {e}"))?;
    if used == bytes.len() {
        Ok(value)
    } else {
        Err(format!(
            "cannot decode: {} of its {} bytes are left over after the message",
            bytes.len() - used,
            bytes.len()
        ))
    }
}
