//! [`Structure`]: everything one structure participant owns — point masses, springs, rigid
//! bodies and their supports — and its time stepping.
//!
//! One substep `[t, t + h]` (h ≤ `max_step`; an advance is cut into equal substeps so that it
//! lands exactly on its end time):
//! 1. washout check of held bodies with the loads at `t` (S1-22);
//! 2. kick of free bodies with the loads at `t` (S1-17, S1-18), drift (see [`RigidBody`]);
//! 3. classical RK4 on the point masses, with external loads at `t`, `t + h/2`, `t + h` and the
//!    body centres moving linearly over the drift, as they do;
//! 4. kick of free bodies with the loads at `t + h`; stop on any non-finite state.
//!
//! Point masses alone are integrated to 4th order; bodies to 2nd order (symplectic, energy kept).
//! A frame, when there is one, is independent of the rest: it takes its own Newmark steps
//! (equal steps ≤ its `time_step`, landing on the end time) with node loads read at each step end.

use crate::anchor::Anchor;
use crate::error::StepError;
use crate::external_loads::ExternalLoads;
use crate::frame::Frame;
use crate::inertia::MassProperties;
use crate::point_mass::PointMass;
use crate::rigid_body::RigidBody;
use crate::spring::Spring;
use crate::stability::check_max_step;
use crate::support::Support;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use schemas::case::structure::{StructureConfig, GROUND};
use schemas::case::FieldError;
use schemas::participant::{DiscardProgress, ProgressSink};

/// The state of one structure participant; `Clone` is its checkpoint, and so is its serde form
/// (a frame's without its caches: see [`Structure::drop_caches`]).
#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub struct Structure {
    time: f64,
    max_step: f64,
    gravity: Vector3<f64>,
    points: Vec<PointMass>,
    springs: Vec<Spring>,
    bodies: Vec<RigidBody>,
    supports: Vec<Support>,
    frame: Option<Frame>,
    /// Frame nodes before any fracture: loads may leave out the nodes made since (see
    /// [`Structure::advance`]).
    frame_nodes_at_start: usize,
    substeps: u64,
}

type V3 = Vector3<f64>;

/// Steps beyond a whole number of `step`s in `span` that are left out (the last steps stretch by
/// at most this share): the round-off of `t_end − t` late in a run is ~1e-16 t, e.g. 1.4e-11 of a
/// 1 ms step at t = 100 s, and a step that much longer is as stable and accurate as `step`.
const STEP_STRETCH: f64 = 1e-6;

/// Number of equal steps ≤ `step` (to within [`STEP_STRETCH`]) that make up `span` (≥ 1).
pub fn equal_steps(span: f64, step: f64) -> u64 {
    (span / step - STEP_STRETCH).ceil().max(1.0) as u64
}

/// External loads as a function of time.
pub type Loads<'a> = dyn Fn(f64) -> Result<ExternalLoads, String> + 'a;

impl Structure {
    /// Builds a participant from its section `key` (e.g. `structure.tower`) at t = 0.
    pub fn from_config(cfg: &StructureConfig, key: &str) -> Result<Self, FieldError> {
        cfg.validate(key)?;
        let points: Vec<PointMass> = cfg.point_mass.iter().map(PointMass::from_config).collect();
        let mut bodies = Vec::with_capacity(cfg.body.len());
        for (i, b) in cfg.body.iter().enumerate() {
            let k = format!("{key}.body[{i}]");
            let m = MassProperties::from_config(b, &k)?;
            let [w, x, y, z] = b.orientation;
            let q = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
            let body = RigidBody::new(&b.name, &m, q, V3::from(b.velocity), V3::from(b.angular_velocity))
                .ok_or_else(|| {
                    FieldError::new(format!("{k}.inertia"), "the inertia tensor cannot be inverted")
                })?;
            bodies.push(body);
        }
        let mut s = Self {
            time: 0.0,
            // a frame alone: one (empty) substep per advance; the frame takes its own steps
            max_step: cfg.max_step.unwrap_or(f64::INFINITY),
            gravity: V3::from(cfg.gravity),
            points,
            springs: Vec::new(),
            bodies,
            supports: Vec::new(),
            frame: cfg
                .frame
                .as_ref()
                .map(|f| Frame::from_config(f, &format!("{key}.frame")))
                .transpose()?,
            frame_nodes_at_start: 0,
            substeps: 0,
        };
        s.frame_nodes_at_start = s.frame_node_count();
        for (i, c) in cfg.spring.iter().enumerate() {
            let anchor = |end: &str, name: &str| {
                s.anchor(name).ok_or_else(|| {
                    FieldError::new(format!("{key}.spring[{i}].{end}"), format!("`{name}` is unknown"))
                })
            };
            let spring = Spring {
                a: anchor("a", &c.a)?,
                b: anchor("b", &c.b)?,
                stiffness: c.stiffness,
            };
            s.springs.push(spring);
        }
        for (i, c) in cfg.support.iter().enumerate() {
            let body = s.body_index(&c.body).ok_or_else(|| {
                FieldError::new(
                    format!("{key}.support[{i}].body"),
                    format!("`{}` is not a body", c.body),
                )
            })?;
            s.supports.push(Support {
                body,
                release_force: c.release_force,
                released_at: None,
            });
        }
        let point_mass: Vec<f64> = s.points.iter().map(|p| p.mass).collect();
        let body_mass: Vec<f64> = s.bodies.iter().map(RigidBody::mass).collect();
        check_max_step(
            &format!("{key}.max_step"),
            s.max_step,
            &s.springs,
            &point_mass,
            &body_mass,
            |a| s.anchor_name(a),
        )?;
        Ok(s)
    }

    /// Simulated time reached [s].
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Largest substep [s] (infinite for a frame alone).
    pub fn max_step(&self) -> f64 {
        self.max_step
    }

    /// Substeps taken since t = 0.
    pub fn substeps(&self) -> u64 {
        self.substeps
    }

    pub fn points(&self) -> &[PointMass] {
        &self.points
    }

    pub fn bodies(&self) -> &[RigidBody] {
        &self.bodies
    }

    pub fn supports(&self) -> &[Support] {
        &self.supports
    }

    pub fn point_index(&self, name: &str) -> Option<usize> {
        self.points.iter().position(|p| p.name == name)
    }

    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// Drops what the frame caches to go faster (its factorisation), as a checkpoint file holds it
    /// without: the structure is then exactly the one read back from it (`frame/checkpoint.rs`).
    pub fn drop_caches(&mut self) -> Result<(), String> {
        match &mut self.frame {
            Some(f) => f.drop_caches(),
            None => Ok(()),
        }
    }

    /// The ASI-Gauss frame, if the participant has one.
    pub fn frame(&self) -> Option<&Frame> {
        self.frame.as_ref()
    }

    /// Starts recording the frame's hinge events (for the output's `hinge-events.csv`).
    pub fn record_hinge_events(&mut self) {
        if let Some(f) = &mut self.frame {
            f.record_hinge_events(true);
        }
    }

    /// Starts keeping the frame's energy account (for the output's `energy.csv`).
    pub fn record_energy(&mut self) {
        if let Some(f) = &mut self.frame {
            f.record_energy(true);
        }
    }

    /// Number of frame nodes (0 without a frame).
    pub fn frame_node_count(&self) -> usize {
        self.frame.as_ref().map_or(0, Frame::node_count)
    }

    /// Index of frame node `id` in the node arrays.
    pub fn frame_node_index(&self, id: u32) -> Option<usize> {
        self.frame.as_ref().and_then(|f| f.node_index(id))
    }

    /// Frame node positions, 3 per node (empty without a frame).
    pub fn node_position(&self) -> Vec<f64> {
        self.frame.as_ref().map(Frame::node_positions).unwrap_or_default()
    }

    /// Frame node velocities and angular velocities, 6 per node (empty without a frame).
    pub fn node_velocity(&self) -> Vec<f64> {
        self.frame
            .as_ref()
            .map(Frame::node_velocities)
            .unwrap_or_default()
    }

    /// Whether body `i` is held by a support that has not released it.
    pub fn is_held(&self, i: usize) -> bool {
        self.supports.iter().any(|s| s.body == i && s.holds())
    }

    /// Released bodies with their release time, in support order.
    pub fn releases(&self) -> Vec<(&str, f64)> {
        self.supports
            .iter()
            .filter_map(|s| s.released_at.map(|t| (self.bodies[s.body].name.as_str(), t)))
            .collect()
    }

    /// Point-mass displacements, 3 per point.
    pub fn point_displacement(&self) -> Vec<f64> {
        self.points
            .iter()
            .flat_map(|p| p.displacement.iter().copied().collect::<Vec<_>>())
            .collect()
    }

    /// Point-mass velocities, 3 per point.
    pub fn point_velocity(&self) -> Vec<f64> {
        self.points
            .iter()
            .flat_map(|p| p.velocity.iter().copied().collect::<Vec<_>>())
            .collect()
    }

    /// Body poses, 7 per body: centre x, y, z and quaternion w, x, y, z (body → world).
    pub fn body_pose(&self) -> Vec<f64> {
        self.bodies
            .iter()
            .flat_map(|b| {
                let (c, q) = (b.centre(), b.orientation());
                [c.x, c.y, c.z, q.w, q.i, q.j, q.k]
            })
            .collect()
    }

    /// Body velocities, 6 per body: velocity of the centre and angular velocity (world).
    pub fn body_velocity(&self) -> Vec<f64> {
        self.bodies
            .iter()
            .flat_map(|b| {
                let (v, w) = (b.velocity(), b.angular_velocity());
                [v.x, v.y, v.z, w.x, w.y, w.z]
            })
            .collect()
    }

    /// Advances from [`Structure::time`] to exactly `t_end` in equal substeps ≤ `max_step`,
    /// reading the external loads at any time from `external` (which may fail, e.g. on inputs
    /// of the wrong size). Frame node loads may cover only the nodes there were before any
    /// fracture (a load schedule is made once, a coupler may not have seen the new geometry yet):
    /// the nodes made by fracture come last and get no load then.
    pub fn advance(&mut self, t_end: f64, external: &Loads) -> Result<(), StepError> {
        self.advance_reporting(t_end, external, &mut DiscardProgress)
    }

    /// [`Structure::advance`], telling `progress` of every substep and frame step it finishes (a
    /// coupled run tells a long window from a hung participant by these reports).
    pub fn advance_reporting(
        &mut self,
        t_end: f64,
        external: &Loads,
        progress: &mut dyn ProgressSink,
    ) -> Result<(), StepError> {
        let t0 = self.time;
        let span = t_end - t0;
        if !(span.is_finite() && span >= 0.0) {
            return Err(StepError::new(
                t0,
                format!("cannot advance from t = {t0} s to t = {t_end} s"),
            ));
        }
        if span == 0.0 {
            return Ok(());
        }
        let n = equal_steps(span, self.max_step);
        let mut start = self.checked_loads(t0, external)?;
        for k in 0..n {
            let t = t0 + span * (k as f64) / (n as f64);
            let t1 = if k + 1 == n {
                t_end
            } else {
                t0 + span * ((k + 1) as f64) / (n as f64)
            };
            let h = t1 - t;
            let mid = self.checked_loads(t + 0.5 * h, external)?;
            let end = self.checked_loads(t1, external)?;
            self.substep(t, h, &start, &mid, &end)?;
            self.time = t1;
            self.substeps += 1;
            start = end;
            progress.step_done(t1);
        }
        self.advance_frame(t0, t_end, external, progress)
    }

    /// Newmark steps of the frame from `t0` to `t_end`, loads at each step end.
    fn advance_frame(
        &mut self,
        t0: f64,
        t_end: f64,
        external: &Loads,
        progress: &mut dyn ProgressSink,
    ) -> Result<(), StepError> {
        let Some(time_step) = self.frame.as_ref().map(Frame::time_step) else {
            return Ok(());
        };
        let span = t_end - t0;
        let n = equal_steps(span, time_step);
        let mut t = t0;
        for k in 0..n {
            let t1 = if k + 1 == n {
                t_end
            } else {
                t0 + span * ((k + 1) as f64) / (n as f64)
            };
            let loads = self.checked_loads(t1, external)?;
            if let Some(frame) = &mut self.frame {
                frame
                    .step(t1 - t, &loads.node_force)
                    .map_err(|m| StepError::new(t, m))?;
            }
            t = t1;
            progress.step_done(t1);
        }
        Ok(())
    }

    fn checked_loads(&self, t: f64, external: &Loads) -> Result<ExternalLoads, StepError> {
        let mut e = external(t).map_err(|m| StepError::new(t, m))?;
        let nodes = 6 * self.frame_node_count();
        let nodes_covered =
            6 * self.frame_nodes_at_start <= e.node_force.len() && e.node_force.len() <= nodes;
        let expect = [3 * self.points.len(), 6 * self.bodies.len(), nodes];
        let got = [e.point_force.len(), e.body_force.len(), e.node_force.len()];
        if expect[..2] != got[..2] || !nodes_covered {
            return Err(StepError::new(
                t,
                format!(
                    "external loads have {got:?} values (point, body, node), expected {expect:?} (node loads \
                     may leave out the {} nodes made by fracture)",
                    self.frame_node_count() - self.frame_nodes_at_start
                ),
            ));
        }
        e.node_force.resize(nodes, 0.0);
        Ok(e)
    }

    fn substep(
        &mut self,
        t: f64,
        h: f64,
        start: &ExternalLoads,
        mid: &ExternalLoads,
        end: &ExternalLoads,
    ) -> Result<(), StepError> {
        let point_u: Vec<V3> = self.points.iter().map(|p| p.displacement).collect();
        let body_u0: Vec<V3> = self.bodies.iter().map(RigidBody::displacement).collect();
        let body_forces = self.body_forces(start, &point_u, &body_u0);
        let up = self.up();
        for s in &mut self.supports {
            let applied = body_forces[s.body].0 - self.bodies[s.body].mass() * self.gravity;
            s.check_release(t, applied.dot(&up));
        }
        for (j, (force, torque)) in body_forces.iter().enumerate() {
            if self.is_held(j) {
                self.bodies[j].stop();
            } else {
                self.bodies[j].kick(0.5 * h, force, torque);
                self.bodies[j].drift(h).map_err(|m| StepError::new(t, m))?;
            }
        }
        let body_u1: Vec<V3> = self.bodies.iter().map(RigidBody::displacement).collect();
        self.rk4_points(h, [start, mid, end], &body_u0, &body_u1);
        let point_u: Vec<V3> = self.points.iter().map(|p| p.displacement).collect();
        let body_forces = self.body_forces(end, &point_u, &body_u1);
        for (j, (force, torque)) in body_forces.iter().enumerate() {
            if !self.is_held(j) {
                self.bodies[j].kick(0.5 * h, force, torque);
            }
        }
        self.check_finite(t)
    }

    /// Classical RK4 for the point masses over `[t, t + h]`, loads at the start, middle and end.
    fn rk4_points(&mut self, h: f64, loads: [&ExternalLoads; 3], body_u0: &[V3], body_u1: &[V3]) {
        if self.points.is_empty() {
            return;
        }
        let u0: Vec<V3> = self.points.iter().map(|p| p.displacement).collect();
        let v0: Vec<V3> = self.points.iter().map(|p| p.velocity).collect();
        let body_at = |s: f64| -> Vec<V3> {
            body_u0
                .iter()
                .zip(body_u1)
                .map(|(a, b)| a + s * (b - a))
                .collect()
        };
        let (body_mid, body_end) = (body_at(0.5), body_at(1.0));
        let axpy =
            |x: &[V3], a: f64, y: &[V3]| -> Vec<V3> { x.iter().zip(y).map(|(x, y)| x + a * y).collect() };
        let a1 = self.point_accelerations(loads[0], &u0, body_u0);
        let (u2, v2) = (axpy(&u0, 0.5 * h, &v0), axpy(&v0, 0.5 * h, &a1));
        let a2 = self.point_accelerations(loads[1], &u2, &body_mid);
        let (u3, v3) = (axpy(&u0, 0.5 * h, &v2), axpy(&v0, 0.5 * h, &a2));
        let a3 = self.point_accelerations(loads[1], &u3, &body_mid);
        let (u4, v4) = (axpy(&u0, h, &v3), axpy(&v0, h, &a3));
        let a4 = self.point_accelerations(loads[2], &u4, &body_end);
        for (i, p) in self.points.iter_mut().enumerate() {
            p.displacement = u0[i] + h / 6.0 * (v0[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
            p.velocity = v0[i] + h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
        }
    }

    /// Point accelerations: (external + springs) / m + g.
    fn point_accelerations(&self, loads: &ExternalLoads, point_u: &[V3], body_u: &[V3]) -> Vec<V3> {
        let mut point_f = vec![V3::zeros(); self.points.len()];
        let mut body_f = vec![V3::zeros(); self.bodies.len()];
        for s in &self.springs {
            s.add_forces(point_u, body_u, &mut point_f, &mut body_f);
        }
        self.points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                (point_f[i] + V3::from_column_slice(&loads.point_force[3 * i..3 * i + 3])) / p.mass
                    + self.gravity
            })
            .collect()
    }

    /// Force (external + springs + weight) and torque (external) on every body.
    fn body_forces(&self, loads: &ExternalLoads, point_u: &[V3], body_u: &[V3]) -> Vec<(V3, V3)> {
        let mut point_f = vec![V3::zeros(); self.points.len()];
        let mut body_f = vec![V3::zeros(); self.bodies.len()];
        for s in &self.springs {
            s.add_forces(point_u, body_u, &mut point_f, &mut body_f);
        }
        self.bodies
            .iter()
            .enumerate()
            .map(|(j, b)| {
                let e = &loads.body_force[6 * j..6 * j + 6];
                let force = body_f[j] + V3::new(e[0], e[1], e[2]) + b.mass() * self.gravity;
                (force, V3::new(e[3], e[4], e[5]))
            })
            .collect()
    }

    /// "Up" for the washout check: against gravity, or +z without gravity.
    fn up(&self) -> V3 {
        let g = self.gravity.norm();
        if g > 0.0 {
            -self.gravity / g
        } else {
            V3::z()
        }
    }

    fn check_finite(&self, t: f64) -> Result<(), StepError> {
        for p in &self.points {
            if !p
                .displacement
                .iter()
                .chain(p.velocity.iter())
                .all(|v| v.is_finite())
            {
                return Err(StepError::new(
                    t,
                    format!(
                        "point mass `{}` reached a non-finite state (u = {:?}, v = {:?}): unstable — lower max_step or check the loads",
                        p.name,
                        p.displacement.as_slice(),
                        p.velocity.as_slice()
                    ),
                ));
            }
        }
        for b in &self.bodies {
            if !b.is_finite() {
                return Err(StepError::new(
                    t,
                    format!(
                        "body `{}` reached a non-finite state (centre {:?}): unstable — lower max_step or check the loads",
                        b.name,
                        b.centre().as_slice()
                    ),
                ));
            }
        }
        Ok(())
    }

    fn anchor(&self, name: &str) -> Option<Anchor> {
        if name == GROUND {
            return Some(Anchor::Ground);
        }
        self.point_index(name)
            .map(Anchor::Point)
            .or_else(|| self.body_index(name).map(Anchor::Body))
    }

    fn anchor_name(&self, a: Anchor) -> String {
        match a {
            Anchor::Ground => GROUND.to_string(),
            Anchor::Point(i) => self.points[i].name.clone(),
            Anchor::Body(i) => self.bodies[i].name.clone(),
        }
    }
}
