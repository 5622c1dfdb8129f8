//! Tests of `schemas::link::codec`.

use schemas::link::LinkError;
use schemas::link::*;
use std::mem::MaybeUninit;

#[derive(bincode::Encode, bincode::Decode, Debug, PartialEq)]
struct Probe {
    step: u64,
    name: String,
    values: Vec<f64>,
}

fn probe() -> Probe {
    Probe {
        step: 300,
        name: "wall".into(),
        values: vec![1.5, -2.0, f64::MAX],
    }
}

#[test]
fn roundtrip_through_uninit_slice() {
    let msg = probe();
    let len = encoded_len(&msg).unwrap();
    let mut buf = vec![MaybeUninit::<u8>::uninit(); len];
    assert_eq!(encode_into_uninit(&msg, &mut buf).unwrap(), len);
    // SAFETY: encode_into_uninit returned Ok(len), so all bytes are initialised.
    let bytes: Vec<u8> = buf.iter().map(|b| unsafe { b.assume_init() }).collect();
    assert_eq!(bytes, bincode::encode_to_vec(&msg, bincode_config()).unwrap());
    assert_eq!(decode_exact::<Probe>(&bytes).unwrap(), msg);
}

#[test]
fn too_small_slice_is_an_encode_error() {
    let msg = probe();
    let len = encoded_len(&msg).unwrap();
    let mut buf = vec![MaybeUninit::<u8>::uninit(); len - 1];
    assert!(matches!(
        encode_into_uninit(&msg, &mut buf),
        Err(LinkError::Encode(_))
    ));
}

#[test]
fn trailing_bytes_are_a_decode_error() {
    let mut bytes = bincode::encode_to_vec(probe(), bincode_config()).unwrap();
    bytes.push(0);
    assert!(matches!(decode_exact::<Probe>(&bytes), Err(LinkError::Decode(_))));
}

#[test]
fn huge_claimed_length_is_refused_without_allocating() {
    // A Vec<u8> claiming 2^40 elements (varint u64 marker 253 + 8 bytes) and nothing behind it.
    let mut bytes = vec![253u8];
    bytes.extend_from_slice(&(1u64 << 40).to_le_bytes());
    let err = decode_exact::<Vec<u8>>(&bytes).unwrap_err();
    assert!(matches!(err, LinkError::Decode(_)), "{err}");
}

#[test]
fn truncated_message_is_a_decode_error() {
    let bytes = bincode::encode_to_vec(probe(), bincode_config()).unwrap();
    assert!(matches!(
        decode_exact::<Probe>(&bytes[..bytes.len() - 3]),
        Err(LinkError::Decode(_))
    ));
}
