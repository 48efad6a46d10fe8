//! One compared case: which baseline, the pose, revdist's answer and the judgement, with its
//! reproducer line for `revdist distance --batch`.

use super::criterion::Judgement;
use super::poses::PoseKind;
use crate::queries::PoseSpec;
use std::time::Duration;

/// Which baseline a record compares with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Check {
    /// FCL 0.7 `BVHModel<OBBRSS>` mesh distance.
    Fcl,
    /// CGAL `Polytope_distance_d` (exact) of the vertex hulls.
    Cgal,
    /// FCL's libccd GJK distance of the vertex hulls.
    Gjk,
    /// libccd GJK+EPA penetration depth of overlapping hulls.
    Penetration,
    /// OpenCASCADE's B-rep distance on the true surfaces (`mesh_bounds` holds OCCT's
    /// tolerance).
    Occt,
}

impl Check {
    pub fn name(self) -> &'static str {
        match self {
            Check::Fcl => "fcl-obbrss",
            Check::Cgal => "cgal-hull",
            Check::Gjk => "ccd-gjk",
            Check::Penetration => "ccd-epa",
            Check::Occt => "occt-brep",
        }
    }
}

/// One compared case.
#[derive(Debug, Clone)]
pub struct CaseRecord {
    pub check: Check,
    pub a: String,
    pub b: String,
    pub eps: f64,
    /// Pose number within the pair and eps.
    pub index: usize,
    pub kind: PoseKind,
    pub pose: PoseSpec,
    /// revdist's answer.
    pub lower: f64,
    pub upper: f64,
    pub value: f64,
    pub overlap: bool,
    /// The baseline's distance (for [`Check::Penetration`]: minus the depth).
    pub baseline: f64,
    /// `h_a + h_b`.
    pub mesh_bounds: f64,
    pub judgement: Judgement,
    /// Why an explained case is explained.
    pub note: &'static str,
    pub query_time: Duration,
    /// The baseline's own time for the case, when measured (OCCT).
    pub baseline_time: Option<Duration>,
}

/// What every check of one case shares: the shape pair, the pose and revdist's answer.
pub struct CaseContext<'c> {
    pub a: &'c str,
    pub b: &'c str,
    pub eps: f64,
    pub index: usize,
    pub kind: PoseKind,
    pub pose: PoseSpec,
    pub answer: &'c revdist::query::Distance,
    /// `h_a + h_b`.
    pub mesh_bounds: f64,
    pub query_time: Duration,
}

impl CaseRecord {
    /// The record of one check of a case.
    pub fn new(
        ctx: &CaseContext,
        check: Check,
        baseline: f64,
        judgement: Judgement,
        note: &'static str,
    ) -> CaseRecord {
        let d = ctx.answer;
        CaseRecord {
            check,
            a: ctx.a.to_string(),
            b: ctx.b.to_string(),
            eps: ctx.eps,
            index: ctx.index,
            kind: ctx.kind,
            pose: ctx.pose,
            lower: d.lower,
            upper: d.upper,
            value: d.value,
            overlap: d.overlap,
            baseline,
            mesh_bounds: ctx.mesh_bounds,
            judgement,
            note,
            query_time: ctx.query_time,
            baseline_time: None,
        }
    }

    /// A JSON line for `revdist distance --batch FILE`.
    pub fn reproducer(&self) -> String {
        format!(
            "{{\"a\":\"{}\",\"b\":\"{}\",\"pose_b\":{},\"eps\":{:?}}}",
            self.a,
            self.b,
            self.pose.json(),
            self.eps
        )
    }
}
