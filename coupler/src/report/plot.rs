//! The report's figures, drawn with plotters into PNG bitmaps with a bundled font (DejaVu Sans
//! Mono, its licence beside it in `coupler/assets/`), so no system font library is needed. Each
//! figure's data are written beside it as CSV (`*.plot.csv`): what was drawn, checkable without
//! reading pixels.

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSansMono.ttf");

pub(crate) fn font() -> Result<(), String> {
    static REGISTER: Once = Once::new();
    let mut result = Ok(());
    REGISTER.call_once(|| {
        result = register_font("sans-serif", FontStyle::Normal, FONT)
            .map_err(|_| "the bundled font does not load".to_string());
    });
    result
}

/// One line of the work–precision plot: (wall time, error, label) per rung.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64, String)>,
}

pub(crate) const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

pub(crate) fn err<E: std::fmt::Display>(path: &Path) -> impl Fn(E) -> String + '_ {
    move |e| format!("cannot draw {}: {e}", path.display())
}

/// Log–log error against wall time, one line per series, points labelled; the drawn points go
/// to `path` with `.plot.csv` for `.png`. Points without a positive error are left out.
pub fn work_precision(path: &Path, title: &str, error_label: &str, series: &[Series]) -> Result<(), String> {
    font()?;
    let drawn: Vec<Series> = series
        .iter()
        .map(|s| Series {
            name: s.name.clone(),
            points: s
                .points
                .iter()
                .filter(|(w, e, _)| *w > 0.0 && e.is_finite() && *e > 0.0)
                .cloned()
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    let mut data = String::from("series,wall_s,error,label\n");
    for s in &drawn {
        for (w, e, l) in &s.points {
            let _ = writeln!(data, "\"{}\",{w:e},{e:e},\"{l}\"", s.name.replace('"', "'"));
        }
    }
    std::fs::write(path.with_extension("plot.csv"), data).map_err(err(path))?;
    let all: Vec<(f64, f64)> = drawn
        .iter()
        .flat_map(|s| s.points.iter().map(|p| (p.0, p.1)))
        .collect();
    let range = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
        if lo.is_finite() {
            (lo / 2.0, hi * 2.0)
        } else {
            (0.1, 10.0)
        }
    };
    let (w0, w1) = range(&mut all.iter().map(|p| p.0));
    let (e0, e1) = range(&mut all.iter().map(|p| p.1));
    let root = BitMapBackend::new(path, (1000, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d((w0..w1).log_scale(), (e0..e1).log_scale())
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .x_desc("wall time [s]")
        .y_desc(error_label)
        .x_labels(8)
        .y_labels(12)
        .x_label_formatter(&|v| format!("{v:.2e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err(path))?;
    for (i, s) in drawn.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let line: Vec<(f64, f64)> = s.points.iter().map(|p| (p.0, p.1)).collect();
        chart
            .draw_series(LineSeries::new(line.clone(), colour.stroke_width(2)))
            .map_err(err(path))?
            .label(s.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        chart
            .draw_series(line.iter().map(|&p| Circle::new(p, 4, colour.filled())))
            .map_err(err(path))?;
        chart
            .draw_series(s.points.iter().map(|(w, e, l)| {
                EmptyElement::at((*w, *e))
                    + Text::new(l.clone(), (7, -14), ("sans-serif", 12).into_font().color(&colour))
            }))
            .map_err(err(path))?;
    }
    legend_and_present(&mut chart, &root, path)
}

/// Draws the series' legend in the upper right corner and writes the image to `path`.
pub(crate) fn legend_and_present<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    root: &DrawingArea<DB, plotters::coord::Shift>,
    path: &Path,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err(path))?;
    root.present().map_err(err(path))
}

/// The end state of a stability run, as drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cell {
    Stable,
    /// Reached its end, but a solver warned that a check failed (e.g. accuracy of its steps).
    Warned,
    Stopped,
    Refused,
    FailedSilently,
    NotRun,
}

impl Cell {
    fn colour(self) -> RGBColor {
        match self {
            Cell::Stable => RGBColor(120, 200, 120),
            Cell::Warned => RGBColor(240, 225, 90),
            Cell::Stopped => RGBColor(245, 170, 60),
            Cell::Refused => RGBColor(180, 180, 180),
            Cell::FailedSilently => RGBColor(220, 40, 40),
            Cell::NotRun => RGBColor(245, 245, 245),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Cell::Stable => "stable",
            Cell::Warned => "warned",
            Cell::Stopped => "stopped",
            Cell::Refused => "refused",
            Cell::FailedSilently => "FAILED SILENTLY",
            Cell::NotRun => "not run",
        }
    }
}

/// One panel of a stability map: cells over rows × columns.
#[derive(Debug, Clone)]
pub struct Panel {
    pub title: String,
    pub rows_name: String,
    pub rows: Vec<String>,
    pub columns_name: String,
    pub columns: Vec<String>,
    /// `cells[row][column]`.
    pub cells: Vec<Vec<Cell>>,
}

/// A map of end states, one panel side by side per panel; its cells go to `.plot.csv`.
pub fn stability_map(path: &Path, title: &str, panels: &[Panel]) -> Result<(), String> {
    font()?;
    let mut data = String::from("panel,row,column,state\n");
    for p in panels {
        for (r, row) in p.cells.iter().enumerate() {
            for (c, cell) in row.iter().enumerate() {
                let _ = writeln!(
                    data,
                    "\"{}\",\"{}\",\"{}\",{}",
                    p.title,
                    p.rows[r],
                    p.columns[c],
                    cell.name()
                );
            }
        }
    }
    std::fs::write(path.with_extension("plot.csv"), data).map_err(err(path))?;
    let width = (220 + 420 * panels.len().max(1) as u32).max(1000);
    let root = BitMapBackend::new(path, (width, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let root = root.titled(title, ("sans-serif", 20)).map_err(err(path))?;
    let (body, legend) = root.split_vertically(410);
    let areas = body.split_evenly((1, panels.len().max(1)));
    for (p, area) in panels.iter().zip(&areas) {
        let (nr, nc) = (p.rows.len().max(1), p.columns.len().max(1));
        let widest = p.rows.iter().map(|r| r.chars().count()).max().unwrap_or(0) as u32;
        let mut chart = ChartBuilder::on(area)
            .caption(&p.title, ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size((8 * widest + 40).max(70))
            .build_cartesian_2d(0.0..nc as f64, 0.0..nr as f64)
            .map_err(err(path))?;
        let (rows, columns) = (p.rows.clone(), p.columns.clone());
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(&p.columns_name)
            .y_desc(&p.rows_name)
            .x_labels(nc * 2 + 1)
            .y_labels(nr * 2 + 1)
            .x_label_formatter(&move |v| label_at(&columns, *v))
            .y_label_formatter(&move |v| label_at(&rows, *v))
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err(path))?;
        for (r, row) in p.cells.iter().enumerate() {
            for (c, cell) in row.iter().enumerate() {
                let (x, y) = (c as f64, r as f64);
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(x + 0.03, y + 0.03), (x + 0.97, y + 0.97)],
                        cell.colour().filled(),
                    )))
                    .map_err(err(path))?;
            }
        }
    }
    let states = [
        Cell::Stable,
        Cell::Warned,
        Cell::Stopped,
        Cell::Refused,
        Cell::FailedSilently,
        Cell::NotRun,
    ];
    for (i, s) in states.iter().enumerate() {
        let x = 20 + 160 * i as i32;
        legend
            .draw(&Rectangle::new([(x, 20), (x + 18, 38)], s.colour().filled()))
            .map_err(err(path))?;
        legend
            .draw(&Text::new(s.name(), (x + 24, 22), ("sans-serif", 14)))
            .map_err(err(path))?;
    }
    root.present().map_err(err(path))?;
    Ok(())
}

/// The label of the cell whose centre is at `v` (labels are drawn at cell centres only).
fn label_at(labels: &[String], v: f64) -> String {
    let i = v.floor();
    if (v - i - 0.5).abs() < 1e-6 && i >= 0.0 {
        labels.get(i as usize).cloned().unwrap_or_default()
    } else {
        String::new()
    }
}
