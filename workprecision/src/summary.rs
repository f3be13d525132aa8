//! Ratios at matched error: our time over the peer's time at our error,
//! the peer's curve interpolated log–log between its two nearest points
//! (none outside the range the peer covers).

use crate::{Problem, Record};

/// The time `curve` would take to reach `error`, by log–log interpolation.
pub fn time_at_error(curve: &[&Record], error: f64) -> Option<f64> {
    let mut points: Vec<&&Record> =
        curve.iter().filter(|r| r.error > 0.0 && r.error.is_finite()).collect();
    points.sort_by(|a, b| b.error.total_cmp(&a.error));
    points.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        if error <= a.error && error >= b.error && a.error > b.error {
            let s = (error.ln() - a.error.ln()) / (b.error.ln() - a.error.ln());
            Some((a.seconds.ln() + s * (b.seconds.ln() - a.seconds.ln())).exp())
        } else if error == a.error {
            Some(a.seconds)
        } else {
            None
        }
    })
}

/// Our time over the peer's at each of our points the peer's curve covers:
/// (our record, ratio).
pub fn matched_ratio<'a>(ours: &[&'a Record], peer: &[&Record]) -> Vec<(&'a Record, f64)> {
    ours.iter()
        .filter(|r| r.error > 0.0 && r.error.is_finite())
        .filter_map(|r| time_at_error(peer, r.error).map(|t| (*r, r.seconds / t)))
        .collect()
}

fn ratio(r: f64) -> String {
    if r < 0.1 {
        format!("{r:.1e}×")
    } else {
        format!("{r:.2}×")
    }
}

/// The methods of a problem, ours first, in the order they ran.
pub(crate) fn curves(records: &[Record]) -> Vec<(String, Vec<&Record>)> {
    let mut out: Vec<(String, Vec<&Record>)> = Vec::new();
    for r in records {
        match out.iter_mut().find(|(m, _)| *m == r.method) {
            Some((_, c)) => c.push(r),
            None => out.push((r.method.clone(), vec![r])),
        }
    }
    out
}

/// The markdown summary: per problem, the cost of expanding the model,
/// the reference, and for each of our methods against each peer the median
/// ratio at matched error (with its range and the number of points), or
/// why there is none.
pub fn summary_markdown(problems: &[Problem]) -> String {
    let mut s = String::new();
    for p in problems {
        s.push_str(&format!("\n### {}\n\n", p.name));
        s.push_str(&format!("Reference: {}.", p.reference_source));
        if let Some(e) = &p.expansion {
            s.push_str(&format!(
                " Macro expansion {:.1} ms, generated code {:.1} kB.",
                e.seconds * 1e3,
                e.bytes as f64 / 1e3
            ));
        }
        if let Some(r) = p.rustc_seconds {
            s.push_str(&format!(" rustc (release) on the generated code: {r:.2} s."));
        }
        for (peer, t) in &p.setup {
            s.push_str(&format!(" {peer} set-up (JIT): {:.1} ms.", t * 1e3));
        }
        s.push('\n');
        let all = curves(&p.records);
        let (ours, peers): (Vec<_>, Vec<_>) =
            all.iter().partition(|(m, _)| m.starts_with("daegen "));
        if peers.is_empty() {
            s.push_str("\nNo peer ran on this problem.\n");
        } else {
            s.push_str("\n| ours | ");
            s.push_str(
                &peers.iter().map(|(m, _)| format!("vs {m}")).collect::<Vec<_>>().join(" | "),
            );
            s.push_str(" |\n|---|");
            s.push_str(&"---|".repeat(peers.len()));
            s.push('\n');
            for (m, curve) in &ours {
                let cells: Vec<String> = peers
                    .iter()
                    .map(|(_, pc)| {
                        let mut r: Vec<f64> =
                            matched_ratio(curve, pc).into_iter().map(|x| x.1).collect();
                        if r.is_empty() {
                            return "no common error range".to_string();
                        }
                        r.sort_by(f64::total_cmp);
                        format!(
                            "{} (range {}–{}, {} pts)",
                            ratio(r[r.len() / 2]),
                            ratio(r[0]),
                            ratio(r[r.len() - 1]),
                            r.len()
                        )
                    })
                    .collect();
                s.push_str(&format!("| {m} | {} |\n", cells.join(" | ")));
            }
        }
        for (peer, why) in &p.missing {
            s.push_str(&format!("\n{peer}: missing ({why}).\n"));
        }
    }
    s
}
