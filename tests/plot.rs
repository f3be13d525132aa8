//! Plots as SVG: the files parse as XML, and hold one polyline per series
//! in the series' colour, through the points of the solution.
#![cfg(feature = "plot")]

use daegen::plot::{line_chart_svg, phase_portrait, time_series, Series, PALETTE};
use daegen::prelude::*;

/// x'' = −x from (1, 0).
#[dae_model]
fn oscillator() {
    let x = state(1.0);
    init(der(x), 0.0);
    der(der(x)) == -x;
    /// Twice the energy.
    let energy = output(x * x + der(x) * der(x));
}

/// The stroke colour of series `k` as the SVG writes it.
fn stroke(k: usize) -> String {
    let c = PALETTE[k];
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// The polylines of a parsed SVG, by stroke colour, as lists of points.
fn polylines(svg: &str, colour: &str) -> Vec<Vec<(f64, f64)>> {
    let doc = roxmltree::Document::parse(svg).expect("the SVG parses as XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(colour))
        .map(|n| {
            n.attribute("points")
                .unwrap_or("")
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("daegen-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn a_time_series_holds_one_line_per_name() {
    let sol =
        Oscillator::default().simulate(0.0, 10.0, &Options::new().method(Method::Taylor)).unwrap();
    let path = temp("series.svg");
    time_series(&sol, &["x", "der(x)", "energy"], &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    for k in 0..3 {
        let lines = polylines(&svg, &stroke(k));
        assert_eq!(lines.len(), 1, "series {k}");
        // Drawn from the Taylor polynomials at a thousand points, not only
        // at the method's few long steps.
        assert!(lines[0].len() > 1000, "series {k}: {} points", lines[0].len());
    }
    assert!(polylines(&svg, &stroke(3)).is_empty());
    for name in ["x", "der(x)", "energy", "Oscillator"] {
        assert!(svg.contains(name), "{name}");
    }
}

/// The phase portrait of the oscillator is the unit circle: its points lie
/// on an ellipse in screen coordinates (the axes scale x and y
/// differently), centred in the plot.
#[test]
fn a_phase_portrait_draws_the_orbit() {
    let opts = Options::new().method(Method::Dop853).tolerance(1e-10);
    let sol = Oscillator::default().simulate(0.0, 6.3, &opts).unwrap();
    let path = temp("phase.svg");
    phase_portrait(&sol, "x", "der(x)", &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    let lines = polylines(&svg, &stroke(0));
    assert_eq!(lines.len(), 1);
    let points = &lines[0];
    let (xmin, xmax) =
        points.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (ymin, ymax) =
        points.iter().fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let (cx, cy, rx, ry) =
        ((xmin + xmax) / 2.0, (ymin + ymax) / 2.0, (xmax - xmin) / 2.0, (ymax - ymin) / 2.0);
    for &(x, y) in points {
        let r = ((x - cx) / rx).powi(2) + ((y - cy) / ry).powi(2);
        // Within a pixel of the ellipse.
        assert!((r.sqrt() - 1.0).abs() < 2.0 / rx.min(ry), "{r}");
    }
}

#[test]
fn plots_of_thinned_runs_draw_the_stored_times_and_bad_names_are_errors() {
    let times: Vec<f64> = (0..=20).map(|k| 0.5 * k as f64).collect();
    let sol =
        Oscillator::default().simulate(0.0, 10.0, &Options::new().output_times(times)).unwrap();
    let path = temp("stored.svg");
    time_series(&sol, &["x"], &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_eq!(polylines(&svg, &stroke(0))[0].len(), 21);
    assert!(matches!(time_series(&sol, &["y"], temp("bad.svg")), Err(Error::UnknownName { .. })));
    match time_series(&sol, &["x"], "/nonexistent-dir/x.svg") {
        Err(Error::Io { message }) => {
            assert!(message.contains("/nonexistent-dir/x.svg"), "{message}")
        }
        other => panic!("expected Io, got {other:?}"),
    }
}

#[test]
fn a_line_chart_leaves_out_non_finite_points_and_refuses_an_empty_one() {
    let line = vec![(-1.0, 0.0), (1.0, 0.0), (f64::NAN, 1.0)];
    let svg = line_chart_svg("axis", "x", "y", &[Series { name: "axis", points: line }]).unwrap();
    assert_eq!(polylines(&svg, &stroke(0))[0].len(), 2);
    assert!(!svg.contains("NaN"));
    let empty = [Series { name: "e", points: vec![] }];
    assert!(matches!(line_chart_svg("none", "x", "y", &empty), Err(Error::Io { .. })));
}
