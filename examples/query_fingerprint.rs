//! A fingerprint of the query's answers: seeded queries over the built-in models (balls and
//! solid tori for the closed form, convex pairs for the convex path, the paper's solids for
//! the search; poses apart, near touching and overlapping; some refined, some at tolerance
//! 0, some with a node-pair budget, some with the fast paths switched off), plus gradients,
//! width limits, a batch, penetration depths and times of impact. It prints one FNV-1a hash
//! per group and one over all of them, of the raw bits of every answer field and every
//! deterministic counter (the wall-time counters are left out).
//!
//! Two builds that print the same hashes answer these queries bit for bit the same; a
//! refactoring that must not change behaviour is checked with it:
//!
//! ```text
//! cargo run --release --example query_fingerprint
//! ```
//!
//! `FINGERPRINT_TRACE=1` also prints each pose query's answer on stderr, to diff two builds.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::models::model;
use revdist::query::{
    distance, penetration, signed_distance, Budget, Distance, Gradient, QueryOptions, Tolerance,
    TraversalStats,
};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use revdist::toi::{time_of_impact, Motion, ToiOptions};
use std::sync::Arc;

/// FNV-1a over 64-bit words.
struct Fnv(u64);

impl Fnv {
    fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for byte in w.to_le_bytes() {
            self.0 ^= byte as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn f(&mut self, x: f64) {
        self.word(x.to_bits());
    }
    fn point(&mut self, p: &Point3<f64>) {
        p.coords.iter().for_each(|&x| self.f(x));
    }
    fn vector(&mut self, v: &Vector3<f64>) {
        v.iter().for_each(|&x| self.f(x));
    }
    fn stats(&mut self, s: &TraversalStats) {
        for n in [
            s.node_pairs,
            s.leaf_bounds,
            s.leaf_tightened,
            s.leaf_tests,
            s.patch_bounds,
            s.patch_tests,
            s.bound_tests,
            s.max_queue,
            s.closed_forms,
            s.convex_paths,
            s.subdivided_pairs,
        ] {
            self.word(n as u64);
        }
        self.word(s.budget_exhausted as u64);
    }
    fn distance(&mut self, d: &Distance) {
        for x in [d.value, d.lower, d.upper] {
            self.f(x);
        }
        self.point(&d.point_a);
        self.point(&d.point_b);
        self.word(d.overlap as u64);
        self.stats(&d.stats);
    }
    fn gradient(&mut self, g: Option<Gradient>) {
        match g {
            None => self.word(u64::MAX),
            Some(g) => {
                self.vector(&g.normal);
                self.vector(&g.translation);
                self.vector(&g.rotation);
            }
        }
    }
}

/// 0 closed form, 1 convex path, 2 search.
fn path(d: &Distance) -> usize {
    if d.stats.closed_forms > 0 {
        0
    } else if d.stats.convex_paths > 0 {
        1
    } else {
        2
    }
}

fn solid(name: &str, eps: f64) -> Solid {
    let profile = Arc::new(model(name).expect("built-in model"));
    Solid::from_profile(profile, eps).expect("tree of a built-in model")
}

/// Bounding radius of a solid about its frame origin.
fn radius(s: &Solid) -> f64 {
    let t = &s.tree;
    let n = &t.nodes[t.root as usize];
    n.bound.center.coords.norm() + n.bound.radius
}

fn rotation(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    let [w, x, y, z] = rng.quaternion();
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
}

/// A random pose of B about A at a distance between the solids' centres drawn across
/// overlap, near touching and apart.
fn pose(rng: &mut SplitMix64, ra: f64, rb: f64) -> Isometry3<f64> {
    let reach = rng.range(0.0, 1.3) * (ra + rb);
    Isometry3::from_parts(Translation3::from(rng.direction() * reach), rotation(rng))
}

/// Options varied by the query's index: mostly the defaults; every seventh refined, every
/// eleventh at tolerance 0, every thirteenth with a node-pair budget, every seventeenth
/// without the fast paths.
fn options(k: usize) -> QueryOptions {
    let mut o = QueryOptions::default();
    if k % 7 == 3 {
        o.refine = true;
    }
    if k % 11 == 5 {
        o.tolerance = Tolerance::Absolute(0.0);
    }
    if k % 13 == 7 {
        o.budget = Budget {
            max_node_pairs: Some(20),
            max_time: None,
        };
    }
    if k % 17 == 2 {
        o.closed_form = false;
        o.convex_path = false;
    }
    o
}

/// With `FINGERPRINT_TRACE` set, one line per pose query on stderr (to find which
/// queries two builds answer differently: diff the two outputs).
fn trace(na: &str, nb: &str, k: usize, d: &Distance) {
    if std::env::var_os("FINGERPRINT_TRACE").is_some() {
        eprintln!(
            "{na}-{nb} {k}: [{:e}, {:e}] value {:e} overlap {} {:?}",
            d.lower, d.upper, d.value, d.overlap, d.stats
        );
    }
}

fn main() {
    let pairs: &[(&str, &str, f64)] = &[
        ("sphere", "sphere", 1e-3),
        ("sphere", "ring", 1e-3),
        ("ring", "ring", 1e-4),
        ("sphere", "capsule", 1e-3),
        ("capsule", "capsule", 1e-4),
        ("capsule", "cylinder", 1e-3),
        ("cylinder", "cone", 1e-3),
        ("cone", "cone", 1e-4),
        ("sphere", "cylinder", 1e-4),
        ("pawn", "pawn", 1e-3),
        ("pawn", "cup", 1e-4),
        ("cup", "bottle", 1e-3),
        ("table", "lightmill", 1e-3),
        ("pawn_ff", "cup_ff", 1e-3),
        ("bottle_ff", "ring", 1e-3),
        ("sphere", "pawn", 1e-3),
    ];
    let mut total = Fnv::new();
    let mut queries = 0usize;
    let mut rng = SplitMix64(0x5eed_f1a9);
    let report = |name: &str, h: &Fnv, total: &mut Fnv| {
        println!("{name:<28} {:016x}", h.0);
        total.word(h.0);
    };
    let mut batch_pairs = Vec::new();
    // Which path answered (closed form, convex, search), overlaps and refined queries: to
    // show the groups cover every path; not hashed.
    let mut paths = [0usize; 5];
    for &(na, nb, eps) in pairs {
        let (a0, b0) = (solid(na, eps), solid(nb, eps));
        let (ra, rb) = (radius(&a0), radius(&b0));
        let mut h = Fnv::new();
        for k in 0..64 {
            let a = a0.with_pose(Isometry3::from_parts(
                Translation3::from(rng.direction() * rng.range(0.0, 0.5)),
                rotation(&mut rng),
            ));
            let pb = a.pose * pose(&mut rng, ra, rb);
            let b = b0.with_pose(pb);
            let opts = options(k);
            let d = distance(&a, &b, &opts);
            trace(na, nb, k, &d);
            queries += 1;
            paths[path(&d)] += 1;
            paths[3] += d.overlap as usize;
            paths[4] += opts.refine as usize;
            h.distance(&d);
            h.gradient(d.gradient(&Point3::from(pb.translation.vector)));
            let limit = revdist::query::width_limit(&a, &b, &opts, &d);
            h.word(limit as u64);
            // Near touching: B moved along the witnesses' direction to a chosen gap.
            let dir = d.point_b - d.point_a;
            if k % 2 == 0 && !d.overlap && dir.norm() > 0.0 && d.value.is_finite() {
                let gap = [1e-2, 1e-4, 1e-7, 0.0, -1e-3][(k / 2) % 5];
                let shift = dir.normalize() * (gap - d.value);
                let moved = Isometry3::from_parts(
                    Translation3::from(pb.translation.vector + shift),
                    pb.rotation,
                );
                let b2 = b0.with_pose(moved);
                let d2 = distance(&a, &b2, &opts);
                trace(na, nb, k, &d2);
                queries += 1;
                paths[path(&d2)] += 1;
                paths[3] += d2.overlap as usize;
                paths[4] += opts.refine as usize;
                h.distance(&d2);
                h.gradient(d2.gradient(&Point3::from(moved.translation.vector)));
                if k % 16 == 0 {
                    batch_pairs.push((a.clone(), b2));
                }
            }
        }
        report(&format!("{na}-{nb}@{eps:e}"), &h, &mut total);
    }

    let mut h = Fnv::new();
    for d in revdist::query::distances(&batch_pairs, &QueryOptions::default()) {
        queries += 1;
        h.distance(&d);
    }
    report("batch", &h, &mut total);

    // Penetration depth and signed distance on overlapping and touching poses.
    let mut h = Fnv::new();
    for &(na, nb) in &[
        ("sphere", "sphere"),
        ("sphere", "pawn"),
        ("capsule", "cone"),
        ("pawn", "cup"),
    ] {
        let (a, b0) = (solid(na, 1e-3), solid(nb, 1e-3));
        let (ra, rb) = (radius(&a), radius(&b0));
        for _ in 0..8 {
            let reach = rng.range(0.0, 0.9) * (ra + rb);
            let pb = Isometry3::from_parts(
                Translation3::from(rng.direction() * reach),
                rotation(&mut rng),
            );
            let b = b0.with_pose(pb);
            match penetration(&a, &b, &QueryOptions::default()) {
                Ok(p) => {
                    h.f(p.lower);
                    h.f(p.upper);
                    h.vector(&p.direction);
                    p.point.iter().for_each(|x| h.point(x));
                    p.contact_b.iter().for_each(|x| h.point(x));
                    h.word(p.narrow as u64);
                    h.word(p.stats.probes as u64);
                    h.word(p.stats.distance_queries as u64);
                    h.word(p.stats.budget_exhausted as u64);
                }
                Err(_) => h.word(1),
            }
            match signed_distance(&a, &b, &QueryOptions::default()) {
                Ok(s) => {
                    h.f(s.lower);
                    h.f(s.upper);
                    h.distance(&s.distance);
                    h.gradient(s.gradient(&Point3::from(pb.translation.vector)));
                }
                Err(_) => h.word(2),
            }
            queries += 2;
        }
    }
    report("penetration", &h, &mut total);

    // Times of impact: B flies past or into A.
    let mut h = Fnv::new();
    for &(na, nb) in &[("sphere", "capsule"), ("pawn", "cup"), ("ring", "ring")] {
        let (a, b) = (solid(na, 1e-3), solid(nb, 1e-3));
        let (ra, rb) = (radius(&a), radius(&b));
        let ma = Motion::fixed(Isometry3::identity()).expect("fixed motion");
        for _ in 0..6 {
            let from = rng.direction() * (2.0 * (ra + rb));
            let to = rng.direction() * rng.range(0.0, 1.2) * (ra + rb);
            let mb = Motion::new(
                Isometry3::from_parts(Translation3::from(from), rotation(&mut rng)),
                Isometry3::from_parts(Translation3::from(to), rotation(&mut rng)),
            )
            .expect("motion");
            match time_of_impact(&a, &ma, &b, &mb, &ToiOptions::default()) {
                Ok(t) => {
                    h.word(t.outcome as u64);
                    h.f(t.t_lower);
                    t.t_upper.iter().for_each(|&x| h.f(x));
                    t.contact.iter().for_each(|d| h.distance(d));
                    h.word(t.queries as u64);
                    h.word(t.steps as u64);
                    h.word(t.certificates as u64);
                    h.f(t.speed_bound);
                    h.stats(&t.stats);
                    queries += t.queries;
                }
                Err(_) => h.word(3),
            }
        }
    }
    report("time of impact", &h, &mut total);

    println!(
        "queries {queries}; of the pose groups: closed form {}, convex {}, search {}, overlap {}, refined {}",
        paths[0], paths[1], paths[2], paths[3], paths[4]
    );
    println!("fingerprint {:016x}", total.0);
}
