//! The constants of the kernels, one uniform block (`Params` in `shaders/common.wgsl`; the field
//! order and padding are the WGSL layout's: a vec3 takes 16 bytes with the scalar after it).

use bytemuck::{Pod, Zeroable};

/// Mirror of `Params` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Params {
    pub origin: [f32; 3],
    pub inv_cell: f32,
    pub dims: [u32; 3],
    pub n: u32,
    pub gravity: [f32; 3],
    pub dt: f32,
    pub re: f32,
    pub re_grad: f32,
    pub inv_n0: f32,
    pub grad_factor: f32,
    pub lap_factor: f32,
    pub nu: f32,
    pub rho: f32,
    pub c2: f32,
    pub coll_dist: f32,
    pub restitution: f32,
    pub reach: u32,
    pub reach_grad: u32,
    pub reach_coll: u32,
    pub cells: u32,
    pub pad: u32,
    pub viscous: u32,
    pub domain_lo: [f32; 3],
    pub spacing: f32,
    pub domain_hi: [f32; 3],
    pub wall_top: f32,
    pub tank_lo: [f32; 3],
    pub open_top: u32,
    pub tank_hi: [f32; 3],
    pub n_boxes: u32,
    pub mass: f32,
    pub volume: f32,
    pub scan_blocks: u32,
    pub n_bodies: u32,
    pub n_members: u32,
    pub reach_contact: u32,
    /// The walls' contact spring k = m ω² and dashpot c = 2 m ω on body particles, ω = 2π /
    /// (CONTACT_PERIOD_STEPS Δt) ([`crate::bodies::body_wall_contact`]); set with each step's Δt.
    pub contact_k: f32,
    pub contact_c: f32,
    /// The mesh solids' and terrains' lattice ([`super::solids`]): origin, 1/Δs, sites per axis,
    /// and 1 when there are solid sites.
    pub solid_lo: [f32; 3],
    pub solid_inv_ds: f32,
    pub solid_n: [u32; 3],
    pub solids: u32,
    /// Damping zones ([`super::damping`]); the artificial viscosity's −α ρ0 c h and 0.01 h²
    /// ([`crate::emps::artificial_viscosity`]; `av_scale` 0: off); the word of the solid sites'
    /// buffer where the bodies' table for the detector starts ([`super::body_inside`]).
    pub n_damping: u32,
    pub av_scale: f32,
    pub av_eta2: f32,
    pub body_table: u32,
    /// The wave maker's paddle ([`super::paddle`]): its first particle id and its particles
    /// (0: none), the row of the members' buffer where its rest positions start, and this
    /// step's placement (set with each step's Δt): a piston's shift and speed, a flap's
    /// cos θ − 1, sin θ and their changes over the step / Δt, about the hinge (x, z).
    pub paddle_first: u32,
    pub paddle_count: u32,
    pub paddle_row: u32,
    pub paddle_shift: f32,
    pub paddle_speed: f32,
    pub paddle_cos_m1: f32,
    pub paddle_sin: f32,
    pub paddle_dcos: f32,
    pub paddle_dsin: f32,
    pub hinge_x: f32,
    pub hinge_z: f32,
    /// The quantum of wide positions' high parts (0: plain f32 positions; [`super::frame`]).
    pub quantum: f32,
    /// The open boundaries' pass ([`super::open_boundary`], set before each step of a case
    /// with an inflow or an outflow): the strip's velocity u(t + Δt/2) and travel u Δt, the x
    /// from which a strip particle becomes fluid and the z above which one is withdrawn (each
    /// half-way between the host's strip particles that do and those that do not; +∞: none),
    /// and the outflow plane (+∞: none).
    pub inflow_u: f32,
    pub inflow_dx: f32,
    pub inflow_enter: f32,
    pub inflow_cut: f32,
    pub outflow_x: f32,
    /// With wide positions ([`super::frame`]) the low parts of the outflow plane and of the
    /// paddle's hinge (0 otherwise): the outflow decides on both parts, as the CPU's f64 does.
    pub outflow_low: f32,
    pub hinge_low_x: f32,
    pub hinge_low_z: f32,
}

/// Converts to the device's f32.
pub fn f32x3(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}
