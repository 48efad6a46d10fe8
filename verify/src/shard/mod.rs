//! Spreading a long campaign over a cluster's job array (a Slurm `--array`, GNU parallel):
//! the run's work is a numbered list of units (e.g. model pair x eps, in the order the
//! unsharded run computes them, each with its own seed); `--shard I/N` runs the units `k`
//! with `k mod N = I` and writes their raw rows ([`rows`]); `--merge DIR...` (with the
//! shards' other flags) reads the rows of all `N` shards and writes the tables and figures
//! the unsharded run writes. Without either flag a run is unchanged.
//!
//! The drivers of `experiments` and `verify crosscheck` share this module; `verify queries`
//! and `verify toi` split their cases by index modulo `N` (cases of one kind each, so
//! modulo is balanced there) and merge with `verify merge-queries`.

pub mod field;
pub mod rows;

pub use field::{Field, Item, Scalar};
pub use rows::{Cells, Record};

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Shard `index` of `count` (`0 <= index < count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The units of `0..units` this shard runs, in increasing order. The units are dealt
    /// round-robin to the `count` shards in an order shuffled by a fixed hash: every unit
    /// goes to exactly one shard, the shards' counts differ by one at most, and a periodic
    /// plan (pair x eps, where every third unit is the slowest eps) does not put all its slow
    /// units on one shard, as `unit mod N` would.
    pub fn units(&self, units: usize) -> Vec<usize> {
        let owner = owners(units, self.count);
        (0..units).filter(|&u| owner[u] == self.index).collect()
    }
}

/// The shard of each unit of `0..units` split `count` ways ([`Shard::units`]).
pub fn owners(units: usize, count: usize) -> Vec<usize> {
    let mut order: Vec<(u64, usize)> = (0..units).map(|u| (mix(u as u64), u)).collect();
    order.sort_unstable();
    let mut owner = vec![0; units];
    for (k, (_, u)) in order.into_iter().enumerate() {
        owner[u] = k % count.max(1);
    }
    owner
}

/// SplitMix64's finaliser: a fixed bijective hash of a unit's number (the deal's order).
fn mix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;

    /// `I/N` with whole numbers `0 <= I < N`.
    fn from_str(text: &str) -> Result<Shard, String> {
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| format!("'{text}' is not of the form I/N (e.g. 0/4)"))?;
        let parse = |v: &str| {
            v.trim()
                .parse::<usize>()
                .map_err(|_| format!("'{text}': '{v}' is not a whole number"))
        };
        let (index, count) = (parse(i)?, parse(n)?);
        if count == 0 || index >= count {
            return Err(format!(
                "'{text}': need 0 <= I < N (shards are numbered from 0)"
            ));
        }
        Ok(Shard { index, count })
    }
}

/// clap's parser of `--shard`.
pub fn parse_shard(text: &str) -> Result<Shard, String> {
    text.parse()
}

/// The flags `--shard I/N` and `--merge DIR...` of a driver (`#[command(flatten)]`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct Flags {
    /// Run only shard I of N (0 <= I < N): a fixed 1/N of the work units, with the seeds of
    /// an unsharded run; writes the raw rows to `DIR/<name>.rows.csv` (tables and figures come
    /// from --merge)
    #[arg(long, value_name = "I/N", value_parser = parse_shard, conflicts_with = "merge",
          allow_hyphen_values = true)]
    pub shard: Option<Shard>,
    /// Write the tables and figures from the raw rows of all shards, read from these output
    /// directories (comma-separated or repeated); give the flags the shards ran with
    #[arg(long, value_name = "DIR,...", value_delimiter = ',', num_args = 1..)]
    pub merge: Vec<PathBuf>,
}

impl Flags {
    /// Whether this run only writes a shard's rows (no tables or figures).
    pub fn is_shard(&self) -> bool {
        self.shard.is_some()
    }

    /// The units of `0..units` this run computes: all of them, a shard's, or none (a merge).
    pub fn units(&self, units: usize) -> Vec<usize> {
        match (self.shard, self.merge.is_empty()) {
            (_, false) => Vec::new(),
            (Some(s), true) => s.units(units),
            (None, true) => (0..units).collect(),
        }
    }

    /// The provenance entry that says a run is a shard or a merge of shards.
    pub fn provenance(&self) -> Option<(&'static str, String)> {
        if let Some(s) = self.shard {
            return Some(("shard", s.to_string()));
        }
        (!self.merge.is_empty()).then(|| {
            let dirs: Vec<String> = self.merge.iter().map(|d| d.display().to_string()).collect();
            (
                "merged_shards",
                format!("{} ({})", dirs.len(), dirs.join(", ")),
            )
        })
    }

    /// The whole campaign's rows, in unit order, once the run computed `rows` (`(unit,
    /// row)` for [`Self::units`], one or more rows per unit, in order): an unsharded run's
    /// own; `None` for a shard, which writes its rows to `dir` instead; for a merge, the rows
    /// of the shards' directories. `name` is the experiment (its file's name), `settings`
    /// what every shard must share.
    pub fn finish<R: Record>(
        &self,
        (dir, name): (&Path, &str),
        settings: &[(&str, String)],
        units: usize,
        mut rows: Vec<(usize, R)>,
    ) -> Result<Option<Vec<R>>, String> {
        if let Some(shard) = self.shard {
            let path = rows::write(dir, name, settings, (shard, units), &rows)?;
            eprintln!(
                "shard {shard}: {} of {units} units ({} rows), raw rows in {} (merge with --merge)",
                self.units(units).len(),
                rows.len(),
                path.display()
            );
            return Ok(None);
        }
        if !self.merge.is_empty() {
            return rows::merge(&self.merge, name, settings).map(Some);
        }
        rows.sort_by_key(|(u, _)| *u); // stable: a unit's rows keep their order
        let mut done: Vec<usize> = rows.iter().map(|(u, _)| *u).collect();
        done.dedup();
        if done.into_iter().ne(0..units) {
            return Err(format!("{name}: the run did not compute every unit"));
        }
        Ok(Some(rows.into_iter().map(|(_, r)| r).collect()))
    }

    /// [`Self::finish`] after computing this run's units one after the other with
    /// `compute(unit)`, one row each.
    pub fn run<R: Record, E: From<String>>(
        &self,
        job: (&Path, &str),
        settings: &[(&str, String)],
        units: usize,
        mut compute: impl FnMut(usize) -> Result<R, E>,
    ) -> Result<Option<Vec<R>>, E> {
        self.run_many(job, settings, units, |u| compute(u).map(|r| vec![r]))
    }

    /// [`Self::run`] for units of several rows each.
    pub fn run_many<R: Record, E: From<String>>(
        &self,
        (dir, name): (&Path, &str),
        settings: &[(&str, String)],
        units: usize,
        mut compute: impl FnMut(usize) -> Result<Vec<R>, E>,
    ) -> Result<Option<Vec<R>>, E> {
        let mut rows = Vec::new();
        for u in self.units(units) {
            rows.extend(compute(u)?.into_iter().map(|r| (u, r)));
        }
        Ok(self.finish((dir, name), settings, units, rows)?)
    }
}

#[cfg(test)]
mod tests;
