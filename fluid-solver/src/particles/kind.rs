//! What a particle is: fluid, wall, dummy, body, gate or inflow, and what each kind takes part in.

/// The kind of a particle, stored as one byte per particle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Kind {
    /// Water: moves by S1-10 … S1-13.
    Fluid = 0,
    /// Inner wall layers: fixed, pressure from the equation of state (S1-14) of their own number
    /// density, and they push the fluid through the pressure gradient (S1-3).
    Wall = 1,
    /// Outer wall layers: fixed, only complete the number density (S1-15) of the wall layers.
    Dummy = 2,
    /// A rigid body's particles: pressure like walls; they move with the body's kinematics.
    Body = 3,
    /// A partition board: a wall until it is removed at t = 0.
    Gate = 4,
    /// An inflow strip's particles: they move with the prescribed u_in (not by S1-10 … S1-13),
    /// carry pressure like walls and become fluid when they cross the inflow plane.
    Inflow = 5,
}

impl Kind {
    /// The byte stored per particle.
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The kind of a stored byte (unknown bytes read as `Dummy`, which exerts no force).
    pub const fn from_code(c: u8) -> Kind {
        match c {
            0 => Kind::Fluid,
            1 => Kind::Wall,
            3 => Kind::Body,
            4 => Kind::Gate,
            5 => Kind::Inflow,
            _ => Kind::Dummy,
        }
    }

    /// Whether the particle gets a pressure from S1-14 and enters the gradient S1-3.
    pub const fn carries_pressure(self) -> bool {
        !matches!(self, Kind::Dummy)
    }

    /// Name used in outputs and diagnostics.
    pub const fn name(self) -> &'static str {
        match self {
            Kind::Fluid => "fluid",
            Kind::Wall => "wall",
            Kind::Dummy => "dummy",
            Kind::Body => "body",
            Kind::Gate => "gate",
            Kind::Inflow => "inflow",
        }
    }
}

/// Stored byte of [`Kind::Fluid`], for branch-free masks in the pair loops.
pub const FLUID: u8 = Kind::Fluid.code();
/// Stored byte of [`Kind::Wall`].
pub const WALL: u8 = Kind::Wall.code();
/// Stored byte of [`Kind::Dummy`].
pub const DUMMY: u8 = Kind::Dummy.code();
