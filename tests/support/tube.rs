// The comparison MAP-LIB's regression tests make of a result with a
// reference: csv-compare 2.1.1's tube (modelica-tools/csv-compare, its
// files TubeSize.cs, Algorithms/Rectangle.cs and Tube.cs; Walther &
// Ruetz's CurveCompare). Around the reference curve, linear between its points,
// a tube of half-width δx = r·max(t_end − t_start, |t_start|) in time and
// half-height δy = r·max(max − min, |min|, 0.001) of the signal, r =
// 0.002 for the MSL. Its upper edge at t is the reference's largest value
// over [t − δx, t + δx] plus δy, its lower edge the smallest minus δy
// (what the rectangle algorithm's corners and cuts make), so a jump the
// result makes a little earlier or later than the reference passes. A
// value below the lower edge or above the upper is an error; a signal
// passes with none.
//
// csv-compare checks the result at its own output times against the
// full reference; the references here (tests/msl/*.csv) keep a subset of
// MAP-LIB's rows, with where they come from in `#` lines, and the result
// is checked at those rows' times, where the reduced curve is the
// reference itself. At an event the two rows of one time are the values
// before and after it.

/// A reference result: its signals' names, its rows.
pub struct Reference {
    /// The compared signals' names, as MSL names them.
    pub signals: Vec<String>,
    /// The rows' times (a time twice at an event).
    pub times: Vec<f64>,
    /// `values[k][row]`: signal `k` at each row.
    pub values: Vec<Vec<f64>>,
}

/// MSL's reference of the example `name` (tests/msl/`name`.csv).
#[allow(dead_code)]
pub fn reference(name: &str) -> Reference {
    reference_in(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/msl"), name)
}

/// The reference of the example `name` in the folder `dir`.
pub fn reference_in(dir: &std::path::Path, name: &str) -> Reference {
    let path = dir.join(format!("{name}.csv"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    let header = lines.next().expect("a header");
    let names: Vec<String> = header.split(',').map(|h| h.trim_matches('"').to_string()).collect();
    let mut times = Vec::new();
    let mut values = vec![Vec::new(); names.len() - 1];
    for line in lines {
        let row: Vec<f64> = line.split(',').map(|v| v.trim().parse().expect("a number")).collect();
        times.push(row[0]);
        for (k, v) in row[1..].iter().enumerate() {
            values[k].push(*v);
        }
    }
    Reference { signals: names[1..].to_vec(), times, values }
}

/// How one signal compared.
#[derive(Debug)]
pub struct Comparison {
    /// The signal, as MSL names it.
    #[allow(dead_code)] // In the tests' messages; the bench's table has none.
    pub signal: String,
    /// The largest distance of the result from the reference at a
    /// reference row, over the tube's half-height δy (within 1: inside
    /// without the tube's width in time).
    pub worst: f64,
    /// Where that was.
    pub at: f64,
    /// Rows whose value lies outside the tube.
    pub outside: usize,
}

/// The tube's edges at `t` for the reference curve (`times`, `values`):
/// its smallest and largest value over [t − dx, t + dx], the curve linear
/// between rows.
fn edges(times: &[f64], values: &[f64], t: f64, dx: f64) -> (f64, f64) {
    let (a, b) = (t - dx, t + dx);
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut take = |v: f64| {
        lo = lo.min(v);
        hi = hi.max(v);
    };
    for k in 0..times.len() {
        if times[k] >= a && times[k] <= b {
            take(values[k]);
        }
        // A segment crossing the window's ends: the curve's value there.
        if k + 1 < times.len() && times[k + 1] > times[k] {
            for end in [a, b] {
                if times[k] < end && end < times[k + 1] {
                    let w = (end - times[k]) / (times[k + 1] - times[k]);
                    take(values[k] + w * (values[k + 1] - values[k]));
                }
            }
        }
    }
    (lo, hi)
}

/// Compares `ours` (the result's value at a time, `true` for the value
/// just before an event there) with signal `k` of `reference` by the
/// tube of relative size `r` (MAP-LIB: 0.002).
pub fn compare(
    reference: &Reference,
    k: usize,
    ours: &dyn Fn(f64, bool) -> f64,
    r: f64,
) -> Comparison {
    let (times, values) = (&reference.times, &reference.values[k]);
    let span = times[times.len() - 1] - times[0];
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let dx = r * span.max(times[0].abs()).max(1e-12);
    let dy = r * (max - min).max(min.abs()).max(0.001);
    let mut comparison =
        Comparison { signal: reference.signals[k].clone(), worst: 0.0, at: times[0], outside: 0 };
    for row in 0..times.len() {
        let t = times[row];
        // The first of two rows at one time is the value before the event.
        let before = row + 1 < times.len() && times[row + 1] == t;
        let value = ours(t, before);
        let distance = (value - values[row]).abs() / dy;
        if distance > comparison.worst || !distance.is_finite() {
            comparison.worst = if distance.is_finite() { distance } else { f64::INFINITY };
            comparison.at = t;
        }
        let (lo, hi) = edges(times, values, t, dx);
        // csv-compare lets a NaN pass; a result here never holds one.
        if !(value >= lo - dy && value <= hi + dy) {
            comparison.outside += 1;
        }
    }
    comparison
}
