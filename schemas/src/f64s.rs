//! [`F64s`]: a flat `f64` array that encodes as one length and raw little-endian bytes,
//! so bulk interface data cost one memory copy per side instead of a per-element encode.

use bincode::de::{read::Reader, Decoder};
use bincode::enc::{write::Writer, Encoder};
use bincode::error::{DecodeError, EncodeError};
use bincode::{Decode, Encode};
use std::ops::{Deref, DerefMut};

/// A flat array of `f64` (e.g. 3 per point, 6 per body) in an interface message.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct F64s(pub Vec<f64>);

impl F64s {
    /// `n` zeros.
    pub fn zeros(n: usize) -> Self {
        F64s(vec![0.0; n])
    }
}

impl Deref for F64s {
    type Target = Vec<f64>;
    fn deref(&self) -> &Vec<f64> {
        &self.0
    }
}

impl DerefMut for F64s {
    fn deref_mut(&mut self) -> &mut Vec<f64> {
        &mut self.0
    }
}

impl From<Vec<f64>> for F64s {
    fn from(v: Vec<f64>) -> Self {
        F64s(v)
    }
}

impl Encode for F64s {
    fn encode<E: Encoder>(&self, encoder: &mut E) -> Result<(), EncodeError> {
        (self.0.len() as u64).encode(encoder)?;
        if cfg!(target_endian = "little") {
            // SAFETY: an initialised `[f64]` is valid as `len * 8` initialised bytes.
            let bytes = unsafe { std::slice::from_raw_parts(self.0.as_ptr().cast::<u8>(), self.0.len() * 8) };
            encoder.writer().write(bytes)
        } else {
            self.0
                .iter()
                .try_for_each(|v| encoder.writer().write(&v.to_le_bytes()))
        }
    }
}

impl<Context> Decode<Context> for F64s {
    fn decode<D: Decoder<Context = Context>>(decoder: &mut D) -> Result<Self, DecodeError> {
        let len = u64::decode(decoder)?;
        let len = usize::try_from(len).map_err(|_| DecodeError::OutsideUsizeRange(len))?;
        decoder.claim_container_read::<f64>(len)?;
        let mut values = vec![0.0_f64; len];
        // SAFETY: every byte pattern is a valid f64, and the byte view covers exactly the vector.
        let bytes =
            unsafe { std::slice::from_raw_parts_mut(values.as_mut_ptr().cast::<u8>(), values.len() * 8) };
        decoder.reader().read(bytes)?;
        if cfg!(target_endian = "big") {
            values
                .iter_mut()
                .for_each(|v| *v = f64::from_le_bytes(v.to_ne_bytes()));
        }
        Ok(F64s(values))
    }
}

bincode::impl_borrow_decode!(F64s);
