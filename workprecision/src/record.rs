//! One run of one method (ours or a peer's) on one problem, and the CSV
//! that holds a sweep.

/// One point of a work-precision diagram, with the work behind it.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The problem (the model's name).
    pub problem: String,
    /// `daegen DOP853`, `diffsol BDF`, …
    pub method: String,
    /// The relative tolerance, or for a fixed-step method the step size.
    pub tol: f64,
    /// max |y − ref| / max(1, |ref|) at the end time; infinite when the run
    /// failed.
    pub error: f64,
    /// Median wall time of a solve, in seconds.
    pub seconds: f64,
    /// Accepted steps (0 where a peer does not say).
    pub steps: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Right-hand-side evaluations.
    pub rhs_evals: usize,
    /// Jacobian evaluations.
    pub jacobian_evals: usize,
}

const HEADER: &str = "problem,method,tol,error,seconds,steps,rejected,rhs_evals,jacobian_evals";

/// The records as CSV, one header line then one line per record.
pub fn to_csv(records: &[Record]) -> String {
    let mut out = String::from(HEADER);
    out.push('\n');
    for r in records {
        out.push_str(&format!(
            "{},{},{:e},{:e},{:e},{},{},{},{}\n",
            quote_field(&r.problem),
            quote_field(&r.method),
            r.tol,
            r.error,
            r.seconds,
            r.steps,
            r.rejected,
            r.rhs_evals,
            r.jacobian_evals
        ));
    }
    out
}

fn quote_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Reads CSV written by [`to_csv`]; `Err` names the first bad line.
pub fn parse_csv(text: &str) -> Result<Vec<Record>, String> {
    let mut lines = text.lines();
    match lines.next() {
        Some(h) if h == HEADER => {}
        other => return Err(format!("expected the header `{HEADER}`, found {other:?}")),
    }
    let mut out = Vec::new();
    for (k, line) in lines.enumerate() {
        let fields = split_fields(line);
        let bad = || format!("line {}: `{line}`", k + 2);
        if fields.len() != 9 {
            return Err(bad());
        }
        let float = |i: usize| fields[i].parse::<f64>().map_err(|_| bad());
        let int = |i: usize| fields[i].parse::<usize>().map_err(|_| bad());
        out.push(Record {
            problem: fields[0].clone(),
            method: fields[1].clone(),
            tol: float(2)?,
            error: float(3)?,
            seconds: float(4)?,
            steps: int(5)?,
            rejected: int(6)?,
            rhs_evals: int(7)?,
            jacobian_evals: int(8)?,
        });
    }
    Ok(out)
}

fn split_fields(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    fields.push(field);
    fields
}
