//! `coupler`: run a case, replay a recording, check a case file, or print the case-file
//! reference.

use clap::{Parser, Subcommand};
use coupler::error::CouplerError;
use coupler::estimate::{parse_size, Estimate};
use coupler::replay::{replay, ReplayOptions};
use coupler::report::{report, ReportOptions};
use coupler::run::{default_output_folder, run, RunOptions};
use coupler::validation::{validation, ValidationOptions};
use schemas::case::error::check::short;
use schemas::case::Case;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;

/// Where case keys are documented, and the exit codes: shown under every command's help.
const AFTER_HELP: &str = "\
Case files: every key, with its type, unit, default, allowed values and the method that reads it,
is in docs/guide/case-reference.md (`coupler reference` prints it, generated from the parser's
types); cases/*/case.toml are commented examples.

Exit codes: 0 success (replay: every recorded answer matches, also those of a run that died with
its reason recorded); 1 the run or replay failed (a participant died, hung or failed, no
convergence, output could not be written, replay departed or compared less than the recording, or
the recording is damaged or cut: it has no end record); 2 bad input, nothing was started (case
file, command line, output folder in use or not empty, estimated output too large);
130 interrupted (Ctrl-C, SIGTERM, SIGHUP).";

/// Runs tsunami–structure simulations as cooperating processes: a particle fluid solver and a
/// structure solver started by this coupler, which exchanges their interface data window by
/// window through shared memory, records every message, and can replay a recording against one
/// solver. Start with `coupler check CASE`, then `coupler run CASE`.
#[derive(Parser)]
#[command(version, after_help = AFTER_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a case: starts only the solvers it needs, couples them window by window, and writes
    /// the recording, the action–reaction ledger and each solver's output to the output folder.
    #[command(after_help = AFTER_HELP)]
    Run {
        /// The case file (TOML), e.g. cases/oscillator/case.toml.
        case: PathBuf,
        /// Output folder (default: out/<case name>). It is locked for the run: a second run into it
        /// is refused. A folder that holds an earlier run's files is refused unless --overwrite.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Delete the earlier run's files in the output folder before starting (they are not kept).
        #[arg(long)]
        overwrite: bool,
        /// Refuse a run whose estimated output (printed before it starts) is larger than this:
        /// bytes or a number with k, M, G, T (powers of 1000). A run is also refused when the
        /// estimate exceeds the free disk space.
        #[arg(long, value_name = "SIZE", default_value = "20G", value_parser = parse_size)]
        max_output: u64,
        /// Use another executable for a participant: --exe NAME=PATH (repeatable).
        #[arg(long, value_name = "NAME=PATH", value_parser = parse_exe)]
        exe: Vec<(String, PathBuf)>,
        /// Continue the run whose output folder is OUT from its last complete checkpoint (the case
        /// sets coupling.checkpoint_interval): every output is cut back to that point and appended
        /// to, ending as an uninterrupted run's would. Takes the folder's lock; needs no --overwrite.
        /// The case and the files it names must be as the run was started with (comments, layout and
        /// case.end_time may differ; a changed setting or file is refused, named). With --end-time,
        /// also a finished run: it continues to the new end time.
        #[arg(long, value_name = "OUT", conflicts_with_all = ["out", "overwrite"])]
        resume: Option<PathBuf>,
        /// Run to this time [s] instead of the case's end_time (coupled cases). With --resume OUT:
        /// extend a finished or stopped run to it, from its last checkpoint, which must be earlier;
        /// the outputs end as those of a run to this time from the start (what was written at the
        /// old end is cut off and continued). A run keeps a checkpoint at its end when its end time
        /// is a whole number of checkpoint intervals, so that extending it runs only the new
        /// windows; otherwise it is extended from its last checkpoint before the end.
        #[arg(long, value_name = "SECONDS", value_parser = parse_end_time)]
        end_time: Option<f64>,
    },
    /// Drive one solver with its partners' recorded messages and compare its answers with the
    /// recorded ones; exits non-zero when it departs, when it compared fewer answers than the
    /// recording holds, or when the recording is damaged or cut (it has no end record: the
    /// coupler was killed while writing it, or the file was truncated). The recording of a run
    /// that died with its reason recorded replays what it holds and says where and why it ended.
    #[command(after_help = AFTER_HELP)]
    Replay {
        /// A recording written by `coupler run` (out/<case>/recording.rec).
        recording: PathBuf,
        /// The participant to replay.
        #[arg(long)]
        participant: String,
        /// Use this executable instead of the participant's default solver.
        #[arg(long)]
        exe: Option<PathBuf>,
        /// Replay against this case file instead of the recorded one (e.g. a changed parameter).
        #[arg(long)]
        case: Option<PathBuf>,
        /// Largest relative difference per field that still passes (relative to the recorded
        /// field's largest value).
        #[arg(long, default_value = "1e-9")]
        tolerance: f64,
        /// Output folder (default: out/replay-<participant>); the replayed solver's own output.
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Check a case file, and every file it names (load tables), as `run` would before it starts:
    /// list its participants, print the estimated windows and output size, start nothing.
    #[command(after_help = AFTER_HELP)]
    Check {
        /// The case file (TOML) to check, e.g. cases/oscillator/case.toml.
        case: PathBuf,
        /// The output folder `run` would use (default: out/<case name>), for the free-space check.
        #[arg(long)]
        out: Option<PathBuf>,
        /// The limit `run --max-output` would apply.
        #[arg(long, value_name = "SIZE", default_value = "20G", value_parser = parse_size)]
        max_output: u64,
    },
    #[command(after_help = AFTER_HELP)]
    /// Error against run time (work–precision) of each case's [report] ladders, or with
    /// --stability its families of stiff and extreme runs; --docs puts the latest report into
    /// docs/validation.md's data (then run `coupler validation`).
    Report {
        /// Case files with [reference] and [report] sections.
        cases: Vec<PathBuf>,
        /// Report folder (default: out/report).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The full ladders and families instead of the CI-sized ones.
        #[arg(long)]
        full: bool,
        /// Run the stability families instead of the ladders.
        #[arg(long)]
        stability: bool,
        /// Timed runs after the warm-up (default: each case's report.repeats).
        #[arg(long)]
        repeats: Option<u32>,
        /// Put the latest report of --out into this docs folder: its Markdown as
        /// validation/report-{accuracy,stability}.md (with --full: …-full.md), its figures into
        /// img/report/ (img/report-full/); runs nothing.
        #[arg(long, value_name = "DOCS", num_args = 0..=1, default_missing_value = "docs")]
        docs: Option<PathBuf>,
        /// With --stability: only the family of this name (repeatable).
        #[arg(long)]
        family: Vec<String>,
    },
    /// Print the case-file reference as Markdown: every table and key of a case file with its
    /// type, unit, default, allowed values and the method or backend that reads it, generated
    /// from the types the parser uses (docs/guide/case-reference.md is this output).
    Reference,
    /// Render docs/validation.md from the validation records (docs/validation/records/) and the
    /// report's fragments, and the README's summary table between its marker comments; with
    /// --collect, first merge freshly written records (a test's record replaces its id's older one).
    Validation {
        /// Merge the records in this folder first (the tests write them to out/validation).
        #[arg(long, value_name = "DIR")]
        collect: Option<PathBuf>,
        /// The workspace root, holding docs/ and README.md.
        #[arg(long, default_value = ".")]
        root: PathBuf,
    },
    /// Plot every column of a CSV file against its first column into a PNG (what was drawn
    /// goes beside it as .plot.csv), e.g. the prism sweep's force-per-width.csv.
    Plot {
        /// The CSV file: a header line, then rows of numbers (an empty cell is a missing point).
        csv: PathBuf,
        /// The PNG to write (default: the CSV's name with .png).
        #[arg(long)]
        png: Option<PathBuf>,
        #[arg(long, default_value = "")]
        title: String,
        /// Label of the x axis (the first column).
        #[arg(long, default_value = "t [s]")]
        x_label: String,
        #[arg(long, default_value = "")]
        y_label: String,
        /// A column drawn dashed (repeatable).
        #[arg(long)]
        dashed: Vec<String>,
    },
}

/// `--end-time`: a time in seconds, finite and greater than 0.
fn parse_end_time(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!("expected a time in seconds greater than 0, got `{s}`")),
    }
}

fn parse_exe(s: &str) -> Result<(String, PathBuf), String> {
    match s.split_once('=') {
        Some((name, path)) if !name.is_empty() && !path.is_empty() => {
            Ok((name.to_string(), PathBuf::from(path)))
        }
        _ => Err(format!("expected NAME=PATH, got `{s}`")),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            out,
            overwrite,
            max_output,
            exe,
            resume,
            end_time,
        } => run(&RunOptions {
            case,
            out,
            exe: exe.into_iter().collect::<BTreeMap<_, _>>(),
            overwrite,
            max_output,
            resume,
            end_time,
        }),
        Command::Replay {
            recording,
            participant,
            exe,
            case,
            tolerance,
            out,
        } => replay(&ReplayOptions {
            recording,
            participant,
            exe,
            case,
            tolerance,
            out,
        })
        .map(|_| ()),
        Command::Check {
            case,
            out,
            max_output,
        } => check(&case, out.as_deref(), max_output),
        Command::Report {
            cases,
            out,
            full,
            stability,
            repeats,
            docs,
            family,
        } => report(&ReportOptions {
            cases,
            out,
            full,
            stability,
            repeats,
            docs,
            families: family,
        }),
        Command::Reference => print_text(&schemas::case::key_reference::markdown()),
        Command::Validation { collect, root } => validation(&ValidationOptions { root, collect }),
        Command::Plot {
            csv,
            png,
            title,
            x_label,
            y_label,
            dashed,
        } => plot(&csv, png, &title, &x_label, &y_label, &dashed),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            coupler::say!("error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// `coupler plot`: see [`coupler::report::line_plot`].
fn plot(
    csv: &std::path::Path,
    png: Option<PathBuf>,
    title: &str,
    x_label: &str,
    y_label: &str,
    dashed: &[String],
) -> Result<(), CouplerError> {
    use coupler::report::line_plot::{draw, read_lines};
    let text = std::fs::read_to_string(csv)
        .map_err(|e| CouplerError::Io(format!("cannot read {}: {e}", csv.display())))?;
    let lines = read_lines(&text, csv, dashed).map_err(CouplerError::Usage)?;
    let png = png.unwrap_or_else(|| csv.with_extension("png"));
    draw(&png, title, x_label, y_label, &lines).map_err(CouplerError::Io)?;
    print_lines(&[format!(
        "wrote {} ({} series) and {}",
        png.display(),
        lines.len(),
        png.with_extension("plot.csv").display()
    )])
}

fn check(path: &std::path::Path, out: Option<&std::path::Path>, max_output: u64) -> Result<(), CouplerError> {
    let case = Case::load(path)?;
    let mut lines = Vec::new();
    lines.push(format!(
        "{}: case `{}`, end time {} s",
        path.display(),
        case.info.name,
        short(case.info.end_time)
    ));
    for (name, kind) in case.participants() {
        let exe = coupler::launch::executable_for(&case, &name, kind, &BTreeMap::new())?;
        let launcher = coupler::launch::launcher_for(&case, &name)?;
        let ranks = match launcher.is_empty() {
            true => String::new(),
            false => format!(
                ", on {} ranks through `{}`",
                case.fluid[&name].rank_count(),
                launcher.join(" ")
            ),
        };
        lines.push(format!(
            "  participant {name}: {} ({}{ranks})",
            kind.binary_name(),
            exe.display()
        ));
    }
    if let Some(c) = &case.coupling {
        lines.push(format!(
            "  coupling: {:?}, window {} s, {} sample(s) per window",
            c.scheme,
            short(c.window),
            c.samples
        ));
        if let (Some(interval), Some(every)) = (c.checkpoint_interval, c.checkpoint_windows()) {
            let windows = coupler::scheme::window_count(case.info.end_time, c.window);
            let at_end = if windows.is_multiple_of(every)
                && coupler::scheme::ends_on_window(case.info.end_time, c.window)
            {
                "; one at the end too (run --resume OUT --end-time T extends the run from it)"
            } else {
                "; none at the end (end_time is not a whole number of intervals)"
            };
            lines.push(format!(
                "  checkpoints: every {} s ({every} windows), the last {} kept in OUT/checkpoint/{at_end}",
                short(interval),
                coupler::checkpoint::KEEP
            ));
        }
    }
    if let Some(r) = &case.reference {
        lines.push(format!(
            "  reference: {:?}, {:?} error ({})",
            r.against, r.measure, r.source
        ));
    }
    if let Some(r) = &case.report {
        lines.push(format!(
            "  report: {} ladder(s), {} stability family(ies)",
            r.ladder.len(),
            r.stability.len()
        ));
    }
    let estimate = Estimate::of(&case);
    lines.push(format!("  estimate: {}", estimate.describe()));
    lines.extend(case.warnings().iter().map(|u| format!("  warning: {u}")));
    print_lines(&lines)?;
    let out = default_output_folder(&case, out);
    coupler::out_folder::check_place(&out)?;
    estimate.check(&out, max_output)
}

/// Writes `lines` to standard output; a reader that closed the pipe early (`coupler check … | head`)
/// is not an error.
fn print_lines(lines: &[String]) -> Result<(), CouplerError> {
    let mut text = lines.join("\n");
    text.push('\n');
    print_text(&text)
}

/// Writes `text` to standard output, as [`print_lines`].
fn print_text(text: &str) -> Result<(), CouplerError> {
    use std::io::Write;
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(CouplerError::Io(format!("cannot write to standard output: {e}")))
        }
        _ => Ok(()),
    }
}
