//! How one value of a raw row is written as a CSV cell and read back, losslessly: floats in
//! Rust's shortest round-trip form (`{:e}`, with `NaN` and `inf`), so that a merge computes
//! the same medians, ratios and tables from the shards' rows as the unsharded run did from
//! its own values.
//!
//! A cell never holds `,` (the CSV's separator), a list never an item with `;` (the list's
//! separator), a pair never a part with `:`: texts escape these (and `%`, `~`, `!`, quotes
//! and line breaks) as `%XX`. `~` is "none" of an `Option`, `!` opens the error of a `Result`.

use std::sync::Mutex;
use std::time::Duration;

/// A value of a raw row: written as one CSV cell and parsed back to the same value.
pub trait Field: Sized {
    fn text(&self) -> String;
    fn parse(cell: &str) -> Result<Self, String>;
}

/// A field whose text holds none of `,`, `;`, `:` and is never `~`: an item of a list, a
/// part of a pair, the value of an `Option`.
pub trait Scalar: Field {}

/// A field whose text holds neither `,` nor `;`: an item of a list (a scalar, or a pair of
/// scalars).
pub trait Item: Field {}

/// The text of an `Option`'s `None`.
const NONE: &str = "~";

/// Characters a text cell escapes as `%XX`.
const ESCAPED: [char; 10] = ['%', ',', ';', ':', '~', '!', '"', '\n', '\r', '\''];

/// What opens the text of a `Result`'s error (a scalar's text never starts with it).
const ERR: char = '!';

/// `s` with the separators escaped.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if ESCAPED.contains(&c) {
            out.push_str(&format!("%{:02X}", c as u32));
        } else {
            out.push(c);
        }
    }
    out
}

/// The text [`escape`] was given.
fn unescape(s: &str) -> Result<String, String> {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(at) = rest.find('%') {
        out.push_str(&rest[..at]);
        let code = rest
            .get(at + 1..at + 3)
            .and_then(|h| u8::from_str_radix(h, 16).ok())
            .ok_or_else(|| format!("'{s}': a bad %-escape"))?;
        out.push(char::from(code));
        rest = &rest[at + 3..];
    }
    out.push_str(rest);
    Ok(out)
}

fn bad<T>(cell: &str, what: &str) -> Result<T, String> {
    Err(format!("'{cell}' is not {what}"))
}

impl Field for f64 {
    fn text(&self) -> String {
        // `{:e}` is the shortest text that parses back to the same double (and keeps the
        // exponent, so 1e-300 stays short); NaN and inf as Rust writes and parses them.
        format!("{self:e}")
    }
    fn parse(cell: &str) -> Result<Self, String> {
        cell.parse().or_else(|_| bad(cell, "a number"))
    }
}

macro_rules! integer_field {
    ($($t:ty),*) => {$(
        impl Field for $t {
            fn text(&self) -> String {
                self.to_string()
            }
            fn parse(cell: &str) -> Result<Self, String> {
                cell.parse().or_else(|_| bad(cell, concat!("an integer (", stringify!($t), ")")))
            }
        }
    )*};
}
integer_field!(usize, u64, u32, i32);

impl Field for bool {
    fn text(&self) -> String {
        self.to_string()
    }
    fn parse(cell: &str) -> Result<Self, String> {
        cell.parse().or_else(|_| bad(cell, "true or false"))
    }
}

impl Field for String {
    fn text(&self) -> String {
        escape(self)
    }
    fn parse(cell: &str) -> Result<Self, String> {
        unescape(cell)
    }
}

/// Texts read back as `&'static str` (model names, variants, notes): each distinct text is
/// leaked once, so a merge holds as many as a run has names, however many rows it reads.
static INTERNED: Mutex<Vec<&'static str>> = Mutex::new(Vec::new());

impl Field for &'static str {
    fn text(&self) -> String {
        escape(self)
    }
    fn parse(cell: &str) -> Result<Self, String> {
        let s = unescape(cell)?;
        let mut known = INTERNED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = known.iter().find(|k| **k == s) {
            return Ok(k);
        }
        let leaked: &'static str = Box::leak(s.into_boxed_str());
        known.push(leaked);
        Ok(leaked)
    }
}

impl Field for Duration {
    /// Whole nanoseconds (a `Duration`'s resolution).
    fn text(&self) -> String {
        self.as_nanos().to_string()
    }
    fn parse(cell: &str) -> Result<Self, String> {
        let ns: u128 = cell.parse().or_else(|_| bad(cell, "nanoseconds"))?;
        let secs = u64::try_from(ns / 1_000_000_000).or_else(|_| bad(cell, "a duration"))?;
        Ok(Duration::new(secs, (ns % 1_000_000_000) as u32))
    }
}

macro_rules! scalar {
    ($($t:ty),*) => {$( impl Scalar for $t {} impl Item for $t {} )*};
}
scalar!(
    f64,
    usize,
    u64,
    u32,
    i32,
    bool,
    String,
    &'static str,
    Duration
);

impl<T: Scalar> Field for Option<T> {
    fn text(&self) -> String {
        self.as_ref().map_or_else(|| NONE.to_owned(), Field::text)
    }
    fn parse(cell: &str) -> Result<Self, String> {
        if cell == NONE {
            Ok(None)
        } else {
            T::parse(cell).map(Some)
        }
    }
}
impl<T: Scalar> Item for Option<T> {}

/// A value, or why there is none (a peer that did not run): the value's text, or `!` and
/// the reason.
impl<T: Scalar> Field for Result<T, String> {
    fn text(&self) -> String {
        match self {
            Ok(v) => v.text(),
            Err(e) => format!("{ERR}{}", escape(e)),
        }
    }
    fn parse(cell: &str) -> Result<Self, String> {
        match cell.strip_prefix(ERR) {
            Some(e) => unescape(e).map(Err),
            None => T::parse(cell).map(Ok),
        }
    }
}

impl<A: Scalar, B: Scalar> Field for (A, B) {
    fn text(&self) -> String {
        format!("{}:{}", self.0.text(), self.1.text())
    }
    fn parse(cell: &str) -> Result<Self, String> {
        let (a, b) = cell
            .split_once(':')
            .ok_or_else(|| format!("'{cell}' is not a pair a:b"))?;
        Ok((A::parse(a)?, B::parse(b)?))
    }
}
impl<A: Scalar, B: Scalar> Item for (A, B) {}

impl<T: Item> Field for Vec<T> {
    /// Items joined by `;` (the empty list: an empty cell).
    fn text(&self) -> String {
        self.iter().map(Field::text).collect::<Vec<_>>().join(";")
    }
    fn parse(cell: &str) -> Result<Self, String> {
        if cell.is_empty() {
            return Ok(Vec::new());
        }
        cell.split(';').map(T::parse).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round<T: Field + PartialEq + std::fmt::Debug>(v: T) {
        let t = v.text();
        assert!(!t.contains(','), "{t}");
        assert_eq!(T::parse(&t).unwrap(), v, "{t}");
    }

    #[test]
    fn values_come_back_bit_for_bit() {
        for x in [
            0.1,
            -0.0,
            1e-300,
            5e-324,
            f64::MAX,
            1.0 / 3.0,
            f64::INFINITY,
        ] {
            let back = f64::parse(&x.text()).unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x}");
        }
        assert!(f64::parse(&f64::NAN.text()).unwrap().is_nan());
        round(12usize);
        round(-3i32);
        round(true);
        round(String::from(
            "revdist distance a b --pose-b '{\"t\": [1, 2]}'; 100%: ~x",
        ));
        round(Some(2.5f64));
        round(None::<usize>);
        round(vec![(1.0f64, 2.0f64), (3.0, 4.0)]);
        round(Vec::<f64>::new());
        round(vec![Some(1usize), None]);
        round(Duration::new(3, 141_592_653));
        round(Ok::<f64, String>(2.5));
        round(Err::<f64, String>(
            "coal missing: run scripts/deps.sh!".into(),
        ));
        round(Ok::<String, String>("!not an error".into()));
        let s: &'static str = Field::parse("pawn_ff").unwrap();
        let t: &'static str = Field::parse("pawn_ff").unwrap();
        assert!(std::ptr::eq(s, t), "interned once");
    }

    #[test]
    fn bad_cells_are_errors() {
        assert!(f64::parse("x").is_err());
        assert!(usize::parse("-1").is_err());
        assert!(String::parse("50%").is_err());
        assert!(<(f64, f64)>::parse("1").is_err());
        assert!(Vec::<f64>::parse("1;;2").is_err());
    }
}
