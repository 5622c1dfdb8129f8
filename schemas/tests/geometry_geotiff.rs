//! Tests of `schemas::geometry::geotiff`.

use schemas::geometry::geotiff::*;
use std::fs::File;
use std::path::Path;
use tiff::encoder::{colortype, TiffEncoder};
use tiff::tags::Tag;

/// Writes a 32-bit float GeoTIFF of `nrows` rows of `ncols` heights (row 0 the northern one),
/// its top-left corner (PixelIsArea) at `corner`, cells `[sx, sy]`.
fn write(
    path: &Path,
    ncols: u32,
    nrows: u32,
    corner: [f64; 2],
    cell: [f64; 2],
    z: &[f32],
    nodata: Option<&str>,
) {
    let file = File::create(path).unwrap_or_else(|e| panic!("{e}"));
    let mut tiff = TiffEncoder::new(file).unwrap_or_else(|e| panic!("{e}"));
    let mut image = tiff
        .new_image::<colortype::Gray32Float>(ncols, nrows)
        .unwrap_or_else(|e| panic!("{e}"));
    let e = image.encoder();
    e.write_tag(Tag::ModelPixelScaleTag, &[cell[0], cell[1], 0.0][..])
        .unwrap_or_else(|e| panic!("{e}"));
    e.write_tag(
        Tag::ModelTiepointTag,
        &[0.0, 0.0, 0.0, corner[0], corner[1], 0.0][..],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    if let Some(n) = nodata {
        e.write_tag(Tag::GdalNodata, n).unwrap_or_else(|e| panic!("{e}"));
    }
    image.write_data(z).unwrap_or_else(|e| panic!("{e}"));
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("geotiff-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir.join(name)
}

/// A 3 × 2 grid whose heights are a plane z = 0.1 x + 0.01 y, its top-left corner at (10, 20),
/// cells 2 × 1 m: the cell centres are at x = 11, 13, 15 and y = 19.5 (north), 18.5 (south),
/// and the grid's heights there are the plane's (to f32 rounding), as an ASCII grid with the
/// same cells gives them.
#[test]
fn a_float_geotiff_places_its_heights_at_the_cell_centres() {
    let plane = |x: f64, y: f64| 0.1 * x + 0.01 * y;
    let (xs, ys) = ([11.0, 13.0, 15.0], [19.5, 18.5]);
    let z: Vec<f32> = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| plane(x, y) as f32))
        .collect();
    let path = scratch("plane.tif");
    write(&path, 3, 2, [10.0, 20.0], [2.0, 1.0], &z, None);
    let grid = read_geotiff(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((grid.ncols(), grid.nrows()), (3, 2));
    assert_eq!(grid.spacing(), [2.0, 1.0]);
    assert_eq!(grid.centre(0, 0), [11.0, 18.5], "the south-west cell's centre");
    for &x in &[11.0, 12.0, 14.5, 15.0] {
        for &y in &[18.5, 19.0, 19.5] {
            let h = grid
                .height_at(x, y)
                .unwrap_or_else(|| panic!("no height at {x}, {y}"));
            assert!(
                (h - plane(x, y)).abs() < 1e-6,
                "{x}, {y}: {h} against {}",
                plane(x, y)
            );
        }
    }
}

#[test]
fn missing_cells_and_missing_placement_are_refused() {
    let path = scratch("hole.tif");
    write(
        &path,
        2,
        2,
        [0.0, 2.0],
        [1.0, 1.0],
        &[1.0, -9999.0, 1.0, 1.0],
        Some("-9999"),
    );
    let e = read_geotiff(&path).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("hole.tif") && e.contains("row 1, column 2") && e.contains("NODATA"),
        "{e}"
    );

    let path = scratch("plain.tif");
    let file = File::create(&path).unwrap_or_else(|e| panic!("{e}"));
    TiffEncoder::new(file)
        .unwrap_or_else(|e| panic!("{e}"))
        .write_image::<colortype::Gray32Float>(2, 2, &[1.0; 4])
        .unwrap_or_else(|e| panic!("{e}"));
    let e = read_geotiff(&path).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("plain.tif") && e.contains("ModelPixelScaleTag"), "{e}");

    let path = scratch("text.tif");
    std::fs::write(&path, "ncols 2\n").unwrap_or_else(|e| panic!("{e}"));
    let e = read_geotiff(&path).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("text.tif") && e.contains("not a TIFF"), "{e}");
}
