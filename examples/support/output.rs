//! What every example writes besides its printed summary: a CSV of its
//! trajectory and an SVG plot of it, under `target/example-output/`.

use daegen_workprecision::{line_chart_svg, Series};
use std::path::PathBuf;

/// Writes `<name>.csv` (a header line, then one line per row) and
/// `<name>.svg` (the series), and says where.
pub fn write(
    name: &str,
    header: &[&str],
    rows: &[Vec<f64>],
    plot: (&str, &str, &str),
    series: &[Series],
) -> std::io::Result<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/target/example-output"
    ));
    std::fs::create_dir_all(&dir)?;
    let mut csv = header.join(",");
    csv.push('\n');
    for row in rows {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
        csv.push_str(&cells.join(","));
        csv.push('\n');
    }
    std::fs::write(dir.join(format!("{name}.csv")), csv)?;
    let (title, x, y) = plot;
    let svg = line_chart_svg(title, x, y, series).map_err(std::io::Error::other)?;
    std::fs::write(dir.join(format!("{name}.svg")), svg)?;
    println!("\nwrote {0}/{name}.csv and {0}/{name}.svg", dir.display());
    Ok(dir)
}
