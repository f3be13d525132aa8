//! Named columns of values at a list of times: what
//! [`crate::Solution::sample`] and [`crate::Solution::table`] return, to
//! print, write as CSV or hand to a plot.

use crate::error::Error;
use std::fmt;

/// Values of some names at some times, one column per name.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Table {
    names: Vec<String>,
    times: Vec<f64>,
    columns: Vec<Vec<f64>>,
}

impl Table {
    /// A table of `columns` (one per name, each as long as `times`).
    pub fn new(names: Vec<String>, times: Vec<f64>, columns: Vec<Vec<f64>>) -> Table {
        debug_assert_eq!(names.len(), columns.len());
        debug_assert!(columns.iter().all(|c| c.len() == times.len()));
        Table { names, times, columns }
    }

    /// The names of the columns, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The times of the rows.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The column of `name`, if the table has it.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        let k = self.names.iter().position(|n| n == name)?;
        Some(&self.columns[k])
    }

    /// The columns in the order of [`Table::names`].
    pub fn columns(&self) -> &[Vec<f64>] {
        &self.columns
    }

    /// Writes the table as CSV: a header row (`t` and the names), then one
    /// row per time, each number in the shortest form that reads back to
    /// the same `f64`.
    pub fn write_csv<W: std::io::Write>(&self, writer: W) -> Result<(), Error> {
        let failed = |e: csv::Error| Error::Io { message: format!("writing CSV failed: {e}") };
        let mut out = csv::Writer::from_writer(writer);
        let header = std::iter::once("t").chain(self.names.iter().map(String::as_str));
        out.write_record(header).map_err(failed)?;
        let mut row = Vec::with_capacity(self.names.len() + 1);
        for (k, t) in self.times.iter().enumerate() {
            row.clear();
            row.push(t.to_string());
            row.extend(self.columns.iter().map(|c| c[k].to_string()));
            out.write_record(&row).map_err(failed)?;
        }
        out.flush().map_err(|e| Error::Io { message: format!("writing CSV failed: {e}") })
    }
}

/// An aligned text table, for printing: `t` and the names as a header,
/// six significant digits.
impl fmt::Display for Table {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let width = self.names.iter().map(|n| n.len()).max().unwrap_or(0).max(12);
        write!(f, "{:>width$}", "t")?;
        for name in &self.names {
            write!(f, " {name:>width$}")?;
        }
        for (k, t) in self.times.iter().enumerate() {
            write!(f, "\n{:>width$}", significant(*t))?;
            for column in &self.columns {
                write!(f, " {:>width$}", significant(column[k]))?;
            }
        }
        Ok(())
    }
}

/// `x` in six significant digits, positional where that is short.
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    // The exponent after rounding to six digits (0.9999996 is 1.00000e0).
    let scientific = format!("{x:.5e}");
    let exponent: i32 = scientific.rsplit('e').next().and_then(|e| e.parse().ok()).unwrap_or(0);
    if (-4..6).contains(&exponent) {
        let decimals = (5 - exponent).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        scientific
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Table {
        Table::new(
            vec!["x".into(), "der(x)".into()],
            vec![0.0, 0.5],
            vec![vec![1.0, 0.1 + 0.2], vec![-2.5e-7, 1234567.0]],
        )
    }

    #[test]
    fn csv_has_a_header_and_numbers_that_read_back_exactly() {
        let mut out = Vec::new();
        table().write_csv(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "t,x,der(x)");
        assert_eq!(lines.len(), 3);
        let values: Vec<f64> = lines[2].split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values, [0.5, 0.1 + 0.2, 1234567.0]);
    }

    #[test]
    fn display_aligns_columns() {
        let text = table().to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines.iter().all(|l| l.len() == lines[0].len()), "{text}");
        assert!(lines[1].contains("1.00000"), "{text}");
        assert!(lines[1].contains("-2.50000e-7"), "{text}");
        assert!(lines[2].contains("1.23457e6"), "{text}");
        assert_eq!(significant(0.99999996), "1.00000");
        assert_eq!(significant(100000.0), "100000");
        assert_eq!(significant(2.5e-5), "2.50000e-5");
    }

    #[test]
    fn columns_by_name() {
        assert_eq!(table().column("y"), None);
        assert_eq!(table().column("x").unwrap(), &[1.0, 0.1 + 0.2]);
    }
}
