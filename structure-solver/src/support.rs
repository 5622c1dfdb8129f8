//! [`Support`]: the washout condition (S1-22). A body sits on its bearings, held fixed, until the
//! upward applied force `F_v` exceeds `F_d`; from then on it moves freely, for good.
//!
//! `F_v` is the applied force (prescribed or hydrodynamic, plus springs) along "up" — against
//! gravity, or +z without gravity; the body's own weight is not part of it, as in the paper where
//! the fluid's lift is compared with `F_d`. It is checked at the start of every substep.

/// A support holding body `body` (index) until release.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Support {
    pub body: usize,
    /// F_d [N].
    pub release_force: f64,
    /// Time of release [s], once released.
    pub released_at: Option<f64>,
}

impl Support {
    /// Whether the body is still held.
    pub fn holds(&self) -> bool {
        self.released_at.is_none()
    }

    /// S1-22: releases the body at time `t` if it is held and `upward_force > F_d`; returns true
    /// when this call released it.
    pub fn check_release(&mut self, t: f64, upward_force: f64) -> bool {
        if self.holds() && upward_force > self.release_force {
            self.released_at = Some(t);
            true
        } else {
            false
        }
    }
}
