//! Where a result came from: machine, git commit, time and the run's parameters, written as
//! `# key: value` comment lines at the top of every CSV (readers: `pandas.read_csv(...,
//! comment="#")`, R `read.csv(..., comment.char = "#")`) and as a footer of every Markdown table.

use std::fmt::Write as _;
use std::process::Command;

/// Provenance of one experiment run.
#[derive(Debug, Clone)]
pub struct Provenance {
    /// `key: value` pairs in display order.
    entries: Vec<(String, String)>,
}

impl Provenance {
    /// Collect the machine, commit and time, and record the experiment's name and parameters.
    pub fn collect(experiment: &str, params: &[(&str, String)]) -> Self {
        let mut entries = vec![
            ("experiment".to_string(), experiment.to_string()),
            ("git_commit".to_string(), git_commit()),
            ("generated_utc".to_string(), utc_now()),
            ("cpu".to_string(), cpu_model()),
            (
                "threads_available".to_string(),
                std::thread::available_parallelism()
                    .map(|n| n.get().to_string())
                    .unwrap_or_else(|_| "unknown".into()),
            ),
            ("kernel".to_string(), kernel()),
            (
                "profile".to_string(),
                if cfg!(debug_assertions) {
                    "debug"
                } else {
                    "release"
                }
                .to_string(),
            ),
        ];
        for (k, v) in params {
            entries.push((format!("param.{k}"), v.clone()));
        }
        Provenance { entries }
    }

    /// The `# key: value` lines that open a CSV file.
    pub fn csv_preamble(&self) -> String {
        let mut s = String::new();
        for (k, v) in &self.entries {
            let _ = writeln!(s, "# {k}: {v}");
        }
        s
    }

    /// A Markdown footer (one line per entry, as a small list).
    pub fn markdown_footer(&self) -> String {
        let mut s = String::from("\n<sub>Provenance: ");
        let parts: Vec<String> = self
            .entries
            .iter()
            .map(|(k, v)| format!("{k} = `{v}`"))
            .collect();
        s.push_str(&parts.join("; "));
        s.push_str("</sub>\n");
        s
    }

    /// The value recorded for `key`, if any.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

fn run(cmd: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(cmd).args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
        .filter(|s| !s.is_empty())
}

/// `HEAD`'s hash, with `-dirty` when the work tree has uncommitted changes to tracked files.
pub fn git_commit() -> String {
    let Some(head) = run("git", &["rev-parse", "--short=12", "HEAD"]) else {
        return "unknown (not a git checkout)".into();
    };
    let dirty = run("git", &["status", "--porcelain", "--untracked-files=no"]).is_some();
    if dirty {
        format!("{head}-dirty")
    } else {
        head
    }
}

fn utc_now() -> String {
    run("date", &["-u", "+%Y-%m-%dT%H:%M:%SZ"]).unwrap_or_else(|| "unknown".into())
}

/// The CPU's model name from `/proc/cpuinfo` (`unknown` elsewhere).
pub fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}

fn kernel() -> String {
    run("uname", &["-sr"]).unwrap_or_else(|| "unknown".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preamble_is_commented_and_holds_params() {
        let p = Provenance::collect("demo", &[("eps", "1e-3".into())]);
        let pre = p.csv_preamble();
        assert!(pre.lines().all(|l| l.starts_with("# ")));
        assert!(pre.contains("# param.eps: 1e-3"));
        assert!(pre.contains("# git_commit: "));
        assert_eq!(p.get("experiment"), Some("demo"));
        assert!(p.markdown_footer().contains("param.eps = `1e-3`"));
    }
}
