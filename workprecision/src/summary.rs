//! Ratios at matched error: our time over the peer's time at our error,
//! the peer's curve interpolated log–log between its two nearest points
//! (none outside the range the peer covers). Points whose error is
//! [`LOST`] or more are not compared.

use crate::{Problem, Record};

/// The error (max |y − ref| / max(1, |ref|)) from which a run has lost the
/// solution: off by as much as the solution is large (an orbit's phase
/// lost, as DOP853 and DOPRI5 lose Kepler's at e = 0.9 and rtol 1e-5).
/// There the curves are not monotone (a tighter tolerance can end farther
/// off) and no time is the time to reach an error, so such points are
/// neither matched nor matched against.
pub const LOST: f64 = 1.0;

/// Whether a record's error can be matched: positive, finite, below [`LOST`].
fn comparable(r: &Record) -> bool {
    r.error > 0.0 && r.error < LOST
}

/// The time `curve` would take to reach `error`, by log–log interpolation.
pub fn time_at_error(curve: &[&Record], error: f64) -> Option<f64> {
    let mut points: Vec<&&Record> = curve.iter().filter(|r| comparable(r)).collect();
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
        .filter(|r| comparable(r))
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

#[cfg(test)]
mod tests {
    use super::*;

    fn point(method: &str, tol: f64, error: f64, seconds: f64) -> Record {
        Record {
            problem: "kepler".into(),
            method: method.into(),
            tol,
            error,
            seconds,
            steps: 0,
            rejected: 0,
            rhs_evals: 0,
            jacobian_evals: 0,
        }
    }

    #[test]
    fn the_peer_is_interpolated_log_log_at_our_error() {
        let peer = [point("peer", 1e-6, 1e-4, 1.0), point("peer", 1e-8, 1e-6, 4.0)];
        let peer: Vec<&Record> = peer.iter().collect();
        // Halfway in log error: halfway in log time, √(1·4) = 2.
        let t = time_at_error(&peer, 1e-5).unwrap_or(f64::NAN);
        assert!((t - 2.0).abs() < 1e-12, "{t}");
        assert_eq!(time_at_error(&peer, 1e-7), None, "outside the peer's range");
    }

    #[test]
    fn lost_solutions_are_not_matched() {
        // Kepler e = 0.9 at loose tolerances: a tighter tolerance ended
        // farther off, then the orbit was found again.
        let peer = [
            point("peer", 1e-3, 1.12, 5.95e-5),
            point("peer", 1e-4, 2.01, 6.98e-5),
            point("peer", 1e-5, 0.75, 8.58e-5),
            point("peer", 1e-6, 0.29, 1.13e-4),
        ];
        let peer: Vec<&Record> = peer.iter().collect();
        let ours = [point("ours", 1e-5, 1.26, 5.12e-5), point("ours", 1e-6, 0.29, 6.45e-5)];
        let ours: Vec<&Record> = ours.iter().collect();
        let matched = matched_ratio(&ours, &peer);
        assert_eq!(matched.len(), 1, "only the point that kept the orbit");
        assert!((matched[0].1 - 6.45e-5 / 1.13e-4).abs() < 1e-12);
        // Nor is a peer's lost point used to bracket ours.
        assert_eq!(time_at_error(&peer, 0.9), None);
    }
}
