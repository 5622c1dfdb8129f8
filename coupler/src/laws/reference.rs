//! `participant/name` references of the case, bound to the participants' declared interfaces.

use crate::error::CouplerError;
use schemas::message::InterfaceDecl;

/// A point or body of a participant: (participant index, index in its declaration).
#[derive(Debug, Clone, Copy)]
pub struct ItemRef {
    pub participant: usize,
    pub index: usize,
}

/// What a `participant/name` reference of the case names.
#[derive(Clone, Copy)]
pub enum Item {
    Point,
    Body,
}

/// Finds `participant/name` among the running participants and what they declared.
pub fn item_ref(
    names: &[String],
    decls: &[InterfaceDecl],
    text: &str,
    item: Item,
) -> Result<ItemRef, CouplerError> {
    let (participant, name) = text.split_once('/').unwrap_or((text, ""));
    let p = participant_index(names, participant, text)?;
    let (declared, what) = match item {
        Item::Point => (&decls[p].points, "points"),
        Item::Body => (&decls[p].bodies, "bodies"),
    };
    let i = declared
        .iter()
        .position(|n| n == name)
        .ok_or_else(|| CouplerError::Participant {
            name: participant.to_string(),
            window: None,
            message: format!("declared {what} {declared:?} at the handshake, but the case couples `{name}`"),
        })?;
    Ok(ItemRef {
        participant: p,
        index: i,
    })
}

/// The serial index of participant `participant` (named in the case's reference `text`).
pub fn participant_index(names: &[String], participant: &str, text: &str) -> Result<usize, CouplerError> {
    names.iter().position(|n| n == participant).ok_or_else(|| {
        CouplerError::Usage(format!(
            "coupling reference `{text}`: no participant `{participant}` is running"
        ))
    })
}
