//! Tests of the convex fast path: the convexity certificate on the built-in models and on
//! random profiles, and the fast path's interval against the traversal at tolerance 0 and
//! against analytic distances.

use crate::bvh::convex::certify_convex;
use crate::models::{model, model_names, primitives::bezier};
use crate::num::cross2;
use crate::nurbs::NurbsCurve;
use crate::profile::Profile;
use crate::query::front::distance::{distance, query_slack, QueryOptions, Tolerance};
use crate::solid::Solid;
use crate::test_rng::SplitMix64;
use nalgebra::{Isometry3, Point2, Translation3, UnitQuaternion, Vector3};
use std::sync::Arc;

const CONVEX_MODELS: [&str; 4] = ["sphere", "capsule", "cylinder", "cone"];

fn solid(name: &str, eps: f64) -> Solid {
    Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap()
}

/// The default options with the convex path on (as by default).
fn with_fast_path() -> QueryOptions {
    QueryOptions {
        convex_path: true,
        ..QueryOptions::default()
    }
}

fn traversal_exact() -> QueryOptions {
    QueryOptions {
        tolerance: Tolerance::Absolute(0.0),
        convex_path: false,
        closed_form: false,
        ..with_fast_path()
    }
}

#[test]
fn convexity_of_built_in_models() {
    for name in model_names() {
        let p = model(name).unwrap();
        let expected = CONVEX_MODELS.contains(name);
        assert_eq!(
            certify_convex(&p).is_some(),
            expected,
            "{name}: certificate {:?}",
            certify_convex(&p)
        );
        if let Some(c) = certify_convex(&p) {
            assert_eq!(c.dent, 0.0, "{name}");
        }
    }
    for t in [0.0, 0.25, 0.5, 0.75] {
        let p = model(&format!("morph@{t}")).unwrap();
        assert!(certify_convex(&p).is_none(), "morph@{t}");
    }
    // Solids built from profiles carry the certificate.
    for name in CONVEX_MODELS {
        assert!(solid(name, 1e-3).tree.convex.is_some(), "{name}");
    }
    assert!(solid("pawn", 1e-3).tree.convex.is_none());
}

#[test]
#[ignore = "probe: prints the trees of the convex models and a few timings"]
fn probe_convex_models() {
    for eps in [1e-3, 1e-5] {
        for name in CONVEX_MODELS {
            let s = solid(name, eps);
            println!(
                "{name} eps {eps:e}: chain {} pieces, tree eps {:e}, target {:e}, hull error {:e}",
                s.tree.chain.len(),
                s.tree.eps,
                s.tree.target_eps,
                s.tree.convex.as_ref().unwrap().error
            );
        }
    }
    let mut rng = SplitMix64(7);
    for (i, name_a) in CONVEX_MODELS.iter().enumerate() {
        for name_b in &CONVEX_MODELS[i..] {
            let a = solid(name_a, 1e-3);
            let b = solid(name_b, 1e-3);
            let mut iters = 0;
            let mut n = 0;
            let t0 = std::time::Instant::now();
            for _ in 0..200 {
                let pose = random_pose(&mut rng, 1.2, 2.5);
                let d = distance(&a, &b.with_pose(pose), &with_fast_path());
                n += d.stats.convex_paths;
                iters += 1;
            }
            println!(
                "{name_a}-{name_b}: {} of {iters} by the fast path, {:.2} us per query",
                n,
                t0.elapsed().as_secs_f64() * 1e6 / iters as f64
            );
        }
    }
}

#[test]
#[ignore = "probe: why the fast path declines"]
fn probe_declines() {
    use super::gjk::gjk;
    let mut rng = SplitMix64(11);
    for (i, name_a) in CONVEX_MODELS.iter().enumerate() {
        for name_b in &CONVEX_MODELS[i..] {
            let a = solid(name_a, 1e-3);
            let b = solid(name_b, 1e-3);
            let (ca, cb) = (
                a.tree.convex.as_ref().unwrap(),
                b.tree.convex.as_ref().unwrap(),
            );
            let mut hist = [0usize; 8];
            let (mut inter, mut wide) = (0, 0);
            let mut total_iters = 0;
            for _ in 0..500 {
                let pose = random_pose(&mut rng, 1.2, 2.5);
                let rot = pose.rotation;
                let r = gjk(
                    |d| ca.support.support(d),
                    |d| pose * cb.support.support(&rot.inverse_transform_vector(d)),
                    Vector3::x(),
                    1e-3,
                    1e-14,
                );
                total_iters += r.iterations;
                hist[(r.iterations / 8).min(7)] += 1;
                let ans = super::convex_distance(&a.tree, &b.tree, &pose, 1e-12, 2e-3);
                if ans.is_none() {
                    if r.intersect {
                        inter += 1;
                        if inter < 4 {
                            let d = distance(&a, &b.with_pose(pose), &traversal_exact());
                            println!(
                                "  intersect: {r:?}\n   traversal [{}, {}] overlap {}",
                                d.lower, d.upper, d.overlap
                            );
                        }
                    } else {
                        wide += 1;
                        if wide < 4 {
                            println!("  wide: {r:?}");
                        }
                    }
                }
            }
            println!(
                "{name_a}-{name_b}: declined {inter} intersect, {wide} wide; mean iterations {:.1}, hist by 8s {hist:?}",
                total_iters as f64 / 500.0
            );
        }
    }
}

#[test]
#[ignore = "probe: freeform convex profiles"]
fn probe_freeform() {
    let mut rng = SplitMix64(99);
    for eps in [1e-3, 1e-4, 1e-5] {
        let (mut used, mut n, mut iters) = (0, 0, 0usize);
        let (mut t_on, mut t_off) = (0.0, 0.0);
        for _ in 0..20 {
            let (Some(pa), Some(pb)) = (
                bezier_profile(&mut rng, false),
                bezier_profile(&mut rng, false),
            ) else {
                continue;
            };
            let a = Solid::from_profile(Arc::new(pa), eps).unwrap();
            let b = Solid::from_profile(Arc::new(pb), eps).unwrap();
            for _ in 0..20 {
                let bp = b.with_pose(random_pose(&mut rng, 1.0, 3.0));
                let t0 = std::time::Instant::now();
                let d = distance(&a, &bp, &with_fast_path());
                t_on += t0.elapsed().as_secs_f64();
                let t0 = std::time::Instant::now();
                let _ = distance(
                    &a,
                    &bp,
                    &QueryOptions {
                        convex_path: false,
                        ..with_fast_path()
                    },
                );
                t_off += t0.elapsed().as_secs_f64();
                used += d.stats.convex_paths;
                n += 1;
                if let Some((_, trace)) = super::convex_distance_traced(
                    &a.tree,
                    &bp.tree,
                    &a.relative_pose(&bp),
                    1e-11,
                    Tolerance::Trees.width(a.tree.target_eps, b.tree.target_eps),
                ) {
                    iters += trace.iterations;
                }
            }
            if n == 20 {
                println!(
                    "eps {eps:e}: chain {} pieces, tree eps {:e}, target {:e}",
                    a.tree.chain.len(),
                    a.tree.eps,
                    a.tree.target_eps
                );
            }
        }
        println!("eps {eps:e}: {used} of {n} by the fast path, {:.1} iterations, on {:.2} us, off {:.2} us", iters as f64 / used.max(1) as f64, t_on * 1e6 / n as f64, t_off * 1e6 / n as f64);
    }
}

#[test]
#[ignore = "probe: iterations at close poses"]
fn probe_close_iterations() {
    let mut rng = SplitMix64(5);
    for (i, j) in [(1, 1), (0, 1), (2, 3), (3, 3)] {
        let a = solid(CONVEX_MODELS[i], 1e-4);
        let b = solid(CONVEX_MODELS[j], 1e-4);
        let mut hist = std::collections::BTreeMap::new();
        let mut total_ns = 0.0;
        for _ in 0..100 {
            let gap = 10f64.powf(rng.range(-4.0, -1.0));
            let Some(pose) = near_touching(&a, &b, &mut rng, gap) else {
                continue;
            };
            let width = Tolerance::Trees.width(a.tree.target_eps, b.tree.target_eps);
            let t0 = std::time::Instant::now();
            let (_, trace) =
                super::convex_distance_traced(&a.tree, &b.tree, &pose, 1e-11, width).unwrap();
            total_ns += t0.elapsed().as_nanos() as f64;
            *hist.entry(trace.iterations).or_insert(0) += 1;
        }
        println!(
            "{}-{}: {:.0} ns, iterations {hist:?}",
            CONVEX_MODELS[i],
            CONVEX_MODELS[j],
            total_ns / 100.0
        );
    }
}

/// A random pose: a random rotation and a translation of length in `[lo, hi)`.
fn random_pose(rng: &mut SplitMix64, lo: f64, hi: f64) -> Isometry3<f64> {
    let axis = nalgebra::Unit::new_normalize(rng.unit());
    let rot = UnitQuaternion::from_axis_angle(&axis, rng.range(0.0, std::f64::consts::TAU));
    let t = rng.unit() * rng.range(lo, hi);
    Isometry3::from_parts(Translation3::from(t), rot)
}

// ---------------------------------------------------------------------------------------
// Convexity of random profiles against an independent sampled check.
// ---------------------------------------------------------------------------------------

/// Sampled convexity of the meridian section (profile and mirror image): the polygon of
/// dense samples turns left everywhere up to the rounding of samples of straight pieces
/// (`Some(true)`), clearly turns right somewhere
/// (`Some(false)`), or is too close to call (`None`). Chords of a convex curve form a
/// convex polygon, so a convex section never samples as `Some(false)`.
fn sampled_convexity(p: &Profile) -> Option<bool> {
    let mut half: Vec<Point2<f64>> = Vec::new();
    for piece in p.pieces() {
        let (t0, t1) = piece.domain();
        for k in 0..=2000 {
            let q = piece.eval(t0 + (t1 - t0) * k as f64 / 2000.0);
            if half.last() != Some(&q) {
                half.push(q);
            }
        }
    }
    if half[0].y > half[half.len() - 1].y {
        half.iter_mut().for_each(|q| q.y = -q.y);
    }
    let mut section = half.clone();
    section.extend(half.iter().rev().map(|q| Point2::new(-q.x, q.y)));
    section.dedup();
    if section.first() == section.last() {
        section.pop();
    }
    let n = section.len();
    let (mut min_turn, mut total) = (f64::INFINITY, 0.0);
    for i in 0..n {
        let (a, b, c) = (section[i], section[(i + 1) % n], section[(i + 2) % n]);
        let (u, v) = ((b - a).normalize(), (c - b).normalize());
        if !(u.x.is_finite() && v.x.is_finite()) {
            continue;
        }
        let turn = cross2(u, v).atan2(u.dot(&v));
        min_turn = min_turn.min(turn);
        total += turn;
    }
    if min_turn < -1e-7 || (total - std::f64::consts::TAU).abs() > 1e-3 {
        Some(false)
    } else if min_turn >= -1e-10 {
        Some(true)
    } else {
        None
    }
}

/// A random convex polygon profile: vertices on a half ellipse from the bottom of the axis
/// to its top; `dent` pulls one middle vertex towards the centre.
fn polygon_profile(rng: &mut SplitMix64, dent: bool) -> Option<Profile> {
    let n = 2 + (rng.next_f64() * 8.0) as usize;
    let (a, b, z0) = (
        rng.range(0.2, 1.5),
        rng.range(0.2, 1.5),
        rng.range(-1.0, 1.0),
    );
    let mut angles: Vec<f64> = (0..n).map(|_| rng.range(-1.5, 1.5)).collect();
    angles.sort_by(f64::total_cmp);
    let mut pts = vec![Point2::new(0.0, z0 - b)];
    pts.extend(
        angles
            .iter()
            .map(|t| Point2::new(a * t.cos(), z0 + b * t.sin())),
    );
    pts.push(Point2::new(0.0, z0 + b));
    if dent {
        let i = 1 + (rng.next_f64() * n as f64) as usize;
        let f = rng.range(0.3, 0.9);
        pts[i] = Point2::new(pts[i].x * f, z0 + (pts[i].y - z0) * f);
    }
    let pieces = pts
        .windows(2)
        .filter(|w| w[0] != w[1])
        .map(|w| NurbsCurve::line(w[0], w[1]).unwrap())
        .collect();
    Profile::new("polygon", pieces).ok()
}

/// A random superellipse-like profile of two cubic Bezier pieces meeting at the equator
/// with a vertical tangent (convex control polygons); `dent` adds a quartic middle piece
/// whose middle control point is pulled in (usually a dent).
fn bezier_profile(rng: &mut SplitMix64, dent: bool) -> Option<Profile> {
    let (a, h) = (rng.range(0.2, 1.2), rng.range(0.2, 1.2));
    let k = [0.0; 4].map(|_| rng.range(0.05, 0.95));
    let mut pieces = vec![cubic([
        [0.0, 0.0],
        [k[0] * a, 0.0],
        [a, h - k[1] * h],
        [a, h],
    ])];
    let top = h + if dent { rng.range(0.2, 1.0) } else { 0.0 };
    if dent {
        let pull = rng.range(0.2, 0.9) * a;
        let mid = 0.5 * (h + top);
        pieces.push(
            bezier(&[
                [a, h],
                [a, h + 0.1 * (top - h)],
                [pull, mid],
                [a, top - 0.1 * (top - h)],
                [a, top],
            ])
            .unwrap(),
        );
    }
    pieces.push(cubic([
        [a, top],
        [a, top + k[2] * h],
        [k[3] * a, top + h],
        [0.0, top + h],
    ]));
    Profile::new("bezier", pieces).ok()
}

fn cubic(points: [[f64; 2]; 4]) -> NurbsCurve {
    bezier(&points).unwrap()
}

#[test]
fn convexity_of_random_profiles_agrees_with_sampling() {
    let mut rng = SplitMix64(0xC0_4E_E5);
    let (mut convex, mut dented, mut certified_convex, mut rejected_dents) = (0, 0, 0, 0);
    for round in 0..800 {
        let dent = round % 2 == 1;
        let p = if round % 4 < 2 {
            polygon_profile(&mut rng, dent)
        } else {
            bezier_profile(&mut rng, dent)
        };
        let Some(p) = p else { continue };
        let certificate = certify_convex(&p);
        match sampled_convexity(&p) {
            Some(false) => {
                dented += 1;
                // The promise: a non-convex solid is never certified.
                assert!(
                    certificate.is_none(),
                    "round {round}: non-convex profile certified"
                );
                rejected_dents += 1;
            }
            Some(true) => {
                convex += 1;
                if certificate.is_some() {
                    certified_convex += 1;
                } else {
                    assert!(
                        dent,
                        "round {round}: a convex profile of the convex families rejected"
                    );
                }
            }
            None => {}
        }
    }
    println!(
        "{convex} convex ({certified_convex} certified), {dented} not ({rejected_dents} rejected)"
    );
    assert!(
        convex > 250 && dented > 150,
        "{convex} convex, {dented} dented"
    );
}

#[test]
fn end_tangents_at_the_axis_decide_convexity() {
    // A dimple at the bottom: the profile leaves the axis downwards (reflex corner of the
    // mirrored section), although the curve itself turns left.
    let dimple = Profile::new(
        "dimple",
        vec![
            cubic([[0.0, 0.0], [0.3, -0.1], [0.6, 0.0], [0.6, 0.4]]),
            cubic([[0.6, 0.4], [0.6, 0.8], [0.3, 1.0], [0.0, 1.0]]),
        ],
    )
    .unwrap();
    assert_eq!(sampled_convexity(&dimple), Some(false));
    assert!(certify_convex(&dimple).is_none());
    // A spike at the bottom (cone tip) is convex; the same running top to bottom too.
    let spike = Profile::new(
        "spike",
        vec![
            cubic([[0.0, 0.0], [0.2, 0.1], [0.5, 0.3], [0.5, 0.6]]),
            cubic([[0.5, 0.6], [0.5, 0.9], [0.3, 1.0], [0.0, 1.0]]),
        ],
    )
    .unwrap();
    assert!(certify_convex(&spike).is_some());
    let reversed: Vec<NurbsCurve> = spike.pieces().iter().rev().map(|c| c.reversed()).collect();
    assert!(certify_convex(&Profile::new("down", reversed).unwrap()).is_some());
}

// ---------------------------------------------------------------------------------------
// The fast path's interval against the traversal and analytic distances.
// ---------------------------------------------------------------------------------------

/// Pose of B whose distance to A is about `gap`: B placed far along a random direction,
/// then moved back along the normal of its closest points (for convex solids the distance
/// drops by exactly the move). `None` when the traversal cannot give the normal.
fn near_touching(a: &Solid, b: &Solid, rng: &mut SplitMix64, gap: f64) -> Option<Isometry3<f64>> {
    let far = random_pose(rng, 3.0, 3.0001);
    let d = distance(a, &b.with_pose(far), &traversal_exact());
    let n = (d.point_b - d.point_a).try_normalize(0.0)?;
    let shift = Translation3::from(-n * (d.value - gap));
    Some(shift * far)
}

/// The fast path's narrowest interval for the pair (the trees' eps and rounding, as for a
/// traversal at tolerance 0).
fn floor(a: &Solid, b: &Solid) -> f64 {
    let pos_ab = a.relative_pose(b);
    let slack = query_slack(&a.tree, &b.tree, &pos_ab);
    super::width_floor(&a.tree, &b.tree, &pos_ab, slack).unwrap()
}

/// Certified intervals of the same distance must meet.
fn assert_meets(fast: &crate::query::Distance, reference: &crate::query::Distance, label: &str) {
    let tol = 1e-12;
    assert!(
        fast.lower <= reference.upper + tol && reference.lower <= fast.upper + tol,
        "{label}: fast [{}, {}] vs traversal [{}, {}]",
        fast.lower,
        fast.upper,
        reference.lower,
        reference.upper
    );
    if fast.overlap {
        assert_eq!(
            reference.lower, 0.0,
            "{label}: overlap claimed, traversal separates"
        );
    }
    if reference.overlap {
        assert_eq!(
            fast.lower, 0.0,
            "{label}: traversal overlaps, fast path separates"
        );
    }
}

#[test]
fn fast_path_contains_the_traversals_distance() {
    let mut rng = SplitMix64(0x5EED_C0DE);
    let eps = 1e-4;
    let solids: Vec<Solid> = CONVEX_MODELS.iter().map(|n| solid(n, eps)).collect();
    let fast_opts = QueryOptions {
        closed_form: false,
        ..with_fast_path()
    };
    let (mut poses, mut by_fast_path, mut overlaps) = (0, 0, 0);
    for i in 0..4 {
        for j in i..4 {
            let (a, b) = (&solids[i], &solids[j]);
            for k in 0..210 {
                let pose = match k % 3 {
                    0 => {
                        let gap = 10f64.powf(rng.range(-6.0, -1.0));
                        near_touching(a, b, &mut rng, gap)
                    }
                    1 => Some(random_pose(&mut rng, 0.0, 0.9)),
                    _ => Some(random_pose(&mut rng, 0.9, 2.5)),
                };
                let Some(pose) = pose else { continue };
                let bp = b.with_pose(pose);
                let label = format!("{}-{} pose {k}", CONVEX_MODELS[i], CONVEX_MODELS[j]);
                let fast = distance(a, &bp, &fast_opts);
                let reference = distance(a, &bp, &traversal_exact());
                assert_meets(&fast, &reference, &label);
                let requested = fast_opts
                    .tolerance
                    .width(a.tree.target_eps, bp.tree.target_eps);
                assert!(fast.upper - fast.lower <= requested, "{label}: width");
                poses += 1;
                by_fast_path += fast.stats.convex_paths;
                overlaps += fast.overlap as usize;
                if fast.stats.convex_paths == 1 && !fast.overlap {
                    // Witnesses are realised: their distance lies in the interval.
                    let w = (fast.point_a - fast.point_b).norm();
                    assert!(
                        w >= fast.lower - 1e-12 && w <= fast.upper + 1e-12,
                        "{label}: witness {w}"
                    );
                }
            }
        }
    }
    println!("{poses} poses, {by_fast_path} by the fast path, {overlaps} overlapping");
    assert!(poses >= 2000);
    assert!(
        by_fast_path as f64 >= 0.97 * poses as f64,
        "{by_fast_path} of {poses}"
    );
}

#[test]
fn fast_path_contains_analytic_distances() {
    let mut rng = SplitMix64(0xA11A);
    let sphere_a = solid("sphere", 1e-3);
    let cylinder = solid("cylinder", 1e-3);
    let opts = QueryOptions {
        closed_form: false,
        tolerance: Tolerance::Absolute(1e-9),
        ..with_fast_path()
    };
    let mut fast = 0;
    for k in 0..400 {
        let pose = random_pose(&mut rng, 0.0, 3.0);
        // The sphere of radius 0.75 is centred at z = 0.75 of its frame.
        let centre = |p: &Isometry3<f64>| p * nalgebra::Point3::new(0.0, 0.0, 0.75);
        let (b, exact) = if k % 2 == 0 {
            let d = (centre(&pose) - centre(&Isometry3::identity())).norm() - 1.5;
            (sphere_a.with_pose(pose), d.max(0.0))
        } else {
            // Sphere centre in the cylinder's frame; the cylinder has radius 0.5, z in [0, 1.5].
            let c = pose.inverse_transform_point(&centre(&Isometry3::identity()));
            let out_r = (c.x.hypot(c.y) - 0.5).max(0.0);
            let out_z = (-c.z).max(c.z - 1.5).max(0.0);
            (
                cylinder.with_pose(pose),
                (out_r.hypot(out_z) - 0.75).max(0.0),
            )
        };
        let d = distance(&sphere_a, &b, &opts);
        fast += d.stats.convex_paths;
        assert!(
            d.lower <= exact + 1e-12 && exact <= d.upper + 1e-12,
            "pose {k}: {exact} outside [{}, {}]",
            d.lower,
            d.upper
        );
        assert!(
            d.upper - d.lower <= 1e-9f64.max(floor(&sphere_a, &b)),
            "pose {k}: width {} ({:?}, exact {exact})",
            d.upper - d.lower,
            d
        );
        if d.overlap {
            assert_eq!(exact, 0.0, "pose {k}");
        }
    }
    assert!(fast >= 390, "{fast} of 400 by the fast path");
}

#[test]
fn width_meets_the_tolerance() {
    let mut rng = SplitMix64(0x3D);
    let solids: Vec<Solid> = CONVEX_MODELS.iter().map(|n| solid(n, 1e-3)).collect();
    for tolerance in [
        Tolerance::Trees,
        Tolerance::Absolute(1e-6),
        Tolerance::Absolute(0.0),
    ] {
        let opts = QueryOptions {
            tolerance,
            ..with_fast_path()
        };
        for k in 0..200 {
            let (a, b) = (&solids[k % 4], &solids[(k / 4) % 4]);
            let bp = b.with_pose(random_pose(&mut rng, 0.5, 2.5));
            let d = distance(a, &bp, &opts);
            let requested = tolerance.width(a.tree.target_eps, b.tree.target_eps);
            assert!(
                d.upper - d.lower <= requested.max(floor(a, &bp)),
                "{tolerance:?} pose {k}: width {}",
                d.upper - d.lower
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// Property test: random convex freeform profiles and poses.
// ---------------------------------------------------------------------------------------

proptest::proptest! {
    // 32 cases unless PROPTEST_CASES asks for more (the seed comes from PROPTEST_RNG_SEED).
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(32),
        failure_persistence: None,
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// Two random superellipse-like convex profiles at random poses (separated, touching
    /// closely or overlapping): both are certified convex, and the fast path's interval
    /// meets the traversal's at tolerance 0 and keeps within the requested width or the
    /// trees' floor.
    #[test]
    fn random_convex_profiles_against_the_traversal(
        seed in proptest::prelude::any::<u64>(),
        eps_exp in 3i32..=4,
        gap_exp in -6.0f64..0.0,
        kind in 0usize..3,
    ) {
        let mut rng = SplitMix64(seed);
        let eps = 10f64.powi(-eps_exp);
        let pa = bezier_profile(&mut rng, false);
        let pb = bezier_profile(&mut rng, false);
        let (Some(pa), Some(pb)) = (pa, pb) else { return Ok(()) };
        let a = Solid::from_profile(Arc::new(pa), eps).unwrap();
        let b = Solid::from_profile(Arc::new(pb), eps).unwrap();
        proptest::prop_assert!(a.tree.convex.is_some() && b.tree.convex.is_some());
        for _ in 0..8 {
            let pose = match kind {
                0 => near_touching(&a, &b, &mut rng, 10f64.powf(gap_exp)),
                1 => Some(random_pose(&mut rng, 0.0, 1.0)),
                _ => Some(random_pose(&mut rng, 1.0, 3.0)),
            };
            let Some(pose) = pose else { continue };
            let bp = b.with_pose(pose);
            let fast = distance(&a, &bp, &with_fast_path());
            let reference = distance(&a, &bp, &traversal_exact());
            assert_meets(&fast, &reference, "random convex");
            let requested = Tolerance::Trees.width(a.tree.target_eps, b.tree.target_eps);
            let floor = floor(&a, &bp);
            proptest::prop_assert!(
                fast.upper - fast.lower <= requested.max(floor),
                "width {} requested {requested} floor {floor}: {:?}",
                fast.upper - fast.lower,
                fast
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// Witnesses and value against the models' analytic surfaces.
// ---------------------------------------------------------------------------------------

/// Distance from `x` (solid frame) to the true surface of a convex built-in model, from
/// its analytic description (`models::basic`): the meridian point's distance to the
/// profile's exact pieces.
fn analytic_surface_gap(name: &str, x: &nalgebra::Point3<f64>) -> f64 {
    let m = Point2::new(x.x.hypot(x.y), x.z);
    let segment = |a: [f64; 2], b: [f64; 2]| {
        let (a, b) = (Point2::new(a[0], a[1]), Point2::new(b[0], b[1]));
        let t = ((m - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
        (m - (a + (b - a) * t)).norm()
    };
    // Quarter or half circles bulging outwards from the axis: the distance to the full
    // circle wherever the foot lies on the rho >= 0 side within the arc's z range.
    let arc = |c: [f64; 2], r: f64, z_lo: f64, z_hi: f64| {
        let d = m - Point2::new(c[0], c[1]);
        let foot = Point2::new(c[0], c[1]) + d * (r / d.norm());
        if foot.x >= 0.0 && foot.y >= z_lo - 1e-15 && foot.y <= z_hi + 1e-15 {
            (d.norm() - r).abs()
        } else {
            f64::INFINITY
        }
    };
    match name {
        "sphere" => arc([0.0, 0.75], 0.75, 0.0, 1.5),
        "capsule" => arc([0.0, 0.4], 0.4, 0.0, 0.4)
            .min(segment([0.4, 0.4], [0.4, 1.2]))
            .min(arc([0.0, 1.2], 0.4, 1.2, 1.6)),
        "cylinder" => segment([0.0, 0.0], [0.5, 0.0])
            .min(segment([0.5, 0.0], [0.5, 1.5]))
            .min(segment([0.5, 1.5], [0.0, 1.5])),
        "cone" => segment([0.0, 0.0], [0.6, 0.0]).min(segment([0.6, 0.0], [0.0, 1.5])),
        _ => unreachable!("{name}"),
    }
}

/// The query's contract on the fast path (checks c-e of `verify`'s oracle), against the
/// analytic surfaces and the traversal's value at tolerance 0: witnesses within the trees'
/// eps of the true surfaces, `|point_a - point_b| = value`, and the value within the
/// requested width of the approximations' distance, at coarse, default and fine
/// tolerances.
#[test]
fn witnesses_on_the_surfaces_and_value_within_the_width() {
    let mut rng = SplitMix64(0x51DE);
    let solids: Vec<Solid> = CONVEX_MODELS.iter().map(|n| solid(n, 1e-4)).collect();
    let (mut checked, mut queries) = (0, 0);
    for tolerance in [
        Tolerance::Absolute(3e-2),
        Tolerance::Trees,
        Tolerance::Absolute(1e-9),
    ] {
        let opts = QueryOptions {
            tolerance,
            closed_form: false,
            ..with_fast_path()
        };
        for k in 0..160 {
            let (i, j) = (k % 4, (k / 4) % 4);
            let (a, b) = (&solids[i], &solids[j]);
            let pose = if k % 2 == 0 {
                let gap = 10f64.powf(rng.range(-5.0, -1.0));
                near_touching(a, b, &mut rng, gap)
            } else {
                Some(random_pose(&mut rng, 1.0, 2.5))
            };
            let Some(pose) = pose else { continue };
            let bp = b.with_pose(pose);
            let d = distance(a, &bp, &opts);
            queries += 1;
            if d.stats.convex_paths == 0 || d.overlap {
                continue;
            }
            checked += 1;
            let label = format!(
                "{tolerance:?} {}-{} pose {k}",
                CONVEX_MODELS[i], CONVEX_MODELS[j]
            );
            let slack = 1e-12 * (1.0 + pose.translation.vector.norm());
            let gap_a = analytic_surface_gap(CONVEX_MODELS[i], &d.point_a);
            let gap_b =
                analytic_surface_gap(CONVEX_MODELS[j], &pose.inverse_transform_point(&d.point_b));
            assert!(
                gap_a <= a.tree.eps + slack,
                "{label}: point_a {gap_a:e} off"
            );
            assert!(
                gap_b <= b.tree.eps + slack,
                "{label}: point_b {gap_b:e} off"
            );
            let pair = (d.point_a - d.point_b).norm();
            assert!(
                (pair - d.value).abs() <= slack,
                "{label}: |pa - pb| {pair} value {}",
                d.value
            );
            let reference = distance(a, &bp, &traversal_exact());
            let width = tolerance.width(a.tree.target_eps, b.tree.target_eps);
            assert!(
                d.value >= reference.lower - slack && d.value - reference.value <= width + slack,
                "{label}: value {} traversal {} [{}, {}]",
                d.value,
                reference.value,
                reference.lower,
                reference.upper
            );
        }
    }
    assert!(checked >= 400, "{checked} of {queries} checked");
}

/// Probe (`docs/performance.md`, the convex path): how often the hulls of non-convex solids (GJK on the
/// supports of their chains' hulls, witnesses moved to the surfaces) would answer a close
/// query at the default width, and what that costs against the traversal.
#[test]
#[ignore = "probe: hull bound for non-convex pairs"]
fn probe_hull_bound_for_non_convex() {
    use crate::bvh::convex::SupportTable;
    use std::time::Instant;
    let mut rng = SplitMix64(0x4A11);
    let names = [
        "pawn",
        "cup",
        "bottle",
        "table",
        "lightmill",
        "pawn_ff",
        "cup_ff",
    ];
    let eps = 1e-4;
    let solids: Vec<Solid> = names.iter().map(|n| solid(n, eps)).collect();
    let tables: Vec<SupportTable> = solids
        .iter()
        .map(|s| SupportTable::of_chain(&s.tree.chain).unwrap())
        .collect();
    for i in 0..names.len() {
        for j in i..names.len() {
            let (a, b) = (&solids[i], &solids[j]);
            let (mut ok, mut n, mut t_hull, mut t_trav) = (0, 0, 0.0, 0.0);
            for _ in 0..40 {
                let gap = 10f64.powf(rng.range(-3.0, -1.0));
                let Some(pose) = near_touching(a, b, &mut rng, gap) else {
                    continue;
                };
                let bp = b.with_pose(pose);
                let pos_ab = a.relative_pose(&bp);
                let rot = pos_ab.rotation.to_rotation_matrix();
                let shift = pos_ab.translation.vector;
                let t0 = Instant::now();
                let r = super::gjk::gjk(
                    |d| tables[i].support(d),
                    |d| rot * tables[j].support(&rot.inverse_transform_vector(d)) + shift,
                    Vector3::x(),
                    1e-4,
                    1e-14,
                );
                let v = r.point_a - r.point_b;
                let qa = super::witness::nearest_surface_point(&a.tree, &r.point_a, &-v);
                let qb = pos_ab
                    * super::witness::nearest_surface_point(
                        &bp.tree,
                        &pos_ab.inverse_transform_point(&r.point_b),
                        &pos_ab.inverse_transform_vector(&v),
                    );
                let value = (qa - qb).norm();
                t_hull += t0.elapsed().as_secs_f64();
                let t1 = Instant::now();
                let d = distance(a, &bp, &QueryOptions::default());
                t_trav += t1.elapsed().as_secs_f64();
                n += 1;
                if !r.intersect && value - r.lower <= 2e-4 {
                    ok += 1;
                    assert!(r.lower - 2e-4 <= d.upper, "{} {}", r.lower, d.upper);
                }
            }
            println!(
                "{:>10}-{:<10} answered {ok:>2}/{n}  hull {:.2} us  traversal {:.1} us",
                names[i],
                names[j],
                t_hull / n as f64 * 1e6,
                t_trav / n as f64 * 1e6
            );
        }
    }
}

/// The ball path (`ball.rs`): a ball against each convex model, either order, answers the
/// close poses itself (no GJK iteration), holds the traversal's distance at tolerance 0,
/// with witnesses on the analytic surfaces; a ball whose centre is inside the other solid,
/// or that overlaps it, is left to GJK (overlap certified or declined), never answered
/// apart.
#[test]
fn ball_path_answers_close_poses_and_leaves_overlaps_to_gjk() {
    let mut rng = SplitMix64(0xBA11);
    let ball = solid("sphere", 1e-4);
    let (mut planar, mut total) = (0, 0);
    for name in CONVEX_MODELS {
        let other = solid(name, 1e-4);
        for k in 0..60 {
            let (a, b, na, nb) = if k % 2 == 0 {
                (&ball, &other, "sphere", name)
            } else {
                (&other, &ball, name, "sphere")
            };
            let gap = if k % 3 == 0 {
                -10f64.powf(rng.range(-3.0, -0.5))
            } else {
                10f64.powf(rng.range(-6.0, -1.0))
            };
            let Some(pose) = near_touching(a, b, &mut rng, gap) else {
                continue;
            };
            let bp = b.with_pose(pose);
            let pos_ab = a.relative_pose(&bp);
            let slack = query_slack(&a.tree, &bp.tree, &pos_ab);
            let width = 2e-4;
            let reference = distance(a, &bp, &traversal_exact());
            let label = format!("{na}-{nb} pose {k} gap {gap:e}");
            total += 1;
            let Some((r, trace)) =
                super::convex_distance_traced(&a.tree, &bp.tree, &pos_ab, slack, width)
            else {
                assert!(gap < 0.0 || name == "sphere", "{label}: declined");
                continue;
            };
            assert!(
                r.lower <= reference.upper + 1e-12 && reference.lower <= r.upper + 1e-12,
                "{label}: [{}, {}] vs [{}, {}]",
                r.lower,
                r.upper,
                reference.lower,
                reference.upper
            );
            if gap < 0.0 {
                assert!(r.overlap || r.lower == 0.0, "{label}: answered apart");
                continue;
            }
            planar += (trace.method == super::Method::Ball) as usize;
            assert!(!r.overlap && r.upper - r.lower <= width, "{label}: {r:?}");
            let w = (r.point_a - r.point_b).norm();
            assert!((w - r.value).abs() <= 1e-14, "{label}: witnesses");
            let gap_a = analytic_surface_gap(na, &r.point_a);
            let gap_b = analytic_surface_gap(nb, &pos_ab.inverse_transform_point(&r.point_b));
            assert!(
                gap_a <= 1e-4 && gap_b <= 1e-4,
                "{label}: {gap_a:e} {gap_b:e}"
            );
        }
    }
    println!("{planar} of {total} answered by the ball path");
    assert!(planar >= total / 2, "{planar} of {total}");
}

/// The rim solver (`rim.rs`) answers a share of the close poses of the pairs with creases
/// (cylinder and cone edges), and those answers hold the traversal's distance at
/// tolerance 0, with witnesses on the analytic surfaces and the value within the width.
#[test]
fn rim_answers_hold_the_traversals_distance() {
    let mut rng = SplitMix64(0x0213);
    let names = ["capsule", "cylinder", "cone"];
    let solids: Vec<Solid> = names.iter().map(|n| solid(n, 1e-4)).collect();
    let (mut by_rim, mut total) = (0, 0);
    for i in 0..3 {
        for j in i..3 {
            let (a, b) = (&solids[i], &solids[j]);
            for k in 0..80 {
                let gap = 10f64.powf(rng.range(-5.0, -1.0));
                let Some(pose) = near_touching(a, b, &mut rng, gap) else {
                    continue;
                };
                let bp = b.with_pose(pose);
                let pos_ab = a.relative_pose(&bp);
                let slack = query_slack(&a.tree, &bp.tree, &pos_ab);
                let width = if k % 2 == 0 { 2e-4 } else { 1e-7 };
                let label = format!(
                    "{}-{} pose {k} gap {gap:e} width {width:e}",
                    names[i], names[j]
                );
                total += 1;
                let Some((r, trace)) =
                    super::convex_distance_traced(&a.tree, &bp.tree, &pos_ab, slack, width)
                else {
                    continue;
                };
                if trace.method != super::Method::Rim {
                    continue;
                }
                by_rim += 1;
                let reference = distance(a, &bp, &traversal_exact());
                assert!(
                    r.lower <= reference.upper + 1e-12 && reference.lower <= r.upper + 1e-12,
                    "{label}: [{}, {}] vs [{}, {}]",
                    r.lower,
                    r.upper,
                    reference.lower,
                    reference.upper
                );
                assert!(
                    !r.overlap && r.upper - r.lower <= width.max(floor(a, &bp)),
                    "{label}"
                );
                assert!(
                    (r.value - reference.value).abs() <= width + 4e-4,
                    "{label}: value {} vs {}",
                    r.value,
                    reference.value
                );
                assert!(
                    ((r.point_a - r.point_b).norm() - r.value).abs() <= 1e-14,
                    "{label}"
                );
                let gap_a = analytic_surface_gap(names[i], &r.point_a);
                let gap_b =
                    analytic_surface_gap(names[j], &pos_ab.inverse_transform_point(&r.point_b));
                assert!(
                    gap_a <= 1e-4 && gap_b <= 1e-4,
                    "{label}: {gap_a:e} {gap_b:e}"
                );
            }
        }
    }
    println!("{by_rim} of {total} answered by the rim solver");
    assert!(by_rim * 5 >= total, "{by_rim} of {total}");
}
