//! The case file: TOML → a typed, validated [`Case`].
//!
//! A case names its participants by kind and name (`[fluid.NAME]`, `[structure.NAME]`),
//! says how long to simulate (`[case]`) and, when there is more than one participant,
//! how they are coupled (`[coupling]`). Unknown keys are errors; every error names the
//! file, the key and what is allowed.

pub mod coupling;
pub mod drag;
pub mod error;
pub mod fluid;
pub mod frame;
pub mod inputs;
pub mod key_reference;
pub mod load_table;
pub mod mesh_placement;
pub mod reference;
pub mod report;
pub mod structure;

use schemars::JsonSchema;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub use coupling::CouplingConfig;
pub use error::{CaseError, FieldError};
pub use fluid::FluidConfig;
pub use reference::ReferenceConfig;
pub use report::ReportConfig;
pub use structure::StructureConfig;

/// `[case]`: what the run is and how long it lasts.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CaseInfo {
    /// Short name of the case, used in output file names; not empty.
    pub name: String,
    /// One or two sentences on what the case is and where its reference data come from.
    #[serde(default)]
    pub description: Option<String>,
    /// Simulated time to reach [s]. Range: > 0.
    pub end_time: f64,
    /// Executable per participant name, replacing the default solver binary
    /// (relative paths are taken from the case file's folder).
    #[serde(default)]
    pub executables: BTreeMap<String, PathBuf>,
}

/// A case file: `[case]`, the participants and, as needed, `[coupling]`, `[reference]` and
/// `[report]` (the file as written; [`Case`] adds where it came from).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    /// What the run is and how long it lasts.
    case: CaseInfo,
    /// The fluid participants, one table each, named by the user.
    #[serde(default)]
    fluid: BTreeMap<String, FluidConfig>,
    /// The structure participants, one table each, named by the user.
    #[serde(default)]
    structure: BTreeMap<String, StructureConfig>,
    /// How the participants are coupled; required with more than one participant.
    #[serde(default)]
    coupling: Option<CouplingConfig>,
    /// What `coupler report` compares the result against.
    #[serde(default)]
    reference: Option<ReferenceConfig>,
    /// The ladders and stability families of `coupler report`.
    #[serde(default)]
    report: Option<ReportConfig>,
}

/// Which solver a participant runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Fluid,
    Structure,
}

impl Kind {
    /// The default executable's file name for this kind.
    pub fn binary_name(self) -> &'static str {
        match self {
            Kind::Fluid => "fluid-solver",
            Kind::Structure => "structure-solver",
        }
    }
}

/// A validated case.
#[derive(Debug, Clone)]
pub struct Case {
    /// The case file.
    pub path: PathBuf,
    /// The case file's text, as read (recordings keep it so a replay needs nothing else).
    pub text: String,
    /// FNV-1a hash of the text; participants and recordings carry it.
    pub hash: u64,
    pub info: CaseInfo,
    pub fluid: BTreeMap<String, FluidConfig>,
    pub structure: BTreeMap<String, StructureConfig>,
    pub coupling: Option<CouplingConfig>,
    /// What the result is compared against (`coupler report`).
    pub reference: Option<ReferenceConfig>,
    /// The ladders and stability families of `coupler report`.
    pub report: Option<ReportConfig>,
}

impl Case {
    /// Reads, parses and validates a case file.
    pub fn load(path: &Path) -> Result<Case, CaseError> {
        Case::load_to(path, None)
    }

    /// Reads, parses and validates a case file, with `end_time` (when given) in place of its
    /// `case.end_time` (`coupler run --end-time`): the case is validated for that end time (a
    /// wave maker's paddle must stay in its tank until then, a coupling window must not be longer).
    /// [`Case::text`] and [`Case::hash`] stay those of the file.
    pub fn load_to(path: &Path, end_time: Option<f64>) -> Result<Case, CaseError> {
        let text = std::fs::read_to_string(path).map_err(|e| CaseError {
            file: path.to_path_buf(),
            key: String::new(),
            message: format!("cannot read the case file: {e}"),
        })?;
        Case::parse_to(path, text, end_time)
    }

    /// Parses and validates case text that came from `path`.
    pub fn parse(path: &Path, text: String) -> Result<Case, CaseError> {
        Case::parse_to(path, text, None)
    }

    /// Parses and validates case text that came from `path`, with `end_time` (when given) in place
    /// of its `case.end_time`, as [`Case::load_to`].
    pub fn parse_to(path: &Path, text: String, end_time: Option<f64>) -> Result<Case, CaseError> {
        if text.trim().is_empty() {
            return Err(CaseError {
                file: path.to_path_buf(),
                key: String::new(),
                message:
                    "the case file is empty: it needs at least a [case] section with `name` and `end_time`, \
                          and one [fluid.NAME] or [structure.NAME] section"
                        .into(),
            });
        }
        let mut file: CaseFile = toml::from_str(&text).map_err(|e| CaseError {
            file: path.to_path_buf(),
            key: e.span().map(|s| key_at(&text, s.start)).unwrap_or_default(),
            message: match e.span() {
                Some(span) => error::located(&text, span.start, e.message().trim()),
                None => e.message().trim().to_string(),
            },
        })?;
        if let Some(t) = end_time {
            file.case.end_time = t;
        }
        let mut case = Case {
            path: path.to_path_buf(),
            hash: fnv1a(text.as_bytes()),
            text,
            info: file.case,
            fluid: file.fluid,
            structure: file.structure,
            coupling: file.coupling,
            reference: file.reference,
            report: file.report,
        };
        case.read_inflow_series().map_err(|e| CaseError::at(path, e))?;
        case.validate().map_err(|e| CaseError::at(path, e))?;
        case.load_geometry().map_err(|e| CaseError::at(path, e))?;
        Ok(case)
    }

    /// The folder that relative paths in the case are taken from.
    pub fn dir(&self) -> PathBuf {
        self.path.parent().map(Path::to_path_buf).unwrap_or_default()
    }

    /// Resolves a path written in the case against the case's folder (an absolute path stays as
    /// it is: [`Path::join`] replaces the folder with it).
    pub fn resolve(&self, p: &Path) -> PathBuf {
        self.dir().join(p)
    }

    /// Each fluid section's warnings ([`fluid::FluidConfig::warnings`]: settings its method leaves
    /// unused, ISPH settings that misread a load in its geometry), as `fluid.NAME: …` for a
    /// `warning: ` line.
    pub fn fluid_warnings(&self) -> Vec<String> {
        self.fluid
            .iter()
            .flat_map(|(name, cfg)| {
                cfg.warnings()
                    .into_iter()
                    .map(move |u| format!("fluid.{name}: {u}"))
            })
            .collect()
    }

    /// Everything a run tells the user before it starts, as `section: …` for a `warning: ` line:
    /// the fluid sections' ([`Case::fluid_warnings`]), frames that nothing holds, and drag
    /// settings that change the result ([`drag::DragLink::warnings`]).
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = self.fluid_warnings();
        warnings.extend(self.frame_and_drag_warnings());
        warnings
    }

    /// The warnings of [`Case::warnings`] that no fluid solver prints itself: frames that nothing
    /// holds and drag settings that change the result.
    pub fn frame_and_drag_warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        for (name, s) in &self.structure {
            if let Some(frame) = &s.frame {
                if frame.support.is_empty() && frame.wall.is_empty() {
                    warnings.push(format!(
                        "structure.{name}.frame: no [[support]] and no contact [[wall]] holds the frame: it falls freely under gravity and drifts under its loads; add a support if it stands on something"
                    ));
                }
            }
        }
        let links = self.coupling.iter().flat_map(|c| c.drag.iter());
        for (i, link) in links.enumerate() {
            warnings.extend(
                link.warnings(self)
                    .into_iter()
                    .map(|w| format!("coupling.drag[{i}]: {w}")),
            );
        }
        warnings
    }

    /// Participant names with their kind: fluid participants first, then structure ones.
    pub fn participants(&self) -> Vec<(String, Kind)> {
        let fluid = self.fluid.keys().map(|n| (n.clone(), Kind::Fluid));
        let structure = self.structure.keys().map(|n| (n.clone(), Kind::Structure));
        fluid.chain(structure).collect()
    }

    /// The kind of the participant `name`, if the case has one.
    pub fn kind_of(&self, name: &str) -> Option<Kind> {
        self.participants()
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, k)| k)
    }

    fn validate(&self) -> Result<(), FieldError> {
        error::check::positive("case.end_time", self.info.end_time)?;
        if self.info.name.trim().is_empty() {
            return Err(FieldError::new("case.name", "must not be empty"));
        }
        let names = self.participants();
        if names.is_empty() {
            return Err(FieldError::new(
                "",
                "the case has no participant: add a [fluid.NAME] or [structure.NAME] section",
            ));
        }
        for (name, kind) in &names {
            let section = match kind {
                Kind::Fluid => "fluid",
                Kind::Structure => "structure",
            };
            check_participant_name(&format!("{section}.{name}"), name)?;
        }
        if let Some(dup) = self.fluid.keys().find(|n| self.structure.contains_key(*n)) {
            return Err(FieldError::new(
                format!("structure.{dup}"),
                format!("participant name `{dup}` is used by a fluid and a structure section; names must be unique"),
            ));
        }
        for name in self.info.executables.keys() {
            if self.kind_of(name).is_none() {
                return Err(FieldError::new(
                    format!("case.executables.{name}"),
                    format!("names no participant; participants are: {}", list(&names)),
                ));
            }
        }
        for (name, cfg) in &self.fluid {
            cfg.validate(&format!("fluid.{name}"))?;
        }
        for (name, cfg) in &self.structure {
            cfg.validate(&format!("structure.{name}"))?;
        }
        self.check_files()?;
        match (&self.coupling, names.len()) {
            (None, n) if n > 1 => {
                return Err(FieldError::new(
                    "coupling",
                    format!(
                        "the case has {n} participants ({}) and needs a [coupling] section",
                        list(&names)
                    ),
                ))
            }
            (Some(c), _) => c.validate(self)?,
            _ => {}
        }
        if let Some(r) = &self.reference {
            r.validate(self)?;
        }
        match &self.report {
            Some(r) => r.validate(self),
            None => Ok(()),
        }
    }
}

impl Case {
    /// Reads the inflow series of the fluid sections, relative to the case's folder, before they
    /// are validated: the strip's height and the time step's velocity scale come from them.
    fn read_inflow_series(&mut self) -> Result<(), FieldError> {
        let dir = self.dir();
        for (name, cfg) in &mut self.fluid {
            if let Some(inflow) = &mut cfg.inflow {
                inflow.read_series(&dir, &format!("fluid.{name}.inflow"))?;
            }
        }
        Ok(())
    }

    /// Reads the meshes and height grids of the fluid sections and builds their wave makers'
    /// motions (reading their tables), and reads the structure bodies' inertia meshes, relative
    /// to the case's folder.
    fn load_geometry(&mut self) -> Result<(), FieldError> {
        let dir = self.dir();
        let end = self.info.end_time;
        for (name, cfg) in &mut self.fluid {
            let key = format!("fluid.{name}");
            cfg.load_files(&dir, &key)?;
            cfg.build_wave_maker(&dir, &key, end)?;
        }
        for (name, cfg) in &mut self.structure {
            for (i, b) in cfg.body.iter_mut().enumerate() {
                b.load_mesh(&dir, &format!("structure.{name}.body[{i}]"))?;
            }
        }
        Ok(())
    }

    /// Reads and checks every file the case names (load tables), so that a bad one is refused
    /// before anything starts, with its line and what is wrong.
    fn check_files(&self) -> Result<(), FieldError> {
        for (name, cfg) in &self.structure {
            for (i, load) in cfg.load.iter().enumerate() {
                if let Some(table) = &load.table {
                    let key = format!("structure.{name}.load[{i}]");
                    let components = load.target(&key)?.components();
                    load_table::LoadTable::read(&self.resolve(table), components, &format!("{key}.table"))?;
                }
            }
        }
        Ok(())
    }
}

/// Participant names go into shared-memory service names: lowercase letters, digits and `-`.
fn check_participant_name(key: &str, name: &str) -> Result<(), FieldError> {
    let ok = !name.is_empty()
        && name.len() <= 32
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-');
    if ok {
        Ok(())
    } else {
        Err(FieldError::new(
            key,
            format!("participant name `{name}` must be 1–32 characters of a–z, 0–9 and `-`"),
        ))
    }
}

fn list(names: &[(String, Kind)]) -> String {
    names
        .iter()
        .map(|(n, _)| n.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The dotted key of the TOML line that holds byte `offset` (best effort, for error messages).
fn key_at(text: &str, offset: usize) -> String {
    let mut table = String::new();
    let mut key = String::new();
    let mut pos = 0;
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with('[') {
            table = trimmed.trim_matches(|c| c == '[' || c == ']').trim().to_string();
            key.clear();
        } else if let Some((k, _)) = trimmed.split_once('=') {
            key = k.trim().to_string();
        } else if !trimmed.is_empty() && !trimmed.starts_with('#') {
            // a key without `= value`
            key = trimmed.split_whitespace().next().unwrap_or_default().to_string();
        }
        pos += line.len() + 1;
        if pos > offset {
            break;
        }
    }
    match (table.is_empty(), key.is_empty()) {
        (true, _) => key,
        (false, true) => table,
        (false, false) => format!("{table}.{key}"),
    }
}

/// 64-bit FNV-1a: a stable hash of the case text (std's hasher is not stable across releases).
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
