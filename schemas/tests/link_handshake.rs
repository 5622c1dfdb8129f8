//! Tests of `schemas::link::handshake`.

use schemas::link::Side;
use schemas::link::*;

#[test]
fn hello_from_the_other_side_is_accepted() {
    assert_eq!(
        Hello::new(Side::Coupler).accept(Side::Participant),
        Ok(std::process::id())
    );
    assert_eq!(
        Hello::new(Side::Participant).accept(Side::Coupler),
        Ok(std::process::id())
    );
}

#[test]
fn hello_from_the_same_side_or_another_version_is_refused() {
    assert!(Hello::new(Side::Coupler).accept(Side::Coupler).is_err());
    let mut old = Hello::new(Side::Coupler);
    old.version = PROTOCOL_VERSION + 1;
    assert!(old.accept(Side::Participant).is_err());
    let mut alien = Hello::new(Side::Coupler);
    alien.magic = 7;
    assert!(alien.accept(Side::Participant).is_err());
}
