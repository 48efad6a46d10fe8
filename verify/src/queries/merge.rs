//! Merging the shards of one campaign: `verify queries --shard I/N --out DIR_I` for every
//! `I` in `0..N` (e.g. a cluster's job array), then `verify merge-queries DIR_0 ... DIR_N-1`
//! adds up their `summary.json` files. The shards must share the seed and the count and
//! cover every index of `0..N` exactly once; the merged counts are then those of one run
//! without shards (the cases are numbered, drawn and placed the same way).

use std::fmt::Write as _;
use std::path::Path;

/// The merged report of the shards in `dirs`, and whether any case failed; an error names
/// a missing, unreadable or inconsistent shard.
pub fn merge(dirs: &[impl AsRef<Path>]) -> Result<(String, bool), String> {
    if dirs.is_empty() {
        return Err("give the output directories of the shards".into());
    }
    let mut seen: Vec<usize> = Vec::new();
    let mut settings: Option<(u64, u64, u64)> = None;
    let (mut cases, mut failing, mut violations, mut wall) = (0u64, 0u64, 0u64, 0.0f64);
    let mut by_check: Vec<(String, u64)> = Vec::new();
    let mut failures: Vec<String> = Vec::new();
    for dir in dirs {
        let path = dir.as_ref().join("summary.json");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read '{}': {e}", path.display()))?;
        let v: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| format!("'{}' is not a campaign summary: {e}", path.display()))?;
        let field = |k: &str| {
            v[k].as_u64()
                .ok_or_else(|| format!("'{}': field `{k}` missing", path.display()))
        };
        let shard = v["shard"]
            .as_array()
            .and_then(|a| Some((a.first()?.as_u64()?, a.get(1)?.as_u64()?)))
            .ok_or_else(|| format!("'{}': field `shard` missing", path.display()))?;
        let these = (field("seed")?, field("count")?, shard.1);
        match settings {
            None => settings = Some(these),
            Some(s) if s != these => {
                return Err(format!(
                    "'{}' is seed {}, count {}, {} shards; the first shard was seed {}, count {}, {} shards",
                    path.display(),
                    these.0,
                    these.1,
                    these.2,
                    s.0,
                    s.1,
                    s.2
                ))
            }
            Some(_) => {}
        }
        let index = shard.0 as usize;
        if seen.contains(&index) {
            return Err(format!(
                "shard {index} is given twice ('{}')",
                path.display()
            ));
        }
        seen.push(index);
        cases += field("cases")?;
        failing += field("failing")?;
        violations += field("violations")?;
        wall += v["wall_s"].as_f64().unwrap_or(0.0);
        if let Some(m) = v["by_check"].as_object() {
            for (name, n) in m {
                let n = n.as_u64().unwrap_or(0);
                match by_check.iter_mut().find(|(k, _)| k == name) {
                    Some(e) => e.1 += n,
                    None => by_check.push((name.clone(), n)),
                }
            }
        }
        if let Some(f) = v["failures"].as_array() {
            failures.extend(f.iter().filter_map(|l| l.as_str().map(String::from)));
        }
    }
    let (seed, count, n) = settings.expect("at least one shard");
    seen.sort_unstable();
    if seen != (0..n as usize).collect::<Vec<_>>() {
        let missing: Vec<usize> = (0..n as usize).filter(|i| !seen.contains(i)).collect();
        return Err(format!("shards {missing:?} of {n} are missing"));
    }
    let mut s = String::new();
    writeln!(
        s,
        "queries (seed {seed}, count {count}, {n} shards merged): {cases} cases, {failing} failing ({violations} violations), wall {wall:.1} s summed over shards"
    )
    .unwrap();
    writeln!(s, "by check (cases):").unwrap();
    for (name, k) in &by_check {
        writeln!(s, "  {name:<24} {k:>6}").unwrap();
    }
    for line in &failures {
        writeln!(s, "failing: {line}").unwrap();
    }
    Ok((s, violations > 0))
}
