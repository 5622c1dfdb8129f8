//! Tests of `schemas::geometry::ascii_grid`.

use schemas::geometry::ascii_grid::*;
use schemas::geometry::height_grid::HeightGrid;
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("schemas-ascii-grid-{}-{name}", std::process::id()))
}

fn read_text(name: &str, text: &str) -> Result<HeightGrid, String> {
    let path = scratch(name);
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    let grid = read_height_grid(&path).map_err(|e| e.to_string());
    let _ = std::fs::remove_file(&path);
    grid
}

fn error(name: &str, text: &str) -> String {
    match read_text(name, text) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => {
            assert!(e.contains(name), "{e}");
            e
        }
    }
}

const GRID: &str = "NCOLS 3\nnrows 2\nxllcorner 100\nYLLCORNER 200\ncellsize 10\nNODATA_value -9999\n\
                    1 2 3\n4 5 6.5\n";

#[test]
fn the_first_row_is_the_northernmost() {
    let g = read_text("ok.asc", GRID).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((g.ncols(), g.nrows()), (3, 2));
    assert_eq!(g.centre(0, 0), [105.0, 205.0]);
    assert_eq!(g.extent(), ([100.0, 200.0], [130.0, 220.0]));
    // the north row (y = 215) is 1 2 3, the south row (y = 205) is 4 5 6.5
    assert_eq!(g.height_at(105.0, 215.0), Some(1.0));
    assert_eq!(g.height_at(125.0, 205.0), Some(6.5));
    assert_eq!(g.height_at(110.0, 210.0), Some((1.0 + 2.0 + 4.0 + 5.0) / 4.0));
    let centred = "ncols 3\nnrows 2\nxllcenter 105\nyllcenter 205\ndx 10\ndy 10\n1 2 3\n4 5 6.5\n";
    assert_eq!(read_text("centred.asc", centred), Ok(g));
}

#[test]
fn write_then_read_is_exact() {
    let g = HeightGrid::from_fn(7, 5, [0.1, -0.3], [0.3, 0.7], |x, y| (x * 3.0).sin() + y / 3.0)
        .unwrap_or_else(|e| panic!("{e}"));
    let path = scratch("round-trip.asc");
    write_ascii_grid(&path, &g).unwrap_or_else(|e| panic!("{e}"));
    let back = read_height_grid(&path);
    let _ = std::fs::remove_file(&path);
    assert_eq!(back, Ok(g));
}

#[test]
fn a_nodata_cell_is_refused_naming_row_and_column() {
    let e = error("hole.asc", &GRID.replace("5 6.5", "-9999 6.5"));
    assert!(
        e.contains("line 8") && e.contains("row 2, column 2") && e.contains("NODATA"),
        "{e}"
    );
    assert!(e.contains("x = 115, y = 205"), "{e}");
}

#[test]
fn a_short_row_is_refused() {
    let e = error("short.asc", &GRID.replace("1 2 3", "1 2"));
    assert!(
        e.contains("line 7") && e.contains("row 1 (from the top) has 2 values, expected `ncols` = 3"),
        "{e}"
    );
    let e = error("rows.asc", &GRID.replace("4 5 6.5\n", ""));
    assert!(e.contains("1 rows of values, expected `nrows` = 2"), "{e}");
    let e = error("extra.asc", &format!("{GRID}7 8 9\n"));
    assert!(e.contains("line 9") && e.contains("more rows"), "{e}");
}

#[test]
fn bad_values_and_headers_are_refused() {
    let e = error("word.asc", &GRID.replace("6.5", "six"));
    assert!(
        e.contains("row 2, column 3") && e.contains("`six` is not a finite number"),
        "{e}"
    );
    let e = error("nan.asc", &GRID.replace("1 2 3", "nan 2 3"));
    assert!(e.contains("row 1, column 1") && e.contains("`nan`"), "{e}");
    let e = error("no-rows.asc", &GRID.replace("nrows 2\n", ""));
    assert!(e.contains("no `nrows`"), "{e}");
    let e = error("no-x.asc", &GRID.replace("xllcorner 100\n", ""));
    assert!(e.contains("no `xllcorner` or `xllcenter`"), "{e}");
    let e = error("zero.asc", &GRID.replace("cellsize 10", "cellsize 0"));
    assert!(e.contains("must be > 0"), "{e}");
    let e = error("negative.asc", &GRID.replace("cellsize 10", "cellsize -2"));
    assert!(e.contains("must be > 0"), "{e}");
    let e = error("unknown.asc", &GRID.replace("NODATA_value", "nodata"));
    assert!(
        e.contains("unknown header key `nodata`") && e.contains("NODATA_value (optional)"),
        "{e}"
    );
    let e = error("twice.asc", &GRID.replace("nrows 2\n", "nrows 2\nNROWS 2\n"));
    assert!(e.contains("line 3") && e.contains("given twice"), "{e}");
    let e = error("count.asc", &GRID.replace("NCOLS 3", "NCOLS 3.5"));
    assert!(e.contains("whole number"), "{e}");
}
