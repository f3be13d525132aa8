//! The work-precision diagram of one problem as SVG: error on the x axis,
//! time on the y axis, both logarithmic, one line per method and peer
//! (ours solid, peers dashed), drawn with plotters.

use crate::summary::curves;
use crate::Record;
use plotters::prelude::*;

use daegen::plot::PALETTE as COLOURS;

/// The SVG text of the diagram; `Err` if there is nothing finite to draw
/// or plotters fails.
pub fn work_precision_svg(title: &str, records: &[Record]) -> Result<String, String> {
    let finite: Vec<&Record> = records
        .iter()
        .filter(|r| r.error > 0.0 && r.error.is_finite() && r.seconds > 0.0)
        .collect();
    if finite.is_empty() {
        return Err(format!("{title}: no run with a finite, positive error"));
    }
    let decade = |v: f64, up: bool| {
        let e = v.log10();
        10f64.powf(if up { e.ceil() } else { e.floor() })
    };
    let fold = |f: fn(&Record) -> f64| {
        let lo = finite.iter().map(|r| f(r)).fold(f64::INFINITY, f64::min);
        let hi = finite.iter().map(|r| f(r)).fold(0.0, f64::max);
        (decade(lo, false), decade(hi, true).max(decade(lo, false) * 10.0))
    };
    let (e0, e1) = fold(|r| r.error);
    let (t0, t1) = fold(|r| r.seconds * 1e3);
    // The frame of daegen::plot's charts (legend beside the chart), on
    // logarithmic axes, which daegen::plot does not draw.
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (880, 480)).into_drawing_area();
        let draw = |e: DrawingAreaErrorKind<_>| format!("{title}: {e:?}");
        root.fill(&WHITE).map_err(draw)?;
        // The legend beside the chart, where it hides no point.
        let (plot, legend) = root.split_horizontally(660);
        let mut chart = ChartBuilder::on(&plot)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((e0..e1).log_scale(), (t0..t1).log_scale())
            .map_err(draw)?;
        chart
            .configure_mesh()
            .x_desc("error at the end (mixed)")
            .y_desc("solve time (ms)")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(draw)?;
        let mut row = 0;
        for (k, (method, curve)) in curves(records).into_iter().enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            let mut points: Vec<(f64, f64)> = curve
                .iter()
                .filter(|r| r.error > 0.0 && r.error.is_finite() && r.seconds > 0.0)
                .map(|r| (r.error, r.seconds * 1e3))
                .collect();
            if points.is_empty() {
                continue;
            }
            points.sort_by(|a, b| b.0.total_cmp(&a.0));
            let ours = method.starts_with("daegen ");
            let width = if ours { 2 } else { 1 };
            let style = ShapeStyle::from(&colour).stroke_width(width);
            chart.draw_series(LineSeries::new(points.clone(), style)).map_err(draw)?;
            chart
                .draw_series(points.iter().map(|&p| {
                    if ours {
                        Circle::new(p, 3, colour.filled()).into_dyn()
                    } else {
                        TriangleMarker::new(p, 4, colour.filled()).into_dyn()
                    }
                }))
                .map_err(draw)?;
            let y = 48 + 22 * row;
            legend.draw(&PathElement::new(vec![(4, y), (28, y)], style)).map_err(draw)?;
            legend.draw(&Text::new(method, (34, y - 7), ("sans-serif", 13))).map_err(draw)?;
            row += 1;
        }
        root.present().map_err(draw)?;
    }
    Ok(svg)
}
