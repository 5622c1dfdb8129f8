//! GeoTIFF height grids (`.tif`, `.tiff`), as DEMs are often shared: one band of heights, placed
//! by the GeoTIFF tags `ModelPixelScaleTag` (cell size, sx and sy) and `ModelTiepointTag` (the
//! raster point (i, j) at the model point (x, y)); rows run from the north (row 0 at the top, y
//! falling by sy per row). The `GTRasterTypeGeoKey` (1025) of the `GeoKeyDirectoryTag` says
//! whether a tiepoint names a pixel's corner (`PixelIsArea`, 1, the default) or its centre
//! (`PixelIsPoint`, 2); the heights are taken at the cell centres either way:
//!
//! `x(c) = x_t + (c − i + ½) sx`, `y(r) = y_t − (r − j + ½) sy` for `PixelIsArea`, without the ½
//! for `PixelIsPoint`.
//!
//! The heights are read as stored (any integer or floating sample type), in the model's vertical
//! unit. `GDAL_NODATA` (42113) marks missing cells, refused as in an ASCII grid: a terrain must
//! have a height everywhere. A grid placed by `ModelTransformationTag` (rotated or sheared) and an
//! image of several bands are refused.

use super::error::GridError;
use super::height_grid::HeightGrid;
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use tiff::decoder::{Decoder, DecodingResult};
use tiff::encoder::{colortype, TiffEncoder};
use tiff::tags::Tag;
use tiff::ColorType;

/// `GTRasterTypeGeoKey`: whether a tiepoint is a pixel's corner or its centre.
const RASTER_TYPE_KEY: u16 = 1025;
/// `RasterPixelIsPoint`: tiepoints name pixel centres.
const PIXEL_IS_POINT: u16 = 2;

/// Reads the GeoTIFF `path` as a height grid (module doc). Every error names the file.
pub fn read_geotiff(path: &Path) -> Result<HeightGrid, GridError> {
    let fail = |message: String| GridError::at(path, None, message);
    let file = File::open(path).map_err(|e| fail(format!("cannot be opened: {e}")))?;
    let mut tiff =
        Decoder::new(BufReader::new(file)).map_err(|e| fail(format!("is not a TIFF file: {e}")))?;
    let (ncols, nrows) = tiff
        .dimensions()
        .map_err(|e| fail(format!("has no image size: {e}")))?;
    match tiff.colortype() {
        Ok(ColorType::Gray(_)) => {}
        Ok(other) => {
            return Err(fail(format!(
                "holds {other:?} pixels: a height grid needs one band of heights (gray samples)"
            )))
        }
        Err(e) => return Err(fail(format!("has no readable sample type: {e}"))),
    }
    let tag =
        |tiff: &mut Decoder<BufReader<File>>, t: Tag, name: &str| -> Result<Option<Vec<f64>>, GridError> {
            match tiff.find_tag(t) {
                Ok(Some(v)) => v
                    .into_f64_vec()
                    .map(Some)
                    .map_err(|e| fail(format!("has an unreadable {name}: {e}"))),
                Ok(None) => Ok(None),
                Err(e) => Err(fail(format!("has an unreadable {name}: {e}"))),
            }
        };
    if tag(&mut tiff, Tag::ModelTransformationTag, "ModelTransformationTag")?.is_some() {
        return Err(fail(
            "is placed by a ModelTransformationTag (a rotated or sheared grid): only grids placed by \
             ModelPixelScaleTag and ModelTiepointTag, aligned with x and y, are read; warp it to a \
             north-up grid first (e.g. gdalwarp)"
                .into(),
        ));
    }
    let missing = |name: &str| {
        fail(format!(
            "has no {name}: a height grid needs ModelPixelScaleTag and ModelTiepointTag to place its \
             cells (it is not a GeoTIFF?)"
        ))
    };
    let scale = tag(&mut tiff, Tag::ModelPixelScaleTag, "ModelPixelScaleTag")?
        .ok_or_else(|| missing("ModelPixelScaleTag"))?;
    let tie = tag(&mut tiff, Tag::ModelTiepointTag, "ModelTiepointTag")?
        .ok_or_else(|| missing("ModelTiepointTag"))?;
    if scale.len() < 2 || tie.len() < 6 {
        return Err(fail(format!(
            "has a ModelPixelScaleTag of {} values and a ModelTiepointTag of {}: at least 2 and 6 are needed",
            scale.len(),
            tie.len()
        )));
    }
    if tie.len() > 6 {
        return Err(fail(format!(
            "has {} tiepoints: only a grid placed by one tiepoint and a pixel scale is read",
            tie.len() / 6
        )));
    }
    let half = if raster_type(&mut tiff) == Some(PIXEL_IS_POINT) {
        0.0
    } else {
        0.5
    };
    let nodata = match tiff.find_tag(Tag::GdalNodata) {
        Ok(Some(v)) => {
            let text = v
                .into_string()
                .map_err(|e| fail(format!("has an unreadable GDAL_NODATA tag: {e}")))?;
            let text = text.trim_matches(char::from(0)).trim();
            Some(
                text.parse::<f64>()
                    .map_err(|_| fail(format!("has a GDAL_NODATA tag `{text}` that is not a number")))?,
            )
        }
        Ok(None) => None,
        Err(e) => return Err(fail(format!("has an unreadable GDAL_NODATA tag: {e}"))),
    };
    let samples = tiff
        .read_image()
        .map_err(|e| fail(format!("has image data that cannot be read: {e}")))?;
    let values = as_f64(samples);
    let (ncols, nrows) = (ncols as usize, nrows as usize);
    if values.len() != ncols * nrows {
        return Err(fail(format!(
            "holds {} samples for {ncols} × {nrows} pixels: a height grid needs one band",
            values.len()
        )));
    }
    let [sx, sy] = [scale[0], scale[1]];
    let (i, j, x_t, y_t) = (tie[0], tie[1], tie[3], tie[4]);
    let x_of = |c: usize| x_t + (c as f64 - i + half) * sx;
    let y_of = |r: usize| y_t - (r as f64 - j + half) * sy;
    // row-major from the south-west cell: the file's last row first
    let mut heights = Vec::with_capacity(values.len());
    for r in (0..nrows).rev() {
        for c in 0..ncols {
            let z = values[r * ncols + c];
            if !z.is_finite() || nodata.is_some_and(|n| z == n) {
                return Err(fail(format!(
                    "has no height at row {}, column {} (counted from 1 at the top-left; x = {}, y = {}): \
                     {}; a terrain needs a height in every cell (fill the gap, or crop the grid)",
                    r + 1,
                    c + 1,
                    x_of(c),
                    y_of(r),
                    if z.is_finite() {
                        format!("the NODATA value {z}")
                    } else {
                        format!("{z}")
                    }
                )));
            }
            heights.push(z);
        }
    }
    HeightGrid::new(ncols, nrows, [x_of(0), y_of(nrows - 1)], [sx, sy], heights)
        .map_err(|e| fail(e.to_string()))
}

/// Writes `grid` to `path` as a GeoTIFF of 64-bit float heights (north up, `PixelIsArea`), which
/// [`read_geotiff`] reads back to the same grid.
pub fn write_geotiff(path: &Path, grid: &HeightGrid) -> Result<(), GridError> {
    let fail = |message: String| GridError::at(path, None, format!("cannot be written: {message}"));
    let (ncols, nrows) = (grid.ncols(), grid.nrows());
    let [dx, dy] = grid.spacing();
    let [x0, y0] = grid.centre(0, nrows - 1);
    // the file's first row is the northern one
    let mut z = Vec::with_capacity(ncols * nrows);
    for r in (0..nrows).rev() {
        z.extend((0..ncols).map(|c| grid.height(c, r).unwrap_or(f64::NAN)));
    }
    let size = |n: usize| u32::try_from(n).map_err(|_| fail(format!("{n} cells are too many for a TIFF")));
    let (width, height) = (size(ncols)?, size(nrows)?);
    let mut bytes = std::io::Cursor::new(Vec::new());
    let encoded = (|| -> tiff::TiffResult<()> {
        let mut tiff = TiffEncoder::new(&mut bytes)?;
        let mut image = tiff.new_image::<colortype::Gray64Float>(width, height)?;
        let e = image.encoder();
        e.write_tag(Tag::ModelPixelScaleTag, &[dx, dy, 0.0][..])?;
        // the top-left corner of the north-west cell
        let corner = [x0 - 0.5 * dx, y0 + 0.5 * dy];
        e.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, corner[0], corner[1], 0.0][..],
        )?;
        image.write_data(&z)
    })();
    encoded.map_err(|e| fail(e.to_string()))?;
    crate::atomic_file::write_with(path, |out| out.write_all(bytes.get_ref()))
        .map_err(|e| fail(e.to_string()))
}

/// The `GTRasterTypeGeoKey` of the GeoKey directory (header of 4 values, then 4 per key: id,
/// location, count, value), when given.
fn raster_type(tiff: &mut Decoder<BufReader<File>>) -> Option<u16> {
    let keys = tiff
        .find_tag(Tag::GeoKeyDirectoryTag)
        .ok()??
        .into_u16_vec()
        .ok()?;
    keys.get(4..)?
        .chunks_exact(4)
        .find(|k| k[0] == RASTER_TYPE_KEY && k[1] == 0)
        .map(|k| k[3])
}

/// The samples as f64, whatever their stored type.
fn as_f64(samples: DecodingResult) -> Vec<f64> {
    match samples {
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U64(v) => v.into_iter().map(|x| x as f64).collect(),
        DecodingResult::F16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
        DecodingResult::I8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I64(v) => v.into_iter().map(|x| x as f64).collect(),
    }
}
