//! Convex pairs: revdist against CGAL's exact hull distance, FCL's libccd GJK distance and
//! libccd's GJK+EPA penetration, on the hulls of the certified meshes' vertices (the module
//! doc of [`super`] proves that such a hull is within the mesh bound of the convex solid).

use super::criterion::{judge, judge_penetration, Baseline, Certified, SLACK_REL};
use super::poses::PoseKind;
use super::record::{CaseContext, CaseRecord, Check};
use super::shapes::{scale, Prepared};
use crate::baselines::{ccd, cgal};
use crate::queries::PoseSpec;
use nalgebra::Point3;
use revdist::query::{distance, QueryOptions};
use std::time::Instant;

/// Extra slack for FCL's libccd GJK distance (length units). Its stopping rule (an iteration
/// improving the distance by less than the tolerance 1e-10) does not bound the error; on
/// polytopes of a few thousand vertices it has been within 1e-9 of CGAL's exact value, and
/// 1e-7 stays two orders below the smallest mesh bound in use.
pub const GJK_SLACK: f64 = 1e-7;

/// Extra slack for libccd's EPA penetration depth (its tolerance is 1e-10; same margin as
/// [`GJK_SLACK`]).
pub const EPA_SLACK: f64 = 1e-7;

/// Runs the three convex checks of one pose.
pub fn check_case(
    a: &Prepared,
    b: &Prepared,
    index: usize,
    kind: PoseKind,
    pose: PoseSpec,
) -> Result<Vec<CaseRecord>, String> {
    let iso = pose.isometry();
    let tq = Instant::now();
    let d = distance(&a.solid, &b.solid.with_pose(iso), &QueryOptions::default());
    let query_time = tq.elapsed();
    let rev = Certified {
        lower: d.lower,
        upper: d.upper,
        overlap: d.overlap,
    };
    let pa: &[Point3<f64>] = &a.vertices;
    let pb: Vec<Point3<f64>> = b.vertices.iter().map(|p| iso * p).collect();
    let h = a.bound + b.bound;
    let slack = SLACK_REL * scale(a, b, &iso);
    let ctx = CaseContext {
        a: &a.name,
        b: &b.name,
        eps: a.eps,
        index,
        kind,
        pose,
        answer: &d,
        mesh_bounds: h,
        query_time,
    };
    let record = |check, baseline, judgement| CaseRecord::new(&ctx, check, baseline, judgement, "");
    let mut out = Vec::with_capacity(3);

    let exact = cgal::polytope_distance_exact(pa, &pb)
        .map_err(|e| format!("CGAL {} / {}: {e}", a.name, b.name))?;
    let dc = exact.value.distance;
    let base = Baseline {
        distance: dc,
        mesh_bounds: h,
        slack,
    };
    out.push(record(Check::Cgal, dc, judge(rev, d.value, base, || false)));

    let gjk =
        ccd::gjk_distance(pa, &pb).map_err(|e| format!("GJK {} / {}: {e}", a.name, b.name))?;
    match gjk {
        Some(g) => {
            let base = Baseline {
                distance: g.distance,
                mesh_bounds: h,
                slack: slack + GJK_SLACK,
            };
            out.push(record(
                Check::Gjk,
                g.distance,
                judge(rev, d.value, base, || false),
            ));
        }
        None => {
            let pen = ccd::penetration(pa, &pb, ccd::Algorithm::Gjk, &ccd::CcdParams::default())
                .map_err(|e| format!("EPA {} / {}: {e}", a.name, b.name))?;
            // GJK says the hulls overlap; EPA may still report touching hulls as separate.
            let depth = pen.map_or(0.0, |p| p.depth);
            out.push(record(
                Check::Penetration,
                -depth,
                judge_penetration(rev, d.value, depth, h, slack + EPA_SLACK),
            ));
        }
    }
    Ok(out)
}
