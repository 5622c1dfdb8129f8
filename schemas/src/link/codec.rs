//! bincode 2 encoding straight into a loaned shared-memory slice, and decoding with a size limit.

use super::LinkError;
use bincode::config::{Configuration, LittleEndian, Varint};
use bincode::enc::write::{SizeWriter, Writer};
use bincode::error::EncodeError;
use std::mem::MaybeUninit;

/// Largest message the link encodes or decodes: 2 GiB. Also caps what a decoder may allocate
/// for lengths read from untrusted bytes.
pub const MAX_MESSAGE_BYTES: usize = 1 << 31;

/// The one bincode configuration of the link: standard (little endian, varint) with a size limit.
pub type LinkConfig = Configuration<LittleEndian, Varint, bincode::config::Limit<MAX_MESSAGE_BYTES>>;

/// The bincode configuration every link message is encoded and decoded with.
pub fn bincode_config() -> LinkConfig {
    bincode::config::standard()
        .with_little_endian()
        .with_variable_int_encoding()
        .with_limit()
}

/// Number of bytes `msg` encodes to (a dry run through bincode's `SizeWriter`).
pub fn encoded_len<T: bincode::Encode>(msg: &T) -> Result<usize, LinkError> {
    let mut sizer = SizeWriter::default();
    bincode::encode_into_writer(msg, &mut sizer, bincode_config()).map_err(encode_error)?;
    if sizer.bytes_written > MAX_MESSAGE_BYTES {
        return Err(LinkError::Encode(format!(
            "message is {} bytes, more than the link's limit of {MAX_MESSAGE_BYTES} bytes",
            sizer.bytes_written
        )));
    }
    Ok(sizer.bytes_written)
}

/// Encodes `msg` into `out`, which must be exactly `encoded_len(msg)` long; returns the bytes written.
/// When it returns `Ok(out.len())` every byte of `out` is initialised.
pub fn encode_into_uninit<T: bincode::Encode>(
    msg: &T,
    out: &mut [MaybeUninit<u8>],
) -> Result<usize, LinkError> {
    let capacity = out.len();
    let mut writer = UninitSliceWriter { out, written: 0 };
    bincode::encode_into_writer(msg, &mut writer, bincode_config()).map_err(encode_error)?;
    if writer.written != capacity {
        return Err(LinkError::Encode(format!(
            "message encoded to {} bytes but was sized at {capacity} (its Encode impl is not deterministic)",
            writer.written
        )));
    }
    Ok(writer.written)
}

/// Decodes one whole message from `bytes`; trailing bytes mean the two sides disagree on the type.
pub fn decode_exact<T: bincode::Decode<()>>(bytes: &[u8]) -> Result<T, LinkError> {
    let (value, read) = bincode::decode_from_slice::<T, _>(bytes, bincode_config())
        .map_err(|e| LinkError::Decode(format!("{e} (message of {} bytes)", bytes.len())))?;
    if read != bytes.len() {
        return Err(LinkError::Decode(format!(
            "message of {} bytes decoded from only its first {read} bytes: sender and receiver \
             expect different message types",
            bytes.len()
        )));
    }
    Ok(value)
}

fn encode_error(e: EncodeError) -> LinkError {
    LinkError::Encode(e.to_string())
}

/// A bincode `Writer` that fills an uninitialised byte slice front to back.
struct UninitSliceWriter<'a> {
    out: &'a mut [MaybeUninit<u8>],
    written: usize,
}

impl Writer for UninitSliceWriter<'_> {
    #[inline]
    fn write(&mut self, bytes: &[u8]) -> Result<(), EncodeError> {
        let end = self.written + bytes.len();
        let Some(dst) = self.out.get_mut(self.written..end) else {
            return Err(EncodeError::UnexpectedEnd);
        };
        // SAFETY: `MaybeUninit<u8>` has the layout of `u8`; `dst` and `bytes` have equal length and
        // cannot overlap (`dst` is exclusively borrowed).
        unsafe {
            std::ptr::copy_nonoverlapping(bytes.as_ptr(), dst.as_mut_ptr().cast::<u8>(), bytes.len());
        }
        self.written = end;
        Ok(())
    }
}
