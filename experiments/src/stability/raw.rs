//! A [`Sample`] as a raw row of `stability --shard` (`verify::shard`): every field, the key's
//! three flattened into columns.

use super::{Key, Level, Sample};
use verify::shard::{Cells, Field, Record, Scalar};

impl Field for Level {
    fn text(&self) -> String {
        self.name().to_owned()
    }
    fn parse(cell: &str) -> Result<Self, String> {
        [Level::Circle, Level::Solid]
            .into_iter()
            .find(|l| l.name() == cell)
            .ok_or_else(|| format!("'{cell}' is not a level"))
    }
}
impl Scalar for Level {}

impl Record for Sample {
    fn columns() -> Vec<&'static str> {
        vec![
            "level",
            "family",
            "delta",
            "variant",
            "seed",
            "exact",
            "value",
            "abs_err",
            "rel_err",
            "bound",
            "lower",
            "upper",
            "certified",
            "seconds",
            "reproducer",
        ]
    }

    fn cells(&self) -> Vec<String> {
        vec![
            self.key.level.text(),
            self.key.family.text(),
            self.key.delta.text(),
            self.variant.text(),
            self.seed.text(),
            self.exact.text(),
            self.value.text(),
            self.abs_err.text(),
            self.rel_err.text(),
            self.bound.text(),
            self.lower.text(),
            self.upper.text(),
            self.certified.text(),
            self.seconds.text(),
            self.reproducer.text(),
        ]
    }

    fn from_cells(line: &Cells) -> Result<Self, String> {
        Ok(Sample {
            key: Key {
                level: line.get("level")?,
                family: line.get("family")?,
                delta: line.get("delta")?,
            },
            variant: line.get("variant")?,
            seed: line.get("seed")?,
            exact: line.get("exact")?,
            value: line.get("value")?,
            abs_err: line.get("abs_err")?,
            rel_err: line.get("rel_err")?,
            bound: line.get("bound")?,
            lower: line.get("lower")?,
            upper: line.get("upper")?,
            certified: line.get("certified")?,
            seconds: line.get("seconds")?,
            reproducer: line.get("reproducer")?,
        })
    }
}
