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
//! Pipeline: a reader thread splits the input into lines; worker threads take lines one at a
//! time from a shared queue (a slow query holds only its own worker), parse them, build each
//! shape once (shared cache) and run the query; the calling thread writes the answers back in
//! input order. The reader stays at most [`MAX_AHEAD`] lines ahead of the writer, so memory
//! stays bounded however long the input.

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::sync::mpsc::{channel, sync_channel, Receiver};
use std::sync::{Arc, Condvar, Mutex};

use revdist::query::QueryOptions;

use super::{answer_line, SolidCache};
use crate::CmdResult;

/// How many lines the reader may run ahead of the writer.
const MAX_AHEAD: usize = 1 << 16;

/// Lines waiting in the queue between the reader and the workers.
const QUEUE_DEPTH: usize = 256;

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
    /// Worker threads.
    pub threads: usize,
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

/// Runs the batch in `path` ("-" for stdin), writing to stdout.
pub fn run(path: &str, settings: &Settings) -> CmdResult {
    let input: Box<dyn Read + Send> = if path == "-" {
        Box::new(std::io::stdin())
    } else {
        if std::path::Path::new(path).is_dir() {
            return Err(format!("'{path}' is a directory, not a batch file").into());
        }
        Box::new(std::fs::File::open(path).map_err(|e| format!("cannot open '{path}': {e}"))?)
    };
    let stdout = std::io::stdout();
    let (total, failed) = run_with(input, &mut stdout.lock(), settings)?;
    if failed > 0 {
        return Err(Box::new(LinesFailed { failed, total }));
    }
    Ok(())
}

/// Lines written so far, and a signal for the reader waiting to run ahead.
type Progress = Arc<(Mutex<usize>, Condvar)>;

/// The batch from `input` to `out`; returns (lines, failed lines). An input that cannot be
/// read further (an I/O error, not bad content) ends the batch after the lines before it
/// were answered, with that error.
pub fn run_with(
    input: Box<dyn Read + Send>,
    out: &mut dyn Write,
    settings: &Settings,
) -> Result<(usize, usize), Box<dyn std::error::Error>> {
    let written: Progress = Arc::new((Mutex::new(0), Condvar::new()));
    let (job_tx, job_rx) = sync_channel::<Job>(QUEUE_DEPTH);
    let (answer_tx, answer_rx) = channel::<(usize, Result<String, String>)>();
    let cache = SolidCache::default();
    let jobs = Mutex::new(job_rx);
    std::thread::scope(|scope| {
        let reader = {
            let written = Arc::clone(&written);
            scope.spawn(move || read_lines(input, &job_tx, &written))
        };
        for _ in 0..settings.threads.max(1) {
            let (jobs, answers, cache) = (&jobs, answer_tx.clone(), &cache);
            scope.spawn(move || work(jobs, &answers, settings, cache));
        }
        drop(answer_tx);
        let counts = write_in_order(&answer_rx, out, &written);
        let read = reader
            .join()
            .unwrap_or_else(|_| Err("the input reader stopped unexpectedly".into()));
        let counts = counts?;
        read?;
        Ok(counts)
    })
}

/// Splits `input` into numbered lines for the workers (see the module doc for blank,
/// non-UTF-8 and byte-order-mark lines); waits while [`MAX_AHEAD`] lines are unwritten.
fn read_lines(
    input: Box<dyn Read + Send>,
    jobs: &std::sync::mpsc::SyncSender<Job>,
    written: &Progress,
) -> Result<(), String> {
    let mut reader = BufReader::new(input);
    let mut bytes = Vec::new();
    for number in 1.. {
        bytes.clear();
        let n = reader
            .read_until(b'\n', &mut bytes)
            .map_err(|e| format!("reading the batch input after line {}: {e}", number - 1))?;
        if n == 0 {
            return Ok(());
        }
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
        {
            let (lock, signal) = &**written;
            let mut done = lock.lock().unwrap_or_else(|e| e.into_inner());
            while number > *done + MAX_AHEAD {
                done = signal.wait(done).unwrap_or_else(|e| e.into_inner());
            }
        }
        if jobs.send((number, job)).is_err() {
            return Ok(());
        }
    }
    Ok(())
}

/// A worker: takes one line at a time until the queue closes.
fn work(
    jobs: &Mutex<Receiver<Job>>,
    answers: &std::sync::mpsc::Sender<(usize, Result<String, String>)>,
    settings: &Settings,
    cache: &SolidCache,
) {
    loop {
        let next = jobs.lock().unwrap_or_else(|e| e.into_inner()).recv();
        let Ok((number, line)) = next else { return };
        let answer = answer_line(
            number,
            line.as_deref().map_err(Clone::clone),
            settings,
            cache,
        );
        if answers.send((number, answer)).is_err() {
            return;
        }
    }
}

/// Writes the answers in input order as they arrive; returns (lines, failed lines).
fn write_in_order(
    answers: &Receiver<(usize, Result<String, String>)>,
    out: &mut dyn Write,
    written: &Progress,
) -> Result<(usize, usize), std::io::Error> {
    let mut pending = BTreeMap::new();
    let (mut next, mut failed) = (1usize, 0usize);
    for (number, answer) in answers {
        pending.insert(number, answer);
        while let Some(answer) = pending.remove(&next) {
            let text = answer.unwrap_or_else(|error| {
                failed += 1;
                serde_json::json!({ "line": next, "error": error }).to_string()
            });
            writeln!(out, "{text}")?;
            next += 1;
        }
        out.flush()?;
        let (lock, signal) = &**written;
        *lock.lock().unwrap_or_else(|e| e.into_inner()) = next - 1;
        signal.notify_all();
    }
    Ok((next - 1, failed))
}
