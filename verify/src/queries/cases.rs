//! What a case is (two shapes of the pool, a pose of B, the query's options) and how case
//! `id` is drawn from the campaign seed.

use super::corners::corner_contact;
use super::placement::{
    axis_centre, draw_rotation, interior_point, newton_gap, place_at_gap, quick_eval, spec,
};
use super::pool::{pick, Shape, ShapeSet};
use super::pose_spec::PoseSpec;
use nalgebra::Vector3;
use revdist::rng::SplitMix64;
use std::fmt::Write as _;

/// How B is placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PoseKind {
    Regression,
    Far,
    Separated,
    NearTouching,
    Touching,
    Overlapping,
    Nested,
    NestedNear,
    Coincident,
    /// A corner circle of A against a corner, an axis end or a smooth point of B
    /// (`super::corners`).
    Corner,
}

impl PoseKind {
    pub fn name(self) -> &'static str {
        match self {
            PoseKind::Regression => "regression",
            PoseKind::Far => "far",
            PoseKind::Separated => "separated",
            PoseKind::NearTouching => "near-touching",
            PoseKind::Touching => "touching",
            PoseKind::Overlapping => "overlapping",
            PoseKind::Nested => "nested",
            PoseKind::NestedNear => "nested-near-wall",
            PoseKind::Coincident => "coincident",
            PoseKind::Corner => "corner",
        }
    }
}

/// One query to run.
#[derive(Debug, Clone)]
pub struct Case {
    pub id: usize,
    pub kind: PoseKind,
    pub a: usize,
    pub b: usize,
    pub pose: PoseSpec,
    pub eps: f64,
    /// Query options beyond the defaults: target interval width (`None`: the default, the
    /// trees' own accuracy, [`revdist::query::Tolerance::Trees`]) and witness refinement.
    pub tolerance: Option<f64>,
    pub refine: bool,
    /// What the placement aimed at.
    pub note: String,
}

impl Case {
    /// Batch JSON line for `revdist distance --batch`, with A and B given as `a` and `b`
    /// (built-in names or profile paths).
    pub fn batch_line(&self, a: &str, b: &str) -> String {
        let mut extra = String::new();
        if let Some(t) = self.tolerance {
            write!(extra, ",\"tolerance\":{t:?}").unwrap();
        }
        if self.refine {
            extra.push_str(",\"refine\":true");
        }
        format!(
            "{{\"a\":{a:?},\"b\":{b:?},\"pose_b\":{},\"eps\":{:?}{extra}}}",
            self.pose.json(),
            self.eps
        )
    }
}

/// Share of the campaign's cases posed as corner contacts ([`super::corners`]).
pub const CORNER_SHARE: f64 = 0.25;
/// Shape pairs a corner case draws before it falls back to a touching case (when neither
/// shape of a pair has a corner).
const CORNER_TRIES: usize = 20;

/// Generates case `id` (deterministic in the seed and id).
pub fn make_case(id: usize, seed: u64, shapes: &[Shape], eps_list: &[f64], set: ShapeSet) -> Case {
    let mut rng = SplitMix64(seed).fork(0xCA5E_0000 + id as u64);
    let eps = eps_list[rng.int(0, eps_list.len() - 1)];
    // Half the queries run with the default tolerance (the trees' accuracy), a third run to
    // the end (tolerance 0), the rest ask for a coarse tolerance; some refine witnesses.
    let u = rng.next_f64();
    let tolerance = if u < 0.15 {
        Some(rng.log_range(1e-4, 1e-1))
    } else if u < 0.5 {
        Some(0.0)
    } else {
        None
    };
    let refine = rng.chance(0.15);
    let u = rng.next_f64();
    // The corner share is drawn after `u`, so the other kinds keep their split of the rest.
    let corner = rng.chance(CORNER_SHARE);
    let kind = match u {
        _ if corner => PoseKind::Corner,
        _ if u < 0.07 => PoseKind::Far,
        _ if u < 0.25 => PoseKind::Separated,
        _ if u < 0.55 => PoseKind::NearTouching,
        _ if u < 0.65 => PoseKind::Touching,
        _ if u < 0.77 => PoseKind::Overlapping,
        _ if u < 0.85 => PoseKind::Nested,
        _ if u < 0.94 => PoseKind::NestedNear,
        _ => PoseKind::Coincident,
    };
    let case = |kind, a, b, pose, note: String| Case {
        id,
        kind,
        a,
        b,
        pose,
        eps,
        tolerance,
        refine,
        note,
    };
    if kind == PoseKind::Corner {
        for _ in 0..CORNER_TRIES {
            let (a, b) = (
                pick(&mut rng, shapes, None, set),
                pick(&mut rng, shapes, None, set),
            );
            if let Some((pose, note)) = corner_contact(&mut rng, &shapes[a], &shapes[b]) {
                return case(kind, a, b, pose, note);
            }
        }
    }
    let kind = if kind == PoseKind::Corner {
        PoseKind::Touching
    } else {
        kind
    };
    match kind {
        PoseKind::Far => {
            let (a, b) = (
                pick(&mut rng, shapes, None, set),
                pick(&mut rng, shapes, None, set),
            );
            let (q, _) = draw_rotation(&mut rng);
            let r = if rng.chance(0.5) { 1e3 } else { 1e6 };
            let u = rng.direction();
            let pose = spec(u * r * rng.range(1.0, 2.0), q);
            case(kind, a, b, pose, format!("|t| ~ {r:e}"))
        }
        PoseKind::Coincident => {
            let a = pick(&mut rng, shapes, None, set);
            case(
                kind,
                a,
                a,
                spec(Vector3::zeros(), [1.0, 0.0, 0.0, 0.0]),
                "same solid, same pose".into(),
            )
        }
        PoseKind::Nested | PoseKind::NestedNear => {
            let a = pick(&mut rng, shapes, Some("big"), set);
            let b = pick(&mut rng, shapes, Some("tiny"), set);
            let (q, _) = draw_rotation(&mut rng);
            let rb = shapes[b].index.geom.radius;
            if let Some(p0) = interior_point(&mut rng, &shapes[a], 1.1 * rb) {
                let pose0 = spec(p0, q);
                if kind == PoseKind::Nested {
                    return case(kind, a, b, pose0, "deep inside".into());
                }
                // Slide along a random line until the surface gap to the wall is the target.
                let target = rng.log_range(1e-7, 1e-2);
                let u = rng.direction();
                let f = |s: f64| {
                    let pos = spec(p0 + u * s, q).isometry();
                    let (_, d, slope) = quick_eval(&shapes[a], &shapes[b], &pos, &u);
                    (d, slope)
                };
                if let Some((s, got)) = newton_gap(f, 0.0, target, 1e-3 * target, 0.05 * target) {
                    return case(
                        kind,
                        a,
                        b,
                        spec(p0 + u * s, q),
                        format!("inner wall gap {got:e}"),
                    );
                }
                return case(PoseKind::Nested, a, b, pose0, "deep inside".into());
            }
            // No room inside: fall back to a separated pair.
            let target = rng.range(0.05, 0.5);
            match place_at_gap(&mut rng, &shapes[a], &shapes[b], target) {
                Some((pose, got)) => case(PoseKind::Separated, a, b, pose, format!("gap {got:e}")),
                None => case(
                    PoseKind::Far,
                    a,
                    b,
                    spec(Vector3::new(1e3, 0.0, 0.0), q),
                    "fallback".into(),
                ),
            }
        }
        _ => {
            let (a, b) = (
                pick(&mut rng, shapes, None, set),
                pick(&mut rng, shapes, None, set),
            );
            let scale = shapes[a].size.max(shapes[b].size);
            let target = match kind {
                PoseKind::Separated => rng.log_range(0.03, 1.0) * scale,
                PoseKind::NearTouching => rng.log_range(1e-7, 1e-2),
                PoseKind::Touching => 0.0,
                _ => 0.0,
            };
            let placed = place_at_gap(&mut rng, &shapes[a], &shapes[b], target);
            match (kind, placed) {
                (PoseKind::Overlapping, Some((pose, _))) => {
                    // From touching, push B further in along the same line.
                    let depth = rng.log_range(1e-5, 0.3) * scale;
                    let iso = pose.isometry();
                    let dir = (iso.translation.vector + iso.rotation * axis_centre(&shapes[b]))
                        - axis_centre(&shapes[a]);
                    let n = dir.norm();
                    let t = if n > 0.0 {
                        iso.translation.vector - dir / n * depth
                    } else {
                        iso.translation.vector
                    };
                    case(
                        kind,
                        a,
                        b,
                        spec(t, pose.rotation),
                        format!("pushed in {depth:e}"),
                    )
                }
                (_, Some((pose, got))) => case(kind, a, b, pose, format!("gap {got:e}")),
                (_, None) => {
                    let (q, _) = draw_rotation(&mut rng);
                    let far = shapes[a].index.geom.radius + shapes[b].index.geom.radius;
                    let u = rng.direction();
                    case(
                        PoseKind::Separated,
                        a,
                        b,
                        spec(u * (far + 0.5), q),
                        "fallback".into(),
                    )
                }
            }
        }
    }
}
