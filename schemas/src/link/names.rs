//! Which end of the link a process is, and the iceoryx2 service names of one coupler <-> participant pair.

use super::LinkError;

/// The end of a coupler <-> participant link a process holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The coupler: sends on `down`, receives on `up`.
    Coupler,
    /// A solver process: sends on `up`, receives on `down`.
    Participant,
}

/// The four services of one link: two byte streams and their wake-up events.
/// Names carry the run id, so two runs on one machine never share a service.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ServiceNames {
    /// Coupler -> participant messages, `tsunami/{run_id}/{participant}/down`.
    pub down: String,
    /// Participant -> coupler messages, `tsunami/{run_id}/{participant}/up`.
    pub up: String,
    /// Wakes the participant when a `down` message is sent.
    pub down_wake: String,
    /// Wakes the coupler when an `up` message is sent.
    pub up_wake: String,
}

/// Longest run id or participant name accepted (iceoryx2 service names are at most 255 bytes).
pub const MAX_NAME_LEN: usize = 96;

impl ServiceNames {
    /// Builds the names after checking `run_id` and `participant` (non-empty, at most
    /// [`MAX_NAME_LEN`] bytes of ASCII letters, digits, `-`, `_`, `.`).
    pub fn new(run_id: &str, participant: &str) -> Result<Self, LinkError> {
        check_name("run id", run_id)?;
        check_name("participant name", participant)?;
        let base = format!("tsunami/{run_id}/{participant}");
        Ok(Self {
            down: format!("{base}/down"),
            up: format!("{base}/up"),
            down_wake: format!("{base}/down/wake"),
            up_wake: format!("{base}/up/wake"),
        })
    }

    /// (outgoing messages, incoming messages, outgoing wake-ups, incoming wake-ups) for `side`.
    pub fn for_side(&self, side: Side) -> (&str, &str, &str, &str) {
        match side {
            Side::Coupler => (&self.down, &self.up, &self.down_wake, &self.up_wake),
            Side::Participant => (&self.up, &self.down, &self.up_wake, &self.down_wake),
        }
    }
}

fn check_name(what: &str, name: &str) -> Result<(), LinkError> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.');
    if name.is_empty() || name.len() > MAX_NAME_LEN || !name.chars().all(allowed) {
        return Err(LinkError::InvalidName(format!(
            "{what} {name:?} must be 1 to {MAX_NAME_LEN} ASCII letters, digits, '-', '_' or '.'"
        )));
    }
    Ok(())
}
