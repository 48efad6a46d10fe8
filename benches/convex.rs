//! The convex fast path against the traversal: per pair of the convex built-in models
//! (sphere, capsule, cylinder, cone: all 10 pairs) and a pair of convex freeform profiles,
//! the median time of one query over seeded close poses (gaps 1e-4..1e-1, placed along the
//! closest points' normal), with `QueryOptions::convex_path` on and off. Each pose's time is
//! the mean of repeated runs; the table gives the median over poses.
//!
//! Run: `cargo bench --bench convex` (plain timing loop, no criterion).

use nalgebra::{Isometry3, Point2, Translation3, UnitQuaternion, Vector3};
use revdist::models::model;
use revdist::nurbs::NurbsCurve;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions, Tolerance};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

const MODELS: [&str; 4] = ["sphere", "capsule", "cylinder", "cone"];
const EPS: f64 = 1e-4;
const POSES: usize = 100;

/// A unit vector: rejection sampling in the shell 0.05..0.5 of the cube [-0.5, 0.5)^3.
fn unit(rng: &mut SplitMix64) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
            rng.next_f64() - 0.5,
        );
        if v.norm() > 0.05 && v.norm() < 0.5 {
            return v.normalize();
        }
    }
}

/// Close poses: B far along a random direction, then moved back along the normal of the
/// closest points to a gap in 1e-4..1e-1 (exact for convex solids).
fn close_poses(a: &Solid, b: &Solid, rng: &mut SplitMix64) -> Vec<Isometry3<f64>> {
    let exact = QueryOptions {
        tolerance: Tolerance::Absolute(0.0),
        convex_path: false,
        closed_form: false,
        ..QueryOptions::default()
    };
    let mut out = Vec::new();
    while out.len() < POSES {
        let rot = UnitQuaternion::from_scaled_axis(unit(rng) * (rng.next_f64() * 3.0));
        let far = Isometry3::from_parts(Translation3::from(unit(rng) * 3.0), rot);
        let d = distance(a, &b.with_pose(far), &exact);
        let Some(n) = (d.point_b - d.point_a).try_normalize(0.0) else {
            continue;
        };
        let gap = 10f64.powf(-4.0 + 3.0 * rng.next_f64());
        out.push(Translation3::from(-n * (d.value - gap)) * far);
    }
    out
}

/// Median over poses of the mean time of `reps` queries, in microseconds.
fn median_us(a: &Solid, bs: &[Solid], opts: &QueryOptions, reps: usize) -> f64 {
    let mut times: Vec<f64> = bs
        .iter()
        .map(|b| {
            let t0 = Instant::now();
            for _ in 0..reps {
                black_box(distance(black_box(a), black_box(b), opts));
            }
            t0.elapsed().as_secs_f64() * 1e6 / reps as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn solid(p: Profile) -> Solid {
    Solid::from_profile(Arc::new(p), EPS).expect("tree")
}

/// A superellipse-like convex profile of two cubic Bezier pieces.
fn freeform(a: f64, h: f64, k: [f64; 4]) -> Profile {
    let cubic = |p: [[f64; 2]; 4]| {
        NurbsCurve::bezier(p.iter().map(|q| Point2::new(q[0], q[1])).collect()).expect("cubic")
    };
    Profile::new(
        "freeform",
        vec![
            cubic([[0.0, 0.0], [k[0] * a, 0.0], [a, h - k[1] * h], [a, h]]),
            cubic([
                [a, h],
                [a, h + k[2] * h],
                [k[3] * a, 2.0 * h],
                [0.0, 2.0 * h],
            ]),
        ],
    )
    .expect("convex profile")
}

fn main() {
    let mut rng = SplitMix64(0xC0FFEE);
    let on = QueryOptions {
        convex_path: true,
        ..QueryOptions::default()
    };
    let off = QueryOptions {
        convex_path: false,
        ..QueryOptions::default()
    };
    let mut named: Vec<(String, Solid)> = MODELS
        .iter()
        .map(|n| (n.to_string(), solid(model(n).expect("model"))))
        .collect();
    named.push((
        "freeform_a".into(),
        solid(freeform(0.6, 0.7, [0.3, 0.6, 0.5, 0.4])),
    ));
    named.push((
        "freeform_b".into(),
        solid(freeform(0.4, 0.9, [0.8, 0.2, 0.3, 0.7])),
    ));
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for i in 0..MODELS.len() {
        for j in i..MODELS.len() {
            pairs.push((i, j));
        }
    }
    pairs.extend([(4, 5), (0, 4), (3, 5)]);
    println!("eps {EPS:e}, {POSES} close poses per pair, median us per query");
    println!(
        "{:<22} {:>9} {:>9} {:>8} {:>10}",
        "pair", "fast on", "fast off", "speedup", "fast used"
    );
    for (i, j) in pairs {
        let (a, b) = (&named[i].1, &named[j].1);
        let bs: Vec<Solid> = close_poses(a, b, &mut rng)
            .into_iter()
            .map(|p| b.with_pose(p))
            .collect();
        let used: usize = bs
            .iter()
            .map(|b| distance(a, b, &on).stats.convex_paths)
            .sum();
        let t_on = median_us(a, &bs, &on, 200);
        let t_off = median_us(a, &bs, &off, 5);
        println!(
            "{:<22} {:>9.2} {:>9.2} {:>7.0}x {:>6}/{}",
            format!("{}-{}", named[i].0, named[j].0),
            t_on,
            t_off,
            t_off / t_on,
            used,
            bs.len()
        );
    }
}
