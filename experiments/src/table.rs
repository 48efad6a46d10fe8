//! A table's columns, listed once, rendering each row both as a CSV line and as a Markdown
//! table line.
//!
//! A column has a CSV form, a Markdown form, or both (each a header and a formatter). The CSV
//! shows the columns that have a CSV form, in list order; the Markdown table those that have a
//! Markdown form, in list order. Where the two orders differ, a quantity gets a CSV-only
//! column at its CSV place and a Markdown-only column at its Markdown place.

use std::fmt::Write as _;
use std::rc::Rc;

/// How a row's cell is written.
type Format<'a, R> = Rc<dyn Fn(&R) -> String + 'a>;

/// A header and how a row's cell is written under it.
struct Cell<'a, R> {
    header: &'a str,
    format: Format<'a, R>,
}

/// One column: its CSV form, its Markdown form, and the Markdown alignment.
struct Column<'a, R> {
    csv: Option<Cell<'a, R>>,
    markdown: Option<Cell<'a, R>>,
    right_aligned: bool,
}

/// The columns of a table of rows `R`, built column by column:
/// `Table::new().csv("eps", |r| ...).with_markdown("eps", |r| ...).markdown("pair", |r| ...)`.
pub struct Table<'a, R> {
    columns: Vec<Column<'a, R>>,
}

impl<R> Default for Table<'_, R> {
    fn default() -> Self {
        Table {
            columns: Vec::new(),
        }
    }
}

impl<'a, R> Table<'a, R> {
    /// A table without columns.
    pub fn new() -> Self {
        Self::default()
    }

    fn push(mut self, csv: Option<Cell<'a, R>>, markdown: Option<Cell<'a, R>>) -> Self {
        self.columns.push(Column {
            csv,
            markdown,
            right_aligned: false,
        });
        self
    }

    /// A new column, in the CSV (give it a Markdown form with [`Self::with_markdown`]).
    pub fn csv(self, header: &'a str, format: impl Fn(&R) -> String + 'a) -> Self {
        let format: Format<'a, R> = Rc::new(format);
        self.push(Some(Cell { header, format }), None)
    }

    /// A new column of the Markdown table only.
    pub fn markdown(self, header: &'a str, format: impl Fn(&R) -> String + 'a) -> Self {
        let format: Format<'a, R> = Rc::new(format);
        self.push(None, Some(Cell { header, format }))
    }

    /// Gives the last column a Markdown form with its own header and cell text.
    pub fn with_markdown(mut self, header: &'a str, format: impl Fn(&R) -> String + 'a) -> Self {
        let format: Format<'a, R> = Rc::new(format);
        self.last().markdown = Some(Cell { header, format });
        self
    }

    /// Gives the last column a Markdown form with its own header and the CSV's cell text.
    pub fn with_markdown_header(mut self, header: &'a str) -> Self {
        let last = self.last();
        let format = Rc::clone(&last.csv.as_ref().expect("a CSV column").format);
        last.markdown = Some(Cell { header, format });
        self
    }

    /// Right-aligns the last column in the Markdown table (`---:`).
    pub fn right(mut self) -> Self {
        self.last().right_aligned = true;
        self
    }

    fn last(&mut self) -> &mut Column<'a, R> {
        self.columns.last_mut().expect("a column to amend")
    }

    /// The CSV header line and one line per row (no provenance: the caller adds it).
    pub fn csv_text<'r>(&self, rows: impl IntoIterator<Item = &'r R>) -> String
    where
        R: 'r,
    {
        let cells: Vec<&Cell<R>> = self.columns.iter().filter_map(|c| c.csv.as_ref()).collect();
        let mut s = line(cells.iter().map(|c| c.header.to_owned()), ",", "", "");
        for r in rows {
            s += &line(cells.iter().map(|c| (c.format)(r)), ",", "", "");
        }
        s
    }

    /// The Markdown table: header, alignment line and one line per row.
    pub fn markdown_text<'r>(&self, rows: impl IntoIterator<Item = &'r R>) -> String
    where
        R: 'r,
    {
        let shown: Vec<(&Cell<R>, bool)> = self
            .columns
            .iter()
            .filter_map(|c| c.markdown.as_ref().map(|m| (m, c.right_aligned)))
            .collect();
        let mut s = line(
            shown.iter().map(|(c, _)| c.header.to_owned()),
            " | ",
            "| ",
            " |",
        );
        let align = shown
            .iter()
            .map(|&(_, right)| if right { "---:" } else { "---" }.to_owned());
        s += &line(align, " | ", "| ", " |");
        for r in rows {
            s += &line(shown.iter().map(|(c, _)| (c.format)(r)), " | ", "| ", " |");
        }
        s
    }
}

/// `cells` joined by `separator` between `open` and `close`, and a newline.
fn line(cells: impl Iterator<Item = String>, separator: &str, open: &str, close: &str) -> String {
    let mut s = String::from(open);
    for (i, c) in cells.enumerate() {
        if i > 0 {
            s.push_str(separator);
        }
        s.push_str(&c);
    }
    let _ = writeln!(s, "{close}");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Row {
        pair: (&'static str, &'static str),
        eps: f64,
        us: f64,
        misses: usize,
    }

    fn table() -> Table<'static, Row> {
        Table::new()
            .csv("a", |r: &Row| r.pair.0.into())
            .csv("b", |r| r.pair.1.into())
            .markdown("pair", |r| format!("{}-{}", r.pair.0, r.pair.1))
            .csv("eps", |r| format!("{:e}", r.eps))
            .with_markdown("eps", |r| format!("{:.0e}", r.eps))
            .csv("us", |r| format!("{:.1}", r.us))
            .with_markdown_header("time (us)")
            .right()
            .csv("misses", |r| r.misses.to_string())
    }

    #[test]
    fn one_row_renders_into_csv_and_markdown() {
        let rows = [Row {
            pair: ("pawn", "cup"),
            eps: 1e-4,
            us: 12.34,
            misses: 0,
        }];
        assert_eq!(
            table().csv_text(&rows),
            "a,b,eps,us,misses\npawn,cup,1e-4,12.3,0\n"
        );
        assert_eq!(
            table().markdown_text(&rows),
            "| pair | eps | time (us) |\n| --- | --- | ---: |\n| pawn-cup | 1e-4 | 12.3 |\n"
        );
    }

    #[test]
    fn no_rows_leaves_the_headers() {
        assert_eq!(table().csv_text(&[]), "a,b,eps,us,misses\n");
        assert_eq!(table().markdown_text(&[]).lines().count(), 2);
    }
}
