//! Signals a model reads from outside (`let u = input(u0);`): a constant,
//! a function of the time, or a table of samples interpolated linearly or
//! by monotone cubics, whose breakpoints a run steps to (a kink is never
//! inside a step).

use std::sync::Arc;

/// The value of a model's input over time: the field `u` of a model that
/// declares `let u = input(u0);` (the constant `u0` by default).
///
/// ```
/// # use daegen_runtime::Input;
/// let step = Input::function(|t| if t < 1.0 { 0.0 } else { 12.0 });
/// let measured = Input::linear(&[0.0, 1.0, 2.0], &[0.0, 5.0, 4.0])?;
/// assert_eq!(measured.at(0.5), 2.5);
/// assert_eq!(measured.breakpoints(), &[0.0, 1.0, 2.0]);
/// # Ok::<(), daegen_runtime::Error>(())
/// ```
///
/// For co-simulation, set a constant between the communication steps and
/// run each step with `simulate_from`: `model.u = Input::constant(v);`.
#[derive(Clone)]
pub struct Input {
    source: Source,
}

#[derive(Clone)]
enum Source {
    Constant(f64),
    Function(Arc<dyn Fn(f64) -> f64 + Send + Sync>),
    Table(Arc<Table>),
}

/// Samples `(t_k, u_k)` with a slope at each: linear interpolation has the
/// secant's on each side, a monotone cubic Fritsch–Carlson's.
#[derive(Debug, PartialEq)]
struct Table {
    times: Vec<f64>,
    values: Vec<f64>,
    /// Hermite slopes at the samples; `None`: linear.
    slopes: Option<Vec<f64>>,
}

impl Input {
    /// The same value at every time.
    pub fn constant(value: f64) -> Input {
        Input { source: Source::Constant(value) }
    }

    /// `f(t)`, called at every evaluation of the model. Its rate (for the
    /// methods that need ∂f/∂t) is a central difference; a function with
    /// jumps or kinks should be a table, whose breakpoints the run steps to.
    pub fn function(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Input {
        Input { source: Source::Function(Arc::new(f)) }
    }

    /// Samples joined by straight lines, held constant before the first
    /// and after the last. The times must increase strictly, and the
    /// values be finite.
    pub fn linear(times: &[f64], values: &[f64]) -> Result<Input, crate::Error> {
        check(times, values)?;
        let table = Table { times: times.to_vec(), values: values.to_vec(), slopes: None };
        Ok(Input { source: Source::Table(Arc::new(table)) })
    }

    /// Samples joined by the monotone piecewise cubic of Fritsch and
    /// Carlson (SIAM J. Numer. Anal. 17, 1980): continuously
    /// differentiable, and monotone wherever the samples are (no
    /// overshoot), held constant outside the samples.
    pub fn monotone_cubic(times: &[f64], values: &[f64]) -> Result<Input, crate::Error> {
        check(times, values)?;
        let slopes = fritsch_carlson(times, values);
        let table = Table { times: times.to_vec(), values: values.to_vec(), slopes: Some(slopes) };
        Ok(Input { source: Source::Table(Arc::new(table)) })
    }

    /// The value at `t`.
    pub fn at(&self, t: f64) -> f64 {
        match &self.source {
            Source::Constant(v) => *v,
            Source::Function(f) => f(t),
            Source::Table(table) => table.at(t, false),
        }
    }

    /// The rate du/dt at `t` (from the right at a breakpoint).
    pub fn rate(&self, t: f64) -> f64 {
        match &self.source {
            Source::Constant(_) => 0.0,
            Source::Function(f) => {
                let h = f64::EPSILON.cbrt() * t.abs().max(1.0);
                (f(t + h) - f(t - h)) / (2.0 * h)
            }
            Source::Table(table) => table.at(t, true),
        }
    }

    /// The times where the input is not smooth (a table's samples), which
    /// a run steps to; empty for a constant or a function.
    pub fn breakpoints(&self) -> &[f64] {
        match &self.source {
            Source::Table(table) => &table.times,
            _ => &[],
        }
    }
}

impl std::fmt::Debug for Input {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.source {
            Source::Constant(v) => write!(f, "Input::constant({v})"),
            Source::Function(_) => write!(f, "Input::function(..)"),
            Source::Table(t) => {
                let kind = if t.slopes.is_some() { "monotone_cubic" } else { "linear" };
                write!(f, "Input::{kind}({} samples)", t.times.len())
            }
        }
    }
}

/// Constants and tables compare by value, functions by identity.
impl PartialEq for Input {
    fn eq(&self, other: &Input) -> bool {
        match (&self.source, &other.source) {
            (Source::Constant(a), Source::Constant(b)) => a == b,
            (Source::Function(a), Source::Function(b)) => Arc::ptr_eq(a, b),
            (Source::Table(a), Source::Table(b)) => a == b,
            _ => false,
        }
    }
}

fn check(times: &[f64], values: &[f64]) -> Result<(), crate::Error> {
    let bad = |message: String| Err(crate::Error::InvalidOptions { message });
    if times.is_empty() || times.len() != values.len() {
        return bad(format!(
            "an input table needs as many values as times, at least one: {} times, {} values",
            times.len(),
            values.len()
        ));
    }
    if let Some(k) =
        times.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
    {
        return bad(format!(
            "an input table's times must increase: t[{}] = {} is followed by {}",
            k,
            times[k],
            times[k + 1]
        ));
    }
    if let Some(k) = times.iter().chain(values).position(|v| !v.is_finite()) {
        return bad(format!("an input table holds a value that is not finite (entry {k})"));
    }
    Ok(())
}

impl Table {
    /// The value (or with `rate`, the slope) at `t`: on the interval
    /// `[t_k, t_{k+1})` that holds it, the line or the cubic Hermite
    /// polynomial; constant outside.
    fn at(&self, t: f64, rate: bool) -> f64 {
        let (times, values) = (&self.times, &self.values);
        let last = times.len() - 1;
        if t < times[0] || t >= times[last] || last == 0 {
            let v = if t < times[0] { values[0] } else { values[last] };
            return if rate { 0.0 } else { v };
        }
        let k = times.partition_point(|&s| s <= t) - 1;
        let h = times[k + 1] - times[k];
        let s = (t - times[k]) / h;
        let (y0, y1) = (values[k], values[k + 1]);
        match &self.slopes {
            None if rate => (y1 - y0) / h,
            None => y0 + s * (y1 - y0),
            Some(m) => {
                let (m0, m1) = (m[k] * h, m[k + 1] * h);
                if rate {
                    let (s2, d) = (s * s, y1 - y0);
                    ((6.0 * s2 - 6.0 * s) * -d
                        + (3.0 * s2 - 4.0 * s + 1.0) * m0
                        + (3.0 * s2 - 2.0 * s) * m1)
                        / h
                } else {
                    let (s2, s3) = (s * s, s * s * s);
                    (2.0 * s3 - 3.0 * s2 + 1.0) * y0
                        + (s3 - 2.0 * s2 + s) * m0
                        + (3.0 * s2 - 2.0 * s3) * y1
                        + (s3 - s2) * m1
                }
            }
        }
    }
}

/// Fritsch–Carlson slopes: the three-point slopes, set to zero at local
/// extrema and scaled where they would overshoot (α² + β² ≤ 9).
fn fritsch_carlson(times: &[f64], values: &[f64]) -> Vec<f64> {
    let n = times.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let secant: Vec<f64> =
        (0..n - 1).map(|k| (values[k + 1] - values[k]) / (times[k + 1] - times[k])).collect();
    let mut m = vec![0.0; n];
    m[0] = secant[0];
    m[n - 1] = secant[n - 2];
    for k in 1..n - 1 {
        m[k] =
            if secant[k - 1] * secant[k] <= 0.0 { 0.0 } else { 0.5 * (secant[k - 1] + secant[k]) };
    }
    for k in 0..n - 1 {
        if secant[k] == 0.0 {
            m[k] = 0.0;
            m[k + 1] = 0.0;
            continue;
        }
        let (a, b) = (m[k] / secant[k], m[k + 1] / secant[k]);
        let r = a * a + b * b;
        if r > 9.0 {
            let tau = 3.0 / r.sqrt();
            m[k] = tau * a * secant[k];
            m[k + 1] = tau * b * secant[k];
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::Input;

    #[test]
    fn tables_interpolate_and_hold_outside() {
        let u = Input::linear(&[0.0, 1.0, 3.0], &[1.0, 3.0, 2.0]).expect("a table");
        assert_eq!(u.at(-1.0), 1.0);
        assert_eq!(u.at(0.5), 2.0);
        assert_eq!(u.at(2.0), 2.5);
        assert_eq!(u.at(5.0), 2.0);
        assert_eq!(u.rate(0.5), 2.0);
        assert_eq!(u.rate(1.0), -0.5);
        assert!(Input::linear(&[0.0, 0.0], &[1.0, 2.0]).is_err());
        assert!(Input::linear(&[0.0], &[1.0, 2.0]).is_err());
    }

    #[test]
    fn monotone_cubics_pass_the_samples_without_overshoot() {
        let (t, y) = ([0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 0.1, 5.0, 5.1, 5.1]);
        let u = Input::monotone_cubic(&t, &y).expect("a table");
        for (ti, yi) in t.iter().zip(&y) {
            assert!((u.at(*ti) - yi).abs() <= 1e-15);
        }
        let mut previous = u.at(0.0);
        for k in 1..=4000 {
            let v = u.at(k as f64 * 1e-3);
            assert!(v >= previous - 1e-14 && v <= 5.1 + 1e-14, "at {}: {v}", k as f64 * 1e-3);
            previous = v;
        }
        // The slope is the value's derivative.
        let (a, h) = (1.37, 1e-6);
        let central = (u.at(a + h) - u.at(a - h)) / (2.0 * h);
        assert!((u.rate(a) - central).abs() <= 1e-6);
    }
}
