//! ESRI ASCII grids (`.asc`, "Arc/Info ASCII Grid"): a header of `key value` lines, then `nrows`
//! lines of `ncols` values, the first line the NORTHERNMOST row (highest y); the values are
//! heights at the cell centres.
//!
//! Header keys, in any letter case and order: `ncols`, `nrows`; `xllcorner` (west edge of the
//! grid) or `xllcenter` (centre of the west column); `yllcorner` or `yllcenter` likewise for the
//! south; `cellsize`, or `dx` and `dy` for rectangular cells; optionally `NODATA_value`. A cell
//! holding the NODATA value is refused: a terrain must have a height everywhere.

use super::error::GridError;
use super::height_grid::HeightGrid;
use crate::atomic_file;
use std::collections::HashMap;
use std::path::Path;

/// The header keys read, lower case.
const KEYS: [&str; 10] = [
    "ncols",
    "nrows",
    "xllcorner",
    "xllcenter",
    "yllcorner",
    "yllcenter",
    "cellsize",
    "dx",
    "dy",
    "nodata_value",
];

/// The allowed keys for messages.
const ALLOWED: &str =
    "ncols, nrows, xllcorner or xllcenter, yllcorner or yllcenter, cellsize (or dx and dy), \
                       NODATA_value (optional)";

/// Reads the ESRI ASCII grid `path` (module doc for the format). Refuses a missing, repeated or
/// unknown header key, a count that is not a positive integer, a cell size that is not finite and
/// positive, a wrong number of rows or of values in a row (expected and got), and a value that is
/// NODATA or not a finite number (naming its row and column counted from 1 at the top-left, as in
/// the file, and the cell's x, y). Every error names the file and, where one line is at fault,
/// the line.
pub fn read_height_grid(path: &Path) -> Result<HeightGrid, GridError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| GridError::at(path, None, format!("cannot be read as text: {e}")))?;
    parse(path, &text)
}

/// The header's values, by lower-case key, with the line each came from.
struct Header<'a> {
    path: &'a Path,
    values: HashMap<&'static str, (&'a str, usize)>,
}

impl Header<'_> {
    fn get(&self, key: &str) -> Option<(&str, usize)> {
        self.values.get(key).copied()
    }

    fn number(&self, key: &str) -> Result<Option<f64>, GridError> {
        match self.get(key) {
            None => Ok(None),
            Some((value, line)) => match value.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(GridError::at(
                    self.path,
                    Some(line),
                    format!("`{key}` is `{value}`: it must be a finite number"),
                )),
            },
        }
    }

    fn count(&self, key: &str) -> Result<usize, GridError> {
        let (value, line) = self.get(key).ok_or_else(|| self.missing(key))?;
        match value.parse::<usize>() {
            Ok(n) if n > 0 => Ok(n),
            _ => Err(GridError::at(
                self.path,
                Some(line),
                format!("`{key}` is `{value}`: it must be a whole number > 0"),
            )),
        }
    }

    fn missing(&self, what: &str) -> GridError {
        GridError::at(
            self.path,
            None,
            format!("the header has no `{what}`; an ESRI ASCII grid's header holds {ALLOWED}"),
        )
    }

    /// The centre of the first cell along one axis, from `{x|y}llcorner` or `{x|y}llcenter`.
    fn first_centre(&self, axis: &str, size: f64) -> Result<f64, GridError> {
        let corner = format!("{axis}llcorner");
        let centre = format!("{axis}llcenter");
        match (self.number(&corner)?, self.number(&centre)?) {
            (Some(_), Some(_)) => Err(GridError::at(
                self.path,
                self.get(&centre).map(|(_, l)| l),
                format!("the header has both `{corner}` and `{centre}`: give one"),
            )),
            (Some(c), None) => Ok(c + 0.5 * size),
            (None, Some(c)) => Ok(c),
            (None, None) => Err(self.missing(&format!("{corner}` or `{centre}"))),
        }
    }

    /// The cell size `[dx, dy]`, from `cellsize` or from `dx` and `dy`.
    fn spacing(&self) -> Result<[f64; 2], GridError> {
        let spacing = match (self.number("cellsize")?, self.number("dx")?, self.number("dy")?) {
            (Some(d), None, None) => [d, d],
            (None, Some(dx), Some(dy)) => [dx, dy],
            (None, None, None) => return Err(self.missing("cellsize")),
            (None, _, _) => return Err(self.missing(if self.get("dx").is_none() { "dx" } else { "dy" })),
            (Some(_), _, _) => {
                return Err(GridError::at(
                    self.path,
                    self.get("cellsize").map(|(_, l)| l),
                    "the header has `cellsize` and `dx`/`dy`: give `cellsize` alone, or `dx` and `dy`",
                ))
            }
        };
        if let Some(d) = spacing.iter().find(|d| **d <= 0.0) {
            let line = ["cellsize", "dx", "dy"]
                .iter()
                .find_map(|k| self.get(k))
                .map(|(_, l)| l);
            return Err(GridError::at(
                self.path,
                line,
                format!("the cell size (`cellsize`, or `dx` and `dy`) is {d}: it must be > 0"),
            ));
        }
        Ok(spacing)
    }
}

fn parse(path: &Path, text: &str) -> Result<HeightGrid, GridError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(n, l)| (n + 1, l))
        .filter(|(_, l)| !l.trim().is_empty())
        .peekable();
    let mut header = Header {
        path,
        values: HashMap::new(),
    };
    let complete = |h: &Header| {
        let has = |k: &str| h.values.contains_key(k);
        has("ncols")
            && has("nrows")
            && (has("cellsize") || (has("dx") && has("dy")))
            && (has("xllcorner") || has("xllcenter"))
            && (has("yllcorner") || has("yllcenter"))
    };
    while let Some(&(line_no, line)) = lines.peek() {
        let mut tokens = line.split_whitespace();
        let Some(first) = tokens.next() else { break };
        if !first.starts_with(|c: char| c.is_ascii_alphabetic()) {
            break;
        }
        let lower = first.to_ascii_lowercase();
        let Some(&key) = KEYS.iter().find(|k| **k == lower) else {
            // after a complete header, `nan` or `inf` starts a row of values (refused as such
            // below), and so does a word in a row that is not `key value`
            let key_like = line.split_whitespace().count() == 2 && first.parse::<f64>().is_err();
            if complete(&header) && !key_like {
                break;
            }
            return Err(GridError::at(
                path,
                Some(line_no),
                format!("unknown header key `{first}`; allowed: {ALLOWED}"),
            ));
        };
        let (Some(value), None) = (tokens.next(), tokens.next()) else {
            return Err(GridError::at(
                path,
                Some(line_no),
                format!("a header line is `key value`, got `{}`", line.trim()),
            ));
        };
        if header.values.insert(key, (value, line_no)).is_some() {
            return Err(GridError::at(
                path,
                Some(line_no),
                format!("`{first}` is given twice"),
            ));
        }
        lines.next();
    }
    let ncols = header.count("ncols")?;
    let nrows = header.count("nrows")?;
    let spacing = header.spacing()?;
    let first_centre = [
        header.first_centre("x", spacing[0])?,
        header.first_centre("y", spacing[1])?,
    ];
    let nodata = header.number("nodata_value")?;

    let cells = ncols
        .checked_mul(nrows)
        .ok_or_else(|| GridError::at(path, None, format!("{ncols} × {nrows} cells are too many")))?;
    // the rows as the file lists them, north first; grown as read, so that a header promising more
    // than the file holds allocates nothing
    let mut north_first = Vec::with_capacity(cells.min(1 << 20));
    let mut rows_read = 0;
    for (line_no, line) in lines {
        rows_read += 1;
        if rows_read > nrows {
            return Err(GridError::at(
                path,
                Some(line_no),
                format!("more rows of values than `nrows` = {nrows}"),
            ));
        }
        let y = first_centre[1] + (nrows - rows_read) as f64 * spacing[1];
        let mut got = 0;
        for (c, token) in line.split_whitespace().enumerate() {
            got += 1;
            if c >= ncols {
                continue;
            }
            let x = first_centre[0] + c as f64 * spacing[0];
            let cell = || {
                format!(
                    "row {rows_read}, column {} (counted from 1 at the top-left, as in the file; the cell \
                     at x = {x}, y = {y})",
                    c + 1
                )
            };
            let value = match token.parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                _ => {
                    return Err(GridError::at(
                        path,
                        Some(line_no),
                        format!("{}: `{token}` is not a finite number", cell()),
                    ))
                }
            };
            if nodata == Some(value) {
                return Err(GridError::at(
                    path,
                    Some(line_no),
                    format!(
                        "{} is NODATA ({token}): the grid must give a height at every cell; fill the hole",
                        cell()
                    ),
                ));
            }
            north_first.push(value);
        }
        if got != ncols {
            return Err(GridError::at(
                path,
                Some(line_no),
                format!("row {rows_read} (from the top) has {got} values, expected `ncols` = {ncols}"),
            ));
        }
    }
    if rows_read != nrows {
        return Err(GridError::at(
            path,
            None,
            format!("{rows_read} rows of values, expected `nrows` = {nrows}"),
        ));
    }
    let heights = north_first.chunks_exact(ncols).rev().flatten().copied().collect();
    HeightGrid::new(ncols, nrows, first_centre, spacing, heights)
        .map_err(|e| GridError::at(path, None, e.message))
}

/// Writes `grid` to `path` as an ESRI ASCII grid (whole or not at all, [`atomic_file`]): the
/// header with `xllcenter`, `yllcenter` (so the centres read back exactly) and `cellsize`, or
/// `dx` and `dy` when they differ; then the rows from the north, every value in the shortest form
/// that reads back to the same f64.
pub fn write_ascii_grid(path: &Path, grid: &HeightGrid) -> Result<(), GridError> {
    let (first, _) = grid.centres_extent();
    let [dx, dy] = grid.spacing();
    atomic_file::write_with(path, |out| {
        writeln!(out, "ncols {}", grid.ncols())?;
        writeln!(out, "nrows {}", grid.nrows())?;
        writeln!(out, "xllcenter {}", first[0])?;
        writeln!(out, "yllcenter {}", first[1])?;
        if dx == dy {
            writeln!(out, "cellsize {dx}")?;
        } else {
            writeln!(out, "dx {dx}")?;
            writeln!(out, "dy {dy}")?;
        }
        for row in (0..grid.nrows()).rev() {
            for col in 0..grid.ncols() {
                let separator = if col == 0 { "" } else { " " };
                write!(out, "{separator}{}", grid.height(col, row).unwrap_or(f64::NAN))?;
            }
            writeln!(out)?;
        }
        Ok(())
    })
    .map_err(|e| GridError::at(path, None, format!("cannot be written: {e}")))
}
