//! Plots of a solution as SVG files (the `plot` feature, on by default):
//! time series of chosen names and phase portraits, drawn with plotters'
//! SVG backend, which needs no system library.
//!
//! ```
//! use daegen::prelude::*;
//!
//! #[dae_model]
//! fn oscillator() {
//!     let x = state(1.0);
//!     init(der(x), 0.0);
//!     der(der(x)) == -x;
//! }
//!
//! let sol = Oscillator::default().simulate(0.0, 10.0, &Options::new())?;
//! let dir = std::env::temp_dir();
//! daegen::plot::time_series(&sol, &["x", "der(x)"], dir.join("oscillator.svg"))?;
//! daegen::plot::phase_portrait(&sol, "x", "der(x)", dir.join("oscillator-phase.svg"))?;
//! # Ok::<(), daegen::Error>(())
//! ```

use crate::{Error, Solution, Table};
use plotters::prelude::*;
use std::path::Path;

/// The colours of the series, in order (matplotlib's "tab10").
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Points drawn between the ends of a run whose solution can be sampled
/// anywhere (its stored steps are added to them).
const SAMPLES: usize = 1000;

/// One named curve of a line chart.
pub struct Series<'a> {
    /// Legend entry.
    pub name: &'a str,
    /// Points (x, y), drawn in order.
    pub points: Vec<(f64, f64)>,
}

/// Draws `names` against time into the SVG file at `path`, one line per
/// name; from the method's continuous extension where the solution has
/// one, else at the stored times.
pub fn time_series(sol: &Solution, names: &[&str], path: impl AsRef<Path>) -> Result<(), Error> {
    let table = curve_points(sol, names)?;
    let series: Vec<Series> = names
        .iter()
        .map(|name| Series {
            name,
            points: table
                .times()
                .iter()
                .copied()
                .zip(table.column(name).unwrap_or(&[]).iter().copied())
                .collect(),
        })
        .collect();
    let svg = line_chart_svg(&title(sol), "t", &names.join(", "), &series)?;
    write(path.as_ref(), &svg)
}

/// Draws `y` against `x` (a phase portrait, or a trajectory in the plane)
/// into the SVG file at `path`.
pub fn phase_portrait(
    sol: &Solution,
    x: &str,
    y: &str,
    path: impl AsRef<Path>,
) -> Result<(), Error> {
    let table = curve_points(sol, &[x, y])?;
    let (xs, ys) = (table.column(x).unwrap_or(&[]), table.column(y).unwrap_or(&[]));
    let name = format!("{y} against {x}");
    let series =
        [Series { name: &name, points: xs.iter().copied().zip(ys.iter().copied()).collect() }];
    let svg = line_chart_svg(&title(sol), x, y, &series)?;
    write(path.as_ref(), &svg)
}

/// A chart's title: the model and the method.
fn title(sol: &Solution) -> String {
    format!("{} ({})", sol.model_name(), sol.stats().method)
}

/// The values to draw: the stored times, and between them a fine grid
/// where the solution interpolates.
fn curve_points(sol: &Solution, names: &[&str]) -> Result<Table, Error> {
    let stored = sol.table(names)?;
    let (Some(&t0), t1) = (sol.times().first(), sol.final_time()) else {
        return Ok(stored);
    };
    if stored.len() >= SAMPLES || t0 == t1 {
        return Ok(stored);
    }
    let mut times: Vec<f64> = (0..=SAMPLES)
        .map(|k| t0 + (t1 - t0) * k as f64 / SAMPLES as f64)
        .chain(sol.times().iter().copied())
        .collect();
    if t1 >= t0 {
        times.sort_by(f64::total_cmp);
    } else {
        times.sort_by(|a, b| b.total_cmp(a));
    }
    times.dedup();
    match sol.sample(names, &times) {
        Ok(table) => Ok(table),
        // Stored at some times only: draw those.
        Err(Error::Thinned { .. } | Error::NotStored { .. }) => Ok(stored),
        Err(e) => Err(e),
    }
}

fn write(path: &Path, svg: &str) -> Result<(), Error> {
    std::fs::write(path, svg)
        .map_err(|e| Error::Io { message: format!("writing {} failed: {e}", path.display()) })
}

/// A line chart as SVG text (linear axes, the ranges from the data, the
/// legend beside the chart): each series is one polyline in its colour of
/// [`PALETTE`]. Non-finite points are left out; `Err` if no point is finite.
pub fn line_chart_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> Result<String, Error> {
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all: Vec<&(f64, f64)> =
        series.iter().flat_map(|s| s.points.iter().filter(finite)).collect();
    if all.is_empty() {
        return Err(Error::Io { message: format!("plotting {title}: no finite point to draw") });
    }
    let span = |f: fn(&(f64, f64)) -> f64| {
        let lo = all.iter().map(|p| f(p)).fold(f64::INFINITY, f64::min);
        let hi = all.iter().map(|p| f(p)).fold(f64::NEG_INFINITY, f64::max);
        let pad = if hi > lo { 0.05 * (hi - lo) } else { 1.0 };
        (lo - pad, hi + pad)
    };
    let (x0, x1) = span(|p| p.0);
    let (y0, y1) = span(|p| p.1);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (880, 480)).into_drawing_area();
        let draw =
            |e: DrawingAreaErrorKind<_>| Error::Io { message: format!("plotting {title}: {e:?}") };
        root.fill(&WHITE).map_err(draw)?;
        // The legend beside the chart, where it hides no point.
        let (plot, legend) = root.split_horizontally(660);
        let mut chart = ChartBuilder::on(&plot)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(draw)?;
        chart.configure_mesh().x_desc(x_desc).y_desc(y_desc).draw().map_err(draw)?;
        for (k, s) in series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            let style = ShapeStyle::from(&colour).stroke_width(2);
            let points: Vec<(f64, f64)> = s.points.iter().copied().filter(|p| finite(&p)).collect();
            chart.draw_series(LineSeries::new(points, style)).map_err(draw)?;
            // A filled swatch, so the curve is the series' only line.
            let y = 48 + 22 * k as i32;
            legend
                .draw(&Rectangle::new([(4, y - 3), (28, y + 3)], colour.filled()))
                .map_err(draw)?;
            legend
                .draw(&Text::new(s.name.to_string(), (34, y - 7), ("sans-serif", 13)))
                .map_err(draw)?;
        }
        root.present().map_err(draw)?;
    }
    Ok(svg)
}
