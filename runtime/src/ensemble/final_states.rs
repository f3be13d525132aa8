//! An ensemble's final states as a table that crosses machines: shards
//! (`--shard i/n`), their CSV files, and the merge that puts them back
//! together in member order.

use crate::error::Error;
use std::ops::Range;
use std::path::Path;

/// Part `index` of `count` contiguous blocks of an ensemble's members,
/// written `index/count` (Slurm's `$SLURM_ARRAY_TASK_ID` or Kubernetes'
/// `$JOB_COMPLETION_INDEX` as `index`, counted from 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which block, from 0.
    pub index: usize,
    /// How many blocks.
    pub count: usize,
}

impl Shard {
    /// The shard `index` of `count`; `Err` unless `index < count`.
    pub fn new(index: usize, count: usize) -> Result<Shard, Error> {
        if index >= count {
            return Err(Error::InvalidOptions {
                message: format!(
                    "shard {index}/{count} does not exist: write i/n with 0 ≤ i < n, such as 0/{}",
                    count.max(1)
                ),
            });
        }
        Ok(Shard { index, count })
    }

    /// Reads `i/n`, as `--shard 3/16` gives it.
    pub fn parse(text: &str) -> Result<Shard, Error> {
        let parsed = text
            .split_once('/')
            .and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
        match parsed {
            Some((index, count)) => Shard::new(index, count),
            None => Err(Error::InvalidOptions {
                message: format!("`{text}` is not a shard: write i/n, such as 0/4"),
            }),
        }
    }

    /// Its members among `0..members`: `[i·N/n, (i+1)·N/n)`, so the blocks
    /// differ in size by one at most and together hold every member once.
    pub fn members(&self, members: usize) -> Range<usize> {
        let at = |k: usize| (k as u128 * members as u128 / self.count as u128) as usize;
        at(self.index)..at(self.index + 1)
    }
}

/// One member's end: its state, or the message of its error.
#[derive(Clone, Debug, PartialEq)]
pub struct FinalState {
    /// The member's index in the whole ensemble.
    pub member: usize,
    /// The state at the end of its run (ordered as the table's names), or
    /// why it has none.
    pub state: Result<Vec<f64>, String>,
}

/// The final states of an ensemble's members (or a shard's), in member
/// order.
#[derive(Clone, Debug, PartialEq)]
pub struct FinalStates {
    /// The states' names ([`crate::ModelInfo::states`]).
    pub names: Vec<String>,
    /// One row a member.
    pub rows: Vec<FinalState>,
}

impl FinalStates {
    /// The members that failed, with their messages.
    pub fn errors(&self) -> impl Iterator<Item = (usize, &str)> {
        self.rows.iter().filter_map(|r| r.state.as_ref().err().map(|e| (r.member, e.as_str())))
    }

    /// Writes the table as CSV: `member,error,<state names…>`, one line a
    /// member, `error` empty where it ran and the states empty where it
    /// did not. Numbers are written in full (they read back exactly).
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let path = path.as_ref();
        let io = |e: csv::Error| Error::Io { message: format!("writing {}: {e}", path.display()) };
        let mut w = csv::Writer::from_path(path).map_err(io)?;
        let mut header = vec!["member".to_string(), "error".to_string()];
        header.extend(self.names.iter().cloned());
        w.write_record(&header).map_err(io)?;
        for row in &self.rows {
            let mut record = vec![row.member.to_string()];
            match &row.state {
                Ok(state) => {
                    record.push(String::new());
                    record.extend(state.iter().map(|v| format!("{v:?}")));
                }
                Err(message) => {
                    record.push(message.clone());
                    record.extend(self.names.iter().map(|_| String::new()));
                }
            }
            w.write_record(&record).map_err(io)?;
        }
        w.flush().map_err(|e| Error::Io { message: format!("writing {}: {e}", path.display()) })
    }

    /// Reads a table [`FinalStates::write_csv`] wrote.
    pub fn read_csv(path: impl AsRef<Path>) -> Result<FinalStates, Error> {
        let path = path.as_ref();
        let at = |line: u64, what: String| Error::Io {
            message: format!("reading {} (line {line}): {what}", path.display()),
        };
        let mut r = csv::Reader::from_path(path).map_err(|e| at(1, e.to_string()))?;
        let header = r.headers().map_err(|e| at(1, e.to_string()))?.clone();
        if header.get(0) != Some("member") || header.get(1) != Some("error") {
            return Err(at(1, "the header does not begin with `member,error`".into()));
        }
        let names: Vec<String> = header.iter().skip(2).map(str::to_string).collect();
        let mut rows = Vec::new();
        for (k, record) in r.records().enumerate() {
            let line = k as u64 + 2;
            let record = record.map_err(|e| at(line, e.to_string()))?;
            let member = record
                .get(0)
                .and_then(|m| m.parse().ok())
                .ok_or_else(|| at(line, "no member index".into()))?;
            let error = record.get(1).unwrap_or_default();
            let state = if error.is_empty() {
                let values: Result<Vec<f64>, _> =
                    record.iter().skip(2).map(|v| v.parse::<f64>()).collect();
                match values {
                    Ok(v) if v.len() == names.len() => Ok(v),
                    _ => return Err(at(line, format!("expected {} numbers", names.len()))),
                }
            } else {
                Err(error.to_string())
            };
            rows.push(FinalState { member, state });
        }
        Ok(FinalStates { names, rows })
    }

    /// The shards' tables of an ensemble of `members` as one, in member
    /// order; `Err` where they name different states, or where a member is
    /// missing (a shard left out) or given twice.
    pub fn merge(
        parts: impl IntoIterator<Item = FinalStates>,
        members: usize,
    ) -> Result<FinalStates, Error> {
        let mut parts = parts.into_iter();
        let Some(mut merged) = parts.next() else {
            return Err(Error::InvalidOptions { message: "no shards to merge".into() });
        };
        for part in parts {
            if part.names != merged.names {
                return Err(Error::InvalidOptions {
                    message: format!(
                        "the shards name different states ({:?} and {:?}): merge shards of one ensemble",
                        merged.names, part.names
                    ),
                });
            }
            merged.rows.extend(part.rows);
        }
        merged.rows.sort_by_key(|r| r.member);
        for (k, row) in merged.rows.iter().enumerate() {
            if row.member != k {
                let message = if row.member < k {
                    format!("member {} is in two shards", row.member)
                } else {
                    format!("member {k} is in no shard: is a shard missing?")
                };
                return Err(Error::InvalidOptions { message });
            }
        }
        if merged.rows.len() != members {
            let message = format!(
                "the shards hold members 0..{} of {members}: is a shard missing?",
                merged.rows.len()
            );
            return Err(Error::InvalidOptions { message });
        }
        Ok(merged)
    }
}
