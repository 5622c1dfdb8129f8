//! [`LoadSchedule`]: the prescribed loads of a case (`[[structure.NAME.load]]`) as a function of
//! time, in the interface order of a [`Structure`].

use crate::external_loads::ExternalLoads;
use crate::load_history::LoadHistory;
use crate::structure::Structure;
use schemas::case::load_table::LoadTable;
use schemas::case::structure::{LoadConfig, LoadHistory as HistoryKind, LoadTarget, StructureConfig};
use schemas::case::FieldError;
use std::path::Path;

/// Where a load goes: the first of its components' index in the point, body or node array.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    Point(usize),
    Body(usize),
    Node(usize),
}

/// Every prescribed load of one structure participant.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSchedule {
    loads: Vec<(Slot, LoadHistory)>,
    points: usize,
    bodies: usize,
    nodes: usize,
}

impl LoadSchedule {
    /// Builds the loads of `cfg` (section `key`) for `structure`; table paths are taken relative to
    /// `case_dir`. Tables are read here, so a missing or malformed file is an error now.
    pub fn from_config(
        cfg: &StructureConfig,
        key: &str,
        case_dir: &Path,
        structure: &Structure,
    ) -> Result<Self, FieldError> {
        let loads = cfg
            .load
            .iter()
            .enumerate()
            .map(|(i, l)| load(l, &format!("{key}.load[{i}]"), case_dir, structure))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            loads,
            points: structure.points().len(),
            bodies: structure.bodies().len(),
            nodes: structure.frame_node_count(),
        })
    }

    /// The prescribed loads at time `t`.
    pub fn at(&self, t: f64) -> ExternalLoads {
        let mut out = ExternalLoads::zeros(self.points, self.bodies, self.nodes);
        for (slot, history) in &self.loads {
            let target = match *slot {
                Slot::Point(i) => &mut out.point_force[3 * i..3 * i + 3],
                Slot::Body(i) => &mut out.body_force[6 * i..6 * i + 6],
                Slot::Node(i) => &mut out.node_force[6 * i..6 * i + 6],
            };
            history.add_at(t, target);
        }
        out
    }
}

fn load(
    l: &LoadConfig,
    key: &str,
    case_dir: &Path,
    s: &Structure,
) -> Result<(Slot, LoadHistory), FieldError> {
    let target = l.target(key)?;
    let unknown =
        |what: &str, name: String| FieldError::new(format!("{key}.{what}"), format!("`{name}` is unknown"));
    let slot = match target {
        LoadTarget::Point(p) => Slot::Point(s.point_index(p).ok_or_else(|| unknown("point", p.to_string()))?),
        LoadTarget::Body(b) => Slot::Body(s.body_index(b).ok_or_else(|| unknown("body", b.to_string()))?),
        LoadTarget::Node(n) => Slot::Node(
            s.frame_node_index(n)
                .ok_or_else(|| unknown("node", n.to_string()))?,
        ),
    };
    let value = || {
        l.value
            .clone()
            .ok_or_else(|| FieldError::new(format!("{key}.value"), "is required"))
    };
    let time = |name: &str, t: Option<f64>| {
        t.ok_or_else(|| FieldError::new(format!("{key}.{name}"), "is required with this history"))
    };
    let history = match l.history {
        HistoryKind::Constant => LoadHistory::Constant(value()?),
        HistoryKind::Step => LoadHistory::Step {
            start: time("start", l.start)?,
            value: value()?,
        },
        HistoryKind::Ramp => LoadHistory::Ramp {
            start: time("start", l.start)?,
            end: time("end", l.end)?,
            value: value()?,
        },
        HistoryKind::Table => {
            let file = l
                .table
                .as_ref()
                .ok_or_else(|| FieldError::new(format!("{key}.table"), "is required"))?;
            // an absolute path replaces the case's folder (`Path::join`)
            let path = case_dir.join(file);
            LoadHistory::Table(LoadTable::read(
                &path,
                target.components(),
                &format!("{key}.table"),
            )?)
        }
    };
    Ok((slot, history))
}
