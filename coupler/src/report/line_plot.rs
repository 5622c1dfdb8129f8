//! A line plot of the columns of a CSV file against its first column, drawn into a PNG with the
//! report's plotting (plotters, bundled font): `coupler plot`. The prism dam break's sweep
//! (`cases/prism-dam-break/sweep.py`) draws its X force per unit width of every width and the
//! resolved run with it. What was drawn goes beside the PNG as `*.plot.csv` (series, x, y,
//! dashed), checkable without reading pixels.

use super::plot::{err, font, legend_and_present, COLOURS};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// One column of the CSV: its header and its (x, y) points (empty cells left out).
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub dashed: bool,
}

/// The columns of `text` (a header line, then rows of numbers) after the first, against the
/// first; columns named in `dashed` are drawn dashed. A cell that is not a number is an error
/// naming its line and column; an empty cell is a missing point.
pub fn read_lines(text: &str, source: &Path, dashed: &[String]) -> Result<Vec<Line>, String> {
    let mut rows = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> = rows
        .next()
        .ok_or_else(|| format!("{}: empty, a header line is needed", source.display()))?
        .split(',')
        .map(str::trim)
        .collect();
    if header.len() < 2 {
        return Err(format!(
            "{}: the header names {} column; x and at least one series are needed",
            source.display(),
            header.len()
        ));
    }
    for d in dashed {
        if !header[1..].contains(&d.as_str()) {
            return Err(format!(
                "--dashed {d}: {} has no such column (it has {})",
                source.display(),
                header[1..].join(", ")
            ));
        }
    }
    let mut lines: Vec<Line> = header[1..]
        .iter()
        .map(|h| Line {
            name: h.to_string(),
            points: Vec::new(),
            dashed: dashed.iter().any(|d| d == h),
        })
        .collect();
    for (k, row) in rows.enumerate() {
        let number = |c: usize, cell: &str| {
            cell.trim().parse::<f64>().map_err(|_| {
                format!(
                    "{}: line {}, column `{}`: `{cell}` is not a number",
                    source.display(),
                    k + 2,
                    header.get(c).unwrap_or(&"?")
                )
            })
        };
        let cells: Vec<&str> = row.split(',').collect();
        let x = number(0, cells[0])?;
        for (c, cell) in cells.iter().enumerate().skip(1).take(lines.len()) {
            if !cell.trim().is_empty() {
                let y = number(c, cell)?;
                lines[c - 1].points.push((x, y));
            }
        }
    }
    Ok(lines)
}

/// Draws `lines` into `path` (PNG) with `title` and axis labels, and writes what was drawn to
/// `path` with `.plot.csv` for `.png`.
pub fn draw(path: &Path, title: &str, x_label: &str, y_label: &str, lines: &[Line]) -> Result<(), String> {
    font()?;
    let mut data = String::from("series,x,y,dashed\n");
    for l in lines {
        for (x, y) in &l.points {
            let _ = writeln!(data, "\"{}\",{x:e},{y:e},{}", l.name.replace('"', "'"), l.dashed);
        }
    }
    std::fs::write(path.with_extension("plot.csv"), data).map_err(err(path))?;
    let all = || lines.iter().flat_map(|l| l.points.iter().copied());
    let (x0, x1) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.0), b.max(p.0))
    });
    let (y0, y1) = all().fold((0.0f64, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let (x0, x1) = if x0 < x1 { (x0, x1) } else { (0.0, 1.0) };
    let pad = 0.05 * (y1 - y0).max(f64::MIN_POSITIVE);
    let root = BitMapBackend::new(path, (1000, 650)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err(path))?;
    for (i, l) in lines.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let style = colour.stroke_width(2);
        let series = if l.dashed {
            chart.draw_series(DashedLineSeries::new(l.points.clone(), 8, 5, style))
        } else {
            chart.draw_series(LineSeries::new(l.points.clone(), style))
        };
        series
            .map_err(err(path))?
            .label(l.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    legend_and_present(&mut chart, &root, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_column_is_one_series_and_the_png_is_an_image() {
        let dir = std::env::temp_dir().join(format!("line-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let csv = "time,w0.01_fx_per_width,w0.05_fx_per_width,resolved_fx_per_width\n\
                   0,0,0,0\n0.1,1.5,2.5,2.0\n0.2,3,,4\n";
        let lines = read_lines(csv, Path::new("f.csv"), &["resolved_fx_per_width".into()])
            .unwrap_or_else(|e| panic!("{e}"));
        let png = dir.join("force.png");
        draw(&png, "title", "t [s]", "F_x / D [N/m]", &lines).unwrap_or_else(|e| panic!("{e}"));
        let bytes = std::fs::read(&png).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "a PNG file");
        // IHDR: width and height (big endian) at bytes 16..24
        let size = |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
        assert_eq!((size(16), size(20)), (1000, 650));
        let drawn = std::fs::read_to_string(png.with_extension("plot.csv")).unwrap_or_else(|e| panic!("{e}"));
        let rows: Vec<Vec<&str>> = drawn.lines().skip(1).map(|l| l.split(',').collect()).collect();
        let names: std::collections::BTreeSet<&str> = rows.iter().map(|r| r[0]).collect();
        assert_eq!(names.len(), 3, "one series per column: {names:?}");
        assert_eq!(
            rows.iter().filter(|r| r[0].contains("w0.05")).count(),
            2,
            "the empty cell is no point"
        );
        assert!(
            rows.iter().all(|r| (r[3] == "true") == r[0].contains("resolved")),
            "only the resolved run is dashed"
        );
        assert!(read_lines("time,a\n0,x\n", Path::new("f.csv"), &[])
            .is_err_and(|e| e.contains("line 2, column `a`")));
        assert!(read_lines(csv, Path::new("f.csv"), &["nope".into()])
            .is_err_and(|e| e.contains("no such column")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
