//! [`ExternalLoads`]: the loads applied to a structure at one instant, in interface order.

use schemas::message::Fields;

/// Forces on point masses (3 each), force and torque on bodies (6 each, world, about the centre)
/// and force and moment on frame nodes (6 each, global).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExternalLoads {
    pub point_force: Vec<f64>,
    pub body_force: Vec<f64>,
    pub node_force: Vec<f64>,
}

impl ExternalLoads {
    /// No load on `points` point masses, `bodies` bodies and `nodes` frame nodes.
    pub fn zeros(points: usize, bodies: usize, nodes: usize) -> Self {
        Self {
            point_force: vec![0.0; 3 * points],
            body_force: vec![0.0; 6 * bodies],
            node_force: vec![0.0; 6 * nodes],
        }
    }

    /// Adds the coupler's input arrays; an empty array means no load. Point and body arrays must
    /// match; node arrays may differ in length by nodes made by fracture (they come last and carry
    /// no load where an array leaves them out), which [`crate::Structure::advance`] checks.
    pub fn add_fields(&mut self, f: &Fields) -> Result<(), String> {
        add(&mut self.point_force, &f.point_force, "point_force")?;
        add(&mut self.body_force, &f.body_force, "body_force")?;
        if self.node_force.len() < f.node_force.len() {
            self.node_force.resize(f.node_force.len(), 0.0);
        }
        self.node_force
            .iter_mut()
            .zip(f.node_force.iter())
            .for_each(|(a, b)| *a += b);
        Ok(())
    }
}

fn add(to: &mut [f64], from: &[f64], name: &str) -> Result<(), String> {
    if from.is_empty() {
        return Ok(());
    }
    if from.len() != to.len() {
        return Err(format!(
            "input `{name}` has {} values, this structure expects {}",
            from.len(),
            to.len()
        ));
    }
    to.iter_mut().zip(from).for_each(|(a, b)| *a += b);
    Ok(())
}
