//! A [`CaseRecord`] as a raw row of `verify crosscheck --shard` ([`crate::shard`]): every
//! field, the pose and the judgement flattened into columns.

use super::criterion::{Judgement, Verdict};
use super::poses::PoseKind;
use super::record::{CaseRecord, Check};
use crate::queries::PoseSpec;
use crate::shard::{Cells, Field, Record, Scalar};

/// Field and scalar impls for a fieldless enum written by its `name()`.
macro_rules! named_enum {
    ($t:ty, $all:expr) => {
        impl Field for $t {
            fn text(&self) -> String {
                self.name().to_owned()
            }
            fn parse(cell: &str) -> Result<Self, String> {
                $all.into_iter()
                    .find(|v: &$t| v.name() == cell)
                    .ok_or_else(|| format!("'{cell}' is not a {}", stringify!($t)))
            }
        }
        impl Scalar for $t {}
    };
}

named_enum!(
    Check,
    [
        Check::Fcl,
        Check::Cgal,
        Check::Gjk,
        Check::Penetration,
        Check::Occt
    ]
);
named_enum!(PoseKind, PoseKind::ALL);
named_enum!(
    Verdict,
    [Verdict::Passed, Verdict::Explained, Verdict::Failed]
);

impl Record for CaseRecord {
    fn columns() -> Vec<&'static str> {
        vec![
            "check",
            "a",
            "b",
            "eps",
            "index",
            "kind",
            "translation",
            "rotation",
            "lower",
            "upper",
            "value",
            "overlap",
            "baseline",
            "mesh_bounds",
            "verdict",
            "separation",
            "usage",
            "note",
            "query_time",
            "baseline_time",
        ]
    }

    fn cells(&self) -> Vec<String> {
        vec![
            self.check.text(),
            self.a.text(),
            self.b.text(),
            self.eps.text(),
            self.index.text(),
            self.kind.text(),
            self.pose.translation.to_vec().text(),
            self.pose.rotation.to_vec().text(),
            self.lower.text(),
            self.upper.text(),
            self.value.text(),
            self.overlap.text(),
            self.baseline.text(),
            self.mesh_bounds.text(),
            self.judgement.verdict.text(),
            self.judgement.separation.text(),
            self.judgement.usage.text(),
            self.note.text(),
            self.query_time.text(),
            self.baseline_time.text(),
        ]
    }

    fn from_cells(line: &Cells) -> Result<Self, String> {
        let array = |name: &str| -> Result<Vec<f64>, String> { line.get(name) };
        let translation: [f64; 3] = array("translation")?
            .try_into()
            .map_err(|_| "`translation` needs 3 numbers".to_owned())?;
        let rotation: [f64; 4] = array("rotation")?
            .try_into()
            .map_err(|_| "`rotation` needs 4 numbers".to_owned())?;
        Ok(CaseRecord {
            check: line.get("check")?,
            a: line.get("a")?,
            b: line.get("b")?,
            eps: line.get("eps")?,
            index: line.get("index")?,
            kind: line.get("kind")?,
            pose: PoseSpec {
                translation,
                rotation,
            },
            lower: line.get("lower")?,
            upper: line.get("upper")?,
            value: line.get("value")?,
            overlap: line.get("overlap")?,
            baseline: line.get("baseline")?,
            mesh_bounds: line.get("mesh_bounds")?,
            judgement: Judgement {
                verdict: line.get("verdict")?,
                separation: line.get("separation")?,
                usage: line.get("usage")?,
            },
            note: line.get("note")?,
            query_time: line.get("query_time")?,
            baseline_time: line.get("baseline_time")?,
        })
    }
}
