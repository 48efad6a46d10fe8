//! The rows of the mesh and convex tables, their raw form for `--shard`, and the fastest peer
//! of a row.

use crate::shard::{Field, Scalar};

/// One method's numbers in a row: median query time, build time, memory.
#[derive(Clone, Copy, Default)]
pub(super) struct Timed {
    pub(super) us: f64,
    pub(super) build_ms: f64,
    pub(super) bytes: usize,
}

/// One row of the mesh table.
pub(super) struct Row {
    pub(super) pair: String,
    pub(super) eps: f64,
    pub(super) poses: usize,
    pub(super) parry_poses: usize,
    pub(super) tris: usize,
    pub(super) h_sum: f64,
    pub(super) rev: Timed,
    pub(super) fcl_obbrss: Timed,
    pub(super) fcl_rss: Timed,
    /// coal `BVHModel<OBBRSS>`, or why it did not run.
    pub(super) coal: Result<Timed, String>,
    pub(super) parry: Timed,
    /// Hook for OpenCASCADE's median time per query on the true surfaces (the peers-occt work,
    /// `verify/src/baselines/occt*`): `None` until it is wired in; counted among the peers of
    /// [`Row::fastest`] when present.
    pub(super) occt_us: Option<f64>,
    pub(super) max_width: f64,
    pub(super) violations: usize,
}

/// A [`Timed`] in a raw row: `us/build_ms/bytes`.
impl Field for Timed {
    fn text(&self) -> String {
        format!(
            "{}/{}/{}",
            self.us.text(),
            self.build_ms.text(),
            self.bytes.text()
        )
    }
    fn parse(cell: &str) -> Result<Self, String> {
        let parts: Vec<&str> = cell.split('/').collect();
        match parts[..] {
            [us, build_ms, bytes] => Ok(Timed {
                us: Field::parse(us)?,
                build_ms: Field::parse(build_ms)?,
                bytes: Field::parse(bytes)?,
            }),
            _ => Err(format!("'{cell}' is not us/build_ms/bytes")),
        }
    }
}
impl Scalar for Timed {}

crate::shard_record!(Row {
    pair,
    eps,
    poses,
    parry_poses,
    tris,
    h_sum,
    rev,
    fcl_obbrss,
    fcl_rss,
    coal,
    parry,
    occt_us,
    max_width,
    violations,
});

impl Row {
    /// The peers' median times by name (those that ran).
    pub(super) fn peers(&self) -> Vec<(&'static str, f64)> {
        let mut v = vec![
            ("FCL OBBRSS", self.fcl_obbrss.us),
            ("FCL RSS", self.fcl_rss.us),
            ("parry3d", self.parry.us),
        ];
        if let Ok(c) = &self.coal {
            v.push(("coal OBBRSS", c.us));
        }
        if let Some(t) = self.occt_us {
            v.push(("OCCT", t));
        }
        v
    }
    /// The fastest peer of the row and its median.
    pub(super) fn fastest(&self) -> (&'static str, f64) {
        self.peers()
            .into_iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("FCL always runs")
    }
    /// Fastest peer's median over revdist's (> 1: revdist is faster).
    pub(super) fn ratio(&self) -> f64 {
        self.fastest().1 / self.rev.us
    }
}

/// One row of the convex table.
pub(super) struct ConvexRow {
    pub(super) pair: String,
    pub(super) poses: usize,
    pub(super) rev_us: f64,
    /// revdist with `QueryOptions { convex_path: true, .. }` (off by default today; the convex
    /// work makes it the default).
    pub(super) rev_convex_us: Option<f64>,
    pub(super) coal: Result<f64, String>,
    pub(super) parry_us: f64,
    /// parry3d's largest distance outside revdist's certified interval.
    pub(super) parry_excess: f64,
    pub(super) max_width: f64,
    pub(super) violations: usize,
}

crate::shard_record!(ConvexRow {
    pair,
    poses,
    rev_us,
    rev_convex_us,
    coal,
    parry_us,
    parry_excess,
    max_width,
    violations,
});

impl ConvexRow {
    pub(super) fn fastest(&self) -> (&'static str, f64) {
        match &self.coal {
            Ok(c) if *c < self.parry_us => ("coal GJK", *c),
            _ => ("parry3d", self.parry_us),
        }
    }
}
