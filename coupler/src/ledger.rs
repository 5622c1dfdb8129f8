//! The action–reaction ledger: per window, the force each participant was given, their sum,
//! and the work done on each side across the interface, written to `ledger.csv`.

use crate::error::CouplerError;
use crate::interface::Interface;
use schemas::message::Fields;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Which window ended, when, and how its coupling iteration went.
#[derive(Debug, Clone, Copy)]
pub struct WindowEnd {
    pub window: u64,
    pub time: f64,
    pub iterations: u32,
    pub residual: f64,
}

/// Writes one CSV line per window and counts windows whose balance is off.
pub struct Ledger {
    out: BufWriter<File>,
    path: PathBuf,
    tolerance: f64,
    /// Windows whose relative force balance exceeded the tolerance.
    pub violations: u64,
    /// Largest relative force balance seen.
    pub worst_balance: f64,
}

impl Ledger {
    /// Creates `path` with its header line.
    pub fn create(path: &Path, names: &[String], tolerance: f64) -> Result<Ledger, CouplerError> {
        let io = |e: std::io::Error| CouplerError::Io(format!("cannot write {}: {e}", path.display()));
        let mut out = BufWriter::new(File::create(path).map_err(io)?);
        let mut header = String::from("window,time,iterations,residual");
        for n in names {
            header.push_str(&format!(",{n}_fx,{n}_fy,{n}_fz,{n}_work"));
        }
        header.push_str(",net_fx,net_fy,net_fz,balance,status");
        writeln!(out, "{header}").map_err(io)?;
        Ok(Ledger {
            out,
            path: path.to_path_buf(),
            tolerance,
            violations: 0,
            worst_balance: 0.0,
        })
    }

    /// Continues `path` (a resumed run, cut back to the checkpoint: header and earlier rows are there).
    pub fn append(path: &Path, tolerance: f64) -> Result<Ledger, CouplerError> {
        let out = schemas::checkpoint::append(path)
            .map_err(|e| CouplerError::Io(format!("cannot continue {}: {e}", path.display())))?;
        Ok(Ledger {
            out: BufWriter::new(out),
            path: path.to_path_buf(),
            tolerance,
            violations: 0,
            worst_balance: 0.0,
        })
    }

    /// One window: forces at the window end and work over the window, as the laws report them, and the balance
    /// `|Σ_p f_p| / Σ_p |f_p|` (0 when no force crossed).
    pub fn window(
        &mut self,
        end: WindowEnd,
        interface: &Interface,
        inputs: &[Vec<Fields>],
        outputs: &[Vec<Fields>],
    ) -> Result<(), CouplerError> {
        let WindowEnd {
            window,
            time,
            iterations,
            residual,
        } = end;
        let mut line = format!("{window},{time:.9e},{iterations},{residual:.3e}");
        let mut net = [0.0; 3];
        let mut magnitude = 0.0;
        for (p, (p_inputs, p_outputs)) in inputs.iter().zip(outputs).enumerate() {
            let f = match (p_inputs.last(), p_outputs.last()) {
                (Some(i), Some(o)) => interface.force_taken(p, i, o),
                _ => [0.0; 3],
            };
            let work = interface.window_work(p, p_inputs, p_outputs);
            line.push_str(&format!(",{:.12e},{:.12e},{:.12e},{work:.12e}", f[0], f[1], f[2]));
            (0..3).for_each(|c| net[c] += f[c]);
            magnitude += f.iter().map(|v| v * v).sum::<f64>().sqrt();
        }
        let net_norm = net.iter().map(|v| v * v).sum::<f64>().sqrt();
        let balance = if magnitude > 0.0 {
            net_norm / magnitude
        } else {
            0.0
        };
        self.worst_balance = self.worst_balance.max(balance);
        let ok = balance <= self.tolerance;
        if !ok {
            self.violations += 1;
            crate::say!(
                "ledger: window {window} (t = {time:.6} s): action and reaction differ by {balance:.3e} (relative), \
                 above coupling.balance_tolerance {:.1e}",
                self.tolerance
            );
        }
        line.push_str(&format!(
            ",{:.12e},{:.12e},{:.12e},{balance:.3e},{}",
            net[0],
            net[1],
            net[2],
            if ok { "ok" } else { "VIOLATED" }
        ));
        let io = |e: std::io::Error| CouplerError::Io(format!("cannot write {}: {e}", self.path.display()));
        writeln!(self.out, "{line}").map_err(io)?;
        self.out.flush().map_err(io)
    }
}
