//! The raw-rows file of a shard, `DIR/<name>.rows.csv`: the provenance lines of the run (with
//! `param.shard: I/N` and `param.shard_units: U`), a header `unit,<field>,...`, and one line
//! per work unit the shard ran, every value written losslessly ([`super::field`]). A merge
//! reads the files of all shards, checks that they belong to one campaign and cover every
//! unit exactly once, and returns the rows in unit order: the rows the unsharded run computes.

use super::field::Field;
use super::Shard;
use crate::provenance::Provenance;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A raw row: named fields, each a [`Field`]. Implemented with [`crate::shard_record`].
pub trait Record: Sized {
    /// The field names, in column order.
    fn columns() -> Vec<&'static str>;
    /// The cells of this row, in column order.
    fn cells(&self) -> Vec<String>;
    /// The row whose cells `line` holds.
    fn from_cells(line: &Cells) -> Result<Self, String>;
}

/// Implements [`Record`] for a struct from the list of its fields (all of them: a field left
/// out is a compile error, so the raw rows always carry the whole row).
#[macro_export]
macro_rules! shard_record {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        impl $crate::shard::Record for $ty {
            fn columns() -> Vec<&'static str> {
                vec![$(stringify!($field)),*]
            }
            fn cells(&self) -> Vec<String> {
                vec![$($crate::shard::Field::text(&self.$field)),*]
            }
            fn from_cells(line: &$crate::shard::Cells) -> Result<Self, String> {
                Ok(Self { $($field: line.get(stringify!($field))?),* })
            }
        }
    };
}

/// The cells of one line, by column name.
pub struct Cells<'a> {
    columns: &'a [String],
    cells: Vec<&'a str>,
}

impl Cells<'_> {
    /// The value of column `name`.
    pub fn get<T: Field>(&self, name: &str) -> Result<T, String> {
        let k = self
            .columns
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| format!("no column `{name}`"))?;
        T::parse(self.cells[k]).map_err(|e| format!("column `{name}`: {e}"))
    }
}

/// The path of the raw rows of experiment `name` in `dir`.
pub fn rows_path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("{name}.rows.csv"))
}

/// Provenance key of the shard (`I/N`) and of the campaign's count of work units.
const SHARD_KEY: &str = "param.shard";
const UNITS_KEY: &str = "param.shard_units";

/// Writes shard `shard`'s rows (`(unit, row)`, units of `0..units`) of experiment `name`
/// run with `settings` to [`rows_path`].
pub fn write<R: Record>(
    dir: &Path,
    name: &str,
    settings: &[(&str, String)],
    (shard, units): (Shard, usize),
    rows: &[(usize, R)],
) -> Result<PathBuf, String> {
    let mut params = settings.to_vec();
    params.push(("shard", shard.to_string()));
    params.push(("shard_units", units.to_string()));
    let mut text = Provenance::collect(name, &params).csv_preamble();
    text.push_str("unit,");
    text.push_str(&R::columns().join(","));
    text.push('\n');
    for (unit, row) in rows {
        text.push_str(&unit.to_string());
        for cell in row.cells() {
            text.push(',');
            text.push_str(&cell);
        }
        text.push('\n');
    }
    let path = rows_path(dir, name);
    std::fs::write(&path, text).map_err(|e| format!("cannot write '{}': {e}", path.display()))?;
    Ok(path)
}

/// One shard's file as read.
struct ShardFile<R> {
    path: PathBuf,
    shard: Shard,
    units: usize,
    commit: String,
    settings: BTreeMap<String, String>,
    rows: Vec<(usize, R)>,
}

fn read<R: Record>(dir: &Path, name: &str) -> Result<ShardFile<R>, String> {
    let path = rows_path(dir, name);
    let at = |what: String| format!("'{}': {what}", path.display());
    let text = std::fs::read_to_string(&path).map_err(|e| at(format!("cannot read: {e}")))?;
    let mut entries = BTreeMap::new();
    let mut lines = text.lines();
    let header = loop {
        let line = lines.next().ok_or_else(|| at("no header line".into()))?;
        match line.strip_prefix("# ") {
            Some(entry) => {
                if let Some((k, v)) = entry.split_once(": ") {
                    entries.insert(k.to_owned(), v.to_owned());
                }
            }
            None => break line,
        }
    };
    let columns: Vec<String> = header.split(',').map(str::to_owned).collect();
    let expected: Vec<String> = std::iter::once("unit")
        .chain(R::columns())
        .map(str::to_owned)
        .collect();
    if columns != expected {
        return Err(at(format!(
            "columns {columns:?}, expected {expected:?} (written by another version?)"
        )));
    }
    let shard: Shard = entries
        .get(SHARD_KEY)
        .ok_or_else(|| at(format!("no `{SHARD_KEY}` line")))?
        .parse()
        .map_err(at)?;
    let units: usize = entries
        .get(UNITS_KEY)
        .and_then(|u| u.parse().ok())
        .ok_or_else(|| at(format!("no `{UNITS_KEY}` line")))?;
    let commit = entries.get("git_commit").cloned().unwrap_or_default();
    let settings = entries
        .iter()
        .filter(|(k, _)| k.starts_with("param.") && *k != SHARD_KEY && *k != UNITS_KEY)
        .map(|(k, v)| (k["param.".len()..].to_owned(), v.clone()))
        .collect();
    let mut rows = Vec::new();
    for (n, line) in lines.enumerate().filter(|(_, l)| !l.is_empty()) {
        let at_line = |e: String| at(format!("row {}: {e}", n + 1));
        let cells: Vec<&str> = line.split(',').collect();
        if cells.len() != columns.len() {
            return Err(at_line(format!(
                "{} cells, expected {}",
                cells.len(),
                columns.len()
            )));
        }
        let unit: usize = Field::parse(cells[0]).map_err(at_line)?;
        let row = R::from_cells(&Cells {
            columns: &columns,
            cells,
        })
        .map_err(at_line)?;
        rows.push((unit, row));
    }
    Ok(ShardFile {
        path,
        shard,
        units,
        commit,
        settings,
        rows,
    })
}

/// The rows of every unit of experiment `name`, read from the shards' directories `dirs`
/// and returned in unit order (a unit's rows, if it has several, in their order). The shards must have been run with `settings` (the merge's
/// own, from the same flags), by one commit, as shards `0..N` of one split, each holding
/// only its units ([`Shard::units`]), together all `U` units (each with a row at least).
pub fn merge<R: Record>(
    dirs: &[PathBuf],
    name: &str,
    settings: &[(&str, String)],
) -> Result<Vec<R>, String> {
    if dirs.is_empty() {
        return Err("--merge needs the output directories of the shards".into());
    }
    let expected: BTreeMap<String, String> = settings
        .iter()
        .map(|(k, v)| ((*k).to_owned(), v.clone()))
        .collect();
    let files = dirs
        .iter()
        .map(|d| read::<R>(d, name))
        .collect::<Result<Vec<_>, _>>()?;
    let commit = files[0].commit.clone();
    let owner = super::owners(files[0].units, files[0].shard.count);
    let mut seen = vec![false; files[0].shard.count];
    let mut by_unit: Vec<Vec<R>> = (0..files[0].units).map(|_| Vec::new()).collect();
    for f in files {
        let at = |what: String| format!("'{}': {what}", f.path.display());
        if (f.shard.count, f.units) != (seen.len(), by_unit.len()) {
            return Err(at(format!(
                "shard {} of {} units; the first shard was of {} shards of {} units",
                f.shard,
                f.units,
                seen.len(),
                by_unit.len()
            )));
        }
        if f.settings != expected {
            let differs = expected
                .iter()
                .find(|(k, v)| f.settings.get(*k) != Some(*v))
                .map(|(k, v)| {
                    format!(
                        "`{k}` is '{}' there, '{v}' in this merge",
                        f.settings.get(k).map_or("(missing)", String::as_str)
                    )
                })
                .unwrap_or_else(|| "it has settings this merge does not".into());
            return Err(at(format!(
                "run with other settings: {differs} (give the merge the flags the shards ran with)"
            )));
        }
        if f.commit != commit {
            return Err(at(format!(
                "run by commit {}, the first shard by {commit}: the merge would mix two versions",
                f.commit
            )));
        }
        if std::mem::replace(&mut seen[f.shard.index], true) {
            return Err(at(format!("shard {} is given twice", f.shard)));
        }
        for (unit, row) in f.rows {
            if unit >= by_unit.len() || owner[unit] != f.shard.index {
                return Err(at(format!("unit {unit} is not one of shard {}'s", f.shard)));
            }
            by_unit[unit].push(row);
        }
    }
    let missing: Vec<usize> = (0..seen.len()).filter(|&i| !seen[i]).collect();
    if !missing.is_empty() {
        return Err(format!("shards {missing:?} of {} are missing", seen.len()));
    }
    let absent: Vec<usize> = (0..by_unit.len())
        .filter(|&u| by_unit[u].is_empty())
        .collect();
    if !absent.is_empty() {
        return Err(format!(
            "units {absent:?} of {} are in no shard's rows (a shard stopped early?)",
            by_unit.len()
        ));
    }
    Ok(by_unit.into_iter().flatten().collect())
}
