//! Progress bars for long steps (indicatif). They draw on stderr only when it is a terminal,
//! so logs of scripted runs stay clean.

use indicatif::{ProgressBar, ProgressStyle};

/// A bar over `len` items labelled `label`, with elapsed time and an estimate of what is left.
pub fn bar(len: u64, label: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    let style = ProgressStyle::with_template(
        "{prefix:>14} [{bar:32}] {pos}/{len} {msg} ({elapsed}, ~{eta} left)",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    pb.set_style(style);
    pb.set_prefix(label.to_string());
    pb
}
