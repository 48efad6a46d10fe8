//! The agreement criterion between revdist's certified interval and a mesh baseline's distance
//! (see the module doc of [`super`] for the derivation).

/// Rounding slack of a comparison, relative to the configuration scale `1 + |t| + size_a +
/// size_b`. FCL's mesh distance is exact for the meshes up to ~1e-16 relative (notes §2) but
/// it applies the pose to the vertices in double (a few roundings of values of the scale);
/// revdist's interval already carries its own rounding slack, and the meshes' bounds carry the
/// rounding of their vertices. 1e-12 covers thousands of such roundings and is still 1e-7 of
/// the smallest mesh bound in use (1e-5).
pub const SLACK_REL: f64 = 1e-12;

/// What a baseline says: its distance and the certified bounds of the meshes it used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Baseline {
    /// Distance between the meshes (or hulls); 0 when they intersect.
    pub distance: f64,
    /// `h_a + h_b`: sum of the meshes' certified two-sided Hausdorff bounds.
    pub mesh_bounds: f64,
    /// Extra slack for this baseline's own accuracy (0 for exact ones), plus rounding.
    pub slack: f64,
}

impl Baseline {
    /// The interval the baseline certifies for the distance between the true surfaces (or,
    /// for convex hulls, between the true convex solids): `d ± (h_a + h_b)`, clipped at 0.
    pub fn interval(&self) -> (f64, f64) {
        let w = self.mesh_bounds + self.slack;
        ((self.distance - w).max(0.0), self.distance + w)
    }
}

/// revdist's answer for a pair of solids.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Certified {
    pub lower: f64,
    pub upper: f64,
    /// Certified overlap or nesting of the solids (`lower = upper = 0`).
    pub overlap: bool,
}

/// Outcome of one comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Verdict {
    /// The intervals intersect.
    Passed,
    /// They do not, but a certified semantic difference accounts for it (solids that nest or
    /// intersect while their surfaces are apart: the solids' distance is 0, the surfaces'
    /// is not).
    Explained,
    /// A contradiction: at least one side's certificate is wrong.
    Failed,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Passed => "passed",
            Verdict::Explained => "explained",
            Verdict::Failed => "failed",
        }
    }
}

/// The comparison of one case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Judgement {
    pub verdict: Verdict,
    /// How far apart the two intervals are (> 0: disjoint by that much; <= 0: they intersect
    /// and `-separation` is the smallest shift that would separate them).
    pub separation: f64,
    /// `|revdist value - baseline distance| / (h_a + h_b + revdist width)`: the fraction of
    /// the combined tolerance a case uses (can exceed 1 only for explained or failed cases,
    /// or through the clipping at 0).
    pub usage: f64,
}

/// Judges a case. `solids_meet` is called only when the intervals are disjoint with revdist
/// below the baseline; it must return `true` only with a certificate that the true solids
/// share a point (then their distance is 0 whatever the surfaces' distance is).
pub fn judge(
    rev: Certified,
    value: f64,
    base: Baseline,
    solids_meet: impl FnOnce() -> bool,
) -> Judgement {
    let (lo, hi) = base.interval();
    let separation = (rev.lower - hi).max(lo - rev.upper);
    let tol = base.mesh_bounds + (rev.upper - rev.lower) + base.slack;
    let usage = if tol > 0.0 {
        (value - base.distance).abs() / tol
    } else {
        0.0
    };
    let verdict = if separation <= 0.0 {
        Verdict::Passed
    } else if lo > rev.upper && rev.lower == 0.0 && solids_meet() {
        // revdist says 0 (solids meet), the meshes' surfaces are apart: nesting.
        Verdict::Explained
    } else {
        Verdict::Failed
    };
    Judgement {
        verdict,
        separation,
        usage,
    }
}

/// Judges libccd's penetration depth `depth` of the hulls (B into A) against revdist: hulls
/// within `h_a + h_b` of the convex solids (Hausdorff) have signed distances within `h_a + h_b`
/// of the solids', so the solids' distance lies in `[0, max(0, h_a + h_b - depth)]` (plus
/// `slack`). revdist's interval must meet it; a depth above the bounds forces `lower = 0`.
pub fn judge_penetration(
    rev: Certified,
    value: f64,
    depth: f64,
    mesh_bounds: f64,
    slack: f64,
) -> Judgement {
    let hi = (mesh_bounds + slack - depth).max(0.0);
    let separation = rev.lower - hi;
    let tol = mesh_bounds + (rev.upper - rev.lower) + slack;
    Judgement {
        verdict: if separation <= 0.0 {
            Verdict::Passed
        } else {
            Verdict::Failed
        },
        separation,
        usage: if tol > 0.0 { value / tol } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base(d: f64) -> Baseline {
        Baseline {
            distance: d,
            mesh_bounds: 2e-3,
            slack: 0.0,
        }
    }

    #[test]
    fn intersecting_intervals_pass() {
        let rev = Certified {
            lower: 0.100,
            upper: 0.1005,
            overlap: false,
        };
        let j = judge(rev, 0.1002, base(0.1015), || unreachable!());
        assert_eq!(j.verdict, Verdict::Passed);
        assert!(j.separation < 0.0);
    }

    #[test]
    fn disjoint_intervals_fail() {
        let rev = Certified {
            lower: 0.2,
            upper: 0.2001,
            overlap: false,
        };
        assert_eq!(judge(rev, 0.2, base(0.1), || true).verdict, Verdict::Failed);
    }

    #[test]
    fn fcl_zero_means_within_bounds() {
        // Meshes intersect: the surfaces are within h_a + h_b.
        let near = Certified {
            lower: 1e-3,
            upper: 1.1e-3,
            overlap: false,
        };
        assert_eq!(
            judge(near, 1e-3, base(0.0), || false).verdict,
            Verdict::Passed
        );
        let far = Certified {
            lower: 3e-3,
            upper: 3.1e-3,
            overlap: false,
        };
        assert_eq!(
            judge(far, 3e-3, base(0.0), || false).verdict,
            Verdict::Failed
        );
    }

    #[test]
    fn nesting_is_explained_only_with_a_certificate() {
        let zero = Certified {
            lower: 0.0,
            upper: 0.0,
            overlap: true,
        };
        assert_eq!(
            judge(zero, 0.0, base(0.3), || true).verdict,
            Verdict::Explained
        );
        assert_eq!(
            judge(zero, 0.0, base(0.3), || false).verdict,
            Verdict::Failed
        );
    }
}
