//! `revdist distance --batch`: JSON lines in, exactly one JSON line out per input line.
//!
//! The contract (README, "Batch mode"):
//! * output line `N` answers input line `N`, in order, and carries `"line": N`: results and
//!   errors alike. Blank lines, lines that are not UTF-8 and lines that are not a valid
//!   request get an error line of their own and never stop the batch; a UTF-8 byte-order
//!   mark at the start of the input is an encoding marker and is skipped.
//! * `--max-time-ms` bounds every query: a query that runs out answers with the bounds it
//!   reached, flagged `"budget_exhausted": true`.
//! * exit status 0 when every line succeeded, 1 when some line failed (after every line
//!   ran), 2 for a usage error (no input, bad flags).
//!
//! Pipeline: worker threads take the input one line at a time (each reads the next line
//! under a lock, so a slow query holds only its own worker), parse it, build each shape once
//! (shared cache) and run the query; the worker that completes the next line due writes it,
//! and any answers after it that are ready, in input order. No thread waits on another
//! except for a shape being built, or when the workers run [`MAX_AHEAD`] lines ahead of a
//! slow line, so memory stays bounded however long the input.

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::sync::{Condvar, Mutex};

use revdist::query::QueryOptions;

use super::SolidCache;
use crate::CmdResult;

/// How many lines the reader may run ahead of the writer.
const MAX_AHEAD: usize = 1 << 16;

/// The UTF-8 byte-order mark.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// What every batch line shares.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// eps of lines that give none.
    pub default_eps: f64,
    /// Query options of lines that override nothing.
    pub opts: QueryOptions,
    /// Add `"time_us"` to each result.
    pub timings: bool,
    /// Add the signed distance and penetration depth (`--signed`) to lines that give no
    /// `"signed"` of their own.
    pub signed: bool,
}

/// Some lines of a batch failed (exit status 1); the others were answered.
#[derive(Debug, thiserror::Error)]
#[error("{failed} of {total} batch lines failed (see their \"error\" lines)")]
pub struct LinesFailed {
    pub failed: usize,
    pub total: usize,
}

/// One input line: its 1-based number and its text, or why it has none.
type Job = (usize, Result<String, String>);

/// What a batch runs per line: the output line for input line `N` (its text, or why it has
/// none), or that line's error message. `revdist distance` and `revdist toi` each give theirs.
pub type Answer<'a> =
    dyn Fn(usize, Result<&str, String>, &SolidCache) -> Result<String, String> + Sync + 'a;

/// Runs the batch in `path` ("-" for stdin) on `threads` workers, writing to stdout.
pub fn run(path: &str, threads: usize, answer: &Answer) -> CmdResult {
    let input: Box<dyn Read + Send> = if path == "-" {
        Box::new(std::io::stdin())
    } else {
        if std::path::Path::new(path).is_dir() {
            return Err(format!("'{path}' is a directory, not a batch file").into());
        }
        Box::new(std::fs::File::open(path).map_err(|e| format!("cannot open '{path}': {e}"))?)
    };
    // Standard output is line-buffered; the writer flushes once per burst of answers.
    let mut out = std::io::BufWriter::new(std::io::stdout());
    let (total, failed) = run_with(input, &mut out, threads, answer)?;
    if failed > 0 {
        return Err(Box::new(LinesFailed { failed, total }));
    }
    Ok(())
}

/// The input, read one line at a time by whichever worker is free.
struct Lines {
    reader: BufReader<Box<dyn Read + Send>>,
    /// Number of the last line read (1-based).
    read: usize,
    /// An I/O error ended the input (not bad content): the lines before it are answered.
    error: Option<String>,
}

/// Answers waiting for the lines before them, and what has been written.
struct Output<'a> {
    out: &'a mut (dyn Write + Send),
    pending: BTreeMap<usize, Result<String, String>>,
    /// Number of the next line to write.
    next: usize,
    failed: usize,
    error: Option<std::io::Error>,
}

impl Output<'_> {
    /// Files the answer of line `number` and writes every answer now due, in order.
    fn file(&mut self, number: usize, answer: Result<String, String>) {
        self.pending.insert(number, answer);
        while let Some(answer) = self.pending.remove(&self.next) {
            let text = answer.unwrap_or_else(|error| {
                self.failed += 1;
                serde_json::json!({ "line": self.next, "error": error }).to_string()
            });
            if self.error.is_none() {
                if let Err(e) = writeln!(self.out, "{text}") {
                    self.error = Some(e);
                }
            }
            self.next += 1;
        }
        if self.pending.is_empty() && self.error.is_none() {
            // Caught up: one write per burst of answers.
            if let Err(e) = self.out.flush() {
                self.error = Some(e);
            }
        }
    }
}

/// The batch from `input` to `out`; returns (lines, failed lines). An input that cannot be
/// read further (an I/O error, not bad content) ends the batch after the lines before it
/// were answered, with that error.
pub fn run_with(
    input: Box<dyn Read + Send>,
    out: &mut (dyn Write + Send),
    threads: usize,
    answer: &Answer,
) -> Result<(usize, usize), Box<dyn std::error::Error>> {
    let lines = Mutex::new(Lines {
        reader: BufReader::new(input),
        read: 0,
        error: None,
    });
    let output = Mutex::new(Output {
        out,
        pending: BTreeMap::new(),
        next: 1,
        failed: 0,
        error: None,
    });
    let caught_up = Condvar::new();
    let cache = SolidCache::default();
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1) {
            scope.spawn(|| work(&lines, &output, &caught_up, answer, &cache));
        }
    });
    let lines = lines.into_inner().unwrap_or_else(|e| e.into_inner());
    let mut output = output.into_inner().unwrap_or_else(|e| e.into_inner());
    if let Some(e) = output.error.take() {
        return Err(e.into());
    }
    output.out.flush()?;
    if let Some(e) = lines.error {
        return Err(e.into());
    }
    Ok((output.next - 1, output.failed))
}

/// A worker: reads the next line, answers it and files the answer, until the input ends.
fn work(
    lines: &Mutex<Lines>,
    output: &Mutex<Output>,
    caught_up: &Condvar,
    answer: &Answer,
    cache: &SolidCache,
) {
    loop {
        let Some((number, line)) = next_line(lines) else {
            return;
        };
        // Stay within MAX_AHEAD lines of the oldest unwritten one.
        {
            let mut o = output.lock().unwrap_or_else(|e| e.into_inner());
            while number > o.next + MAX_AHEAD {
                o = caught_up.wait(o).unwrap_or_else(|e| e.into_inner());
            }
        }
        let text = answer(number, line.as_deref().map_err(Clone::clone), cache);
        let mut o = output.lock().unwrap_or_else(|e| e.into_inner());
        let before = o.next;
        o.file(number, text);
        if o.next > before {
            caught_up.notify_all();
        }
    }
}

/// The next numbered line of the input (see the module doc for blank, non-UTF-8 and
/// byte-order-mark lines), or `None` at its end or after a read error (kept in `lines`).
fn next_line(lines: &Mutex<Lines>) -> Option<Job> {
    let mut l = lines.lock().unwrap_or_else(|e| e.into_inner());
    if l.error.is_some() {
        return None;
    }
    let mut bytes = Vec::new();
    let number = l.read + 1;
    match l.reader.read_until(b'\n', &mut bytes) {
        Ok(0) => return None,
        Ok(_) => l.read = number,
        Err(e) => {
            l.error = Some(format!(
                "reading the batch input after line {}: {e}",
                number - 1
            ));
            return None;
        }
    }
    drop(l);
    if bytes.last() == Some(&b'\n') {
        bytes.pop();
    }
    if bytes.last() == Some(&b'\r') {
        bytes.pop();
    }
    let text = if number == 1 && bytes.starts_with(BOM) {
        &bytes[BOM.len()..]
    } else {
        &bytes[..]
    };
    let job = match std::str::from_utf8(text) {
        Err(e) => Err(format!(
            "line is not valid UTF-8 (byte 0x{:02X} at column {})",
            text[e.valid_up_to()],
            e.valid_up_to() + 1
        )),
        Ok(t) if t.trim().is_empty() => Err("blank line: no request".to_string()),
        Ok(t) => Ok(t.to_string()),
    };
    Some((number, job))
}
