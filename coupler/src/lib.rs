//! The coupler: the user's entry point. It starts the participants a case needs, runs the
//! coupling windows (explicit, or implicit with acceleration), computes the interface laws
//! once for both sides, keeps the action–reaction ledger, records every message, and replays
//! recordings against one solver, and reports error against run time and stability; and renders
//! the validation page from the records the validation tests write.

pub mod acceleration;
pub mod checkpoint;
pub mod error;
pub mod estimate;
pub mod interface;
pub mod launch;
pub mod laws;
pub mod ledger;
pub mod out_folder;
pub mod progress;
pub mod replay;
pub mod report;
pub mod run;
pub mod scheme;
pub mod stability;
pub mod stack;
pub mod state;
pub mod terminal;
pub mod validation;
