//! Resolved rigid bodies on the device (`shaders/bodies.wgsl`), the GPU path of
//! [`crate::bodies`]: the host hands over each body's pose and velocity for a step (the values
//! the CPU path passes to [`crate::bodies::RigidBodies::set_kinematics`]), the device places the
//! body particles, sums the fluid's pair forces and the walls' contact on them as gathers, and
//! reduces force and moment per body; it also sums the bodies' reaction on the fluid from the
//! fluid particles' side (`shaders/reaction.wgsl`), for the action–reaction ledger; 96 B per body
//! come back per step.

use super::buffers::SUMS;
use super::frame::Frame;
use bytemuck::{Pod, Zeroable};

/// Mirror of `Member` in `shaders/common.wgsl`: a body particle's offset from its body's initial
/// centre, its id and its body (a paddle particle's row keeps the low parts of its rest position
/// in `pad`: [`super::paddle`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Member {
    pub offset: [f32; 3],
    pub id: u32,
    pub body: u32,
    pub pad: [u32; 3],
}

/// Mirror of `BodyKin`: centre (its w: the lead of `set_kinematics`), quaternion (w, x, y, z), V
/// and ω of one body (their w unused), and the low part of the centre with wide positions
/// ([`super::frame`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct BodyKin {
    pub centre: [f32; 4],
    pub quat: [f32; 4],
    pub vel: [f32; 4],
    pub omega: [f32; 4],
    pub low: [f32; 4],
}

/// Mirror of `BodyLoad`: force and moment (w unused).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct BodyLoad {
    pub force: [f32; 4],
    pub moment: [f32; 4],
}

/// The device's member table: (particle id, body, offset) sorted by id, as
/// [`crate::bodies::RigidBodies::members`] gives it.
pub fn members(table: &[(u32, usize, [f64; 3])]) -> Vec<Member> {
    table
        .iter()
        .map(|&(id, body, offset)| Member {
            offset: offset.map(|v| v as f32),
            id,
            body: body as u32,
            pad: [0; 3],
        })
        .collect()
}

/// The device's kinematics of each body from `pose` (7 per body: centre, quaternion w x y z),
/// `velocity` (6 per body: V, ω) and the `lead` of [`crate::bodies::RigidBodies::set_kinematics`],
/// the centres in the device's `frame`.
pub fn kinematics(pose: &[f64], velocity: &[f64], lead: f64, frame: &Frame) -> Vec<BodyKin> {
    pose.chunks_exact(7)
        .zip(velocity.chunks_exact(6))
        .map(|(p, v)| {
            let f = |x: f64| x as f32;
            let ([cx, cy, cz], [lx, ly, lz]) = frame.split([p[0], p[1], p[2]]);
            BodyKin {
                centre: [cx, cy, cz, f(lead)],
                quat: [f(p[3]), f(p[4]), f(p[5]), f(p[6])],
                vel: [f(v[0]), f(v[1]), f(v[2]), 0.0],
                omega: [f(v[3]), f(v[4]), f(v[5]), 0.0],
                low: [lx, ly, lz, 0.0],
            }
        })
        .collect()
}

/// The sums read back (`SUMS` per body: loads, the fluid-side reaction, the walls' contact) as
/// 6 per body (fx fy fz mx my mz) in f64: the loads, and the reaction on the fluid and the walls
/// (the fluid-side sum minus the walls' contact, whose reaction the walls take, as
/// [`crate::solver`] does on the CPU).
pub fn loads_and_reactions(read: &[BodyLoad]) -> (Vec<f64>, Vec<f64>) {
    let six = |l: &BodyLoad| {
        let (f, m) = (l.force, l.moment);
        [f[0], f[1], f[2], m[0], m[1], m[2]].map(f64::from)
    };
    let mut loads = Vec::new();
    let mut reactions = Vec::new();
    for sums in read.chunks_exact(SUMS as usize) {
        let (fluid_side, walls) = (six(&sums[1]), six(&sums[2]));
        loads.extend(six(&sums[0]));
        reactions.extend((0..6).map(|a| fluid_side[a] - walls[a]));
    }
    (loads, reactions)
}
