//! The shapes cases draw from: built-in models, M_t frames, the frozen and seeded random
//! profiles, and the balls and solid tori of the primitive campaign.

use super::regressions::frozen_profiles;
use crate::oracle::{self, PlanarIndex};
use crate::random_profiles::{random_profile, SplitMix64};
use revdist::profile::Profile;
use std::sync::Arc;

/// A profile of the pool.
pub struct Shape {
    /// Built-in name, or the reproducer file name for random profiles.
    pub name: String,
    pub profile: Arc<Profile>,
    pub index: PlanarIndex,
    /// Random profiles are written out for reproducers.
    pub random: bool,
    /// Rough size class (for nesting): the index's bounding diagonal.
    pub size: f64,
    /// revdist certifies the solid convex (its queries against other convex solids take the
    /// GJK path).
    pub convex: bool,
}

/// The pool: built-in models, M_t frames every 0.05, random profiles of three size classes.
pub fn build_pool(seed: u64, n_random: usize) -> Vec<Shape> {
    let mut shapes = Vec::new();
    let mut push = |name: String, p: Profile, random: bool| {
        let index = oracle::index(&p);
        let size = index.geom.size;
        let convex = revdist::bvh::convex::certify_convex(&p).is_some();
        shapes.push(Shape {
            name,
            profile: Arc::new(p),
            index,
            random,
            size,
            convex,
        });
    };
    for name in revdist::models::model_names() {
        push(
            name.to_string(),
            revdist::models::model(name).expect("built-in"),
            false,
        );
    }
    for i in 0..=20 {
        let name = format!("morph@{:.2}", i as f64 * 0.05);
        let name = name.trim_end_matches('0').trim_end_matches('.').to_string();
        let p = revdist::models::model(&name).expect("morph frame");
        push(name, p, false);
    }
    push("straight-span".into(), straight_span_profile(), true);
    for (name, p) in frozen_profiles() {
        push(format!("frozen-{name}"), p, true);
    }
    let base = SplitMix64(seed ^ 0x05EE_D0FF_11E5);
    for k in 0..n_random {
        let mut rng = base.fork(k as u64);
        // Mostly unit-sized; every fifth large (outer solids for nesting), every fifth tiny.
        let size = match k % 5 {
            3 => rng.range(3.0, 5.0),
            4 => rng.range(0.08, 0.3),
            _ => rng.range(0.6, 2.0),
        };
        let name = format!("rand-s{seed}-{k}");
        let (p, _) = random_profile(&mut rng, &name, size);
        push(name, p, true);
    }
    for (name, p) in primitive_profiles() {
        push(name, p, false);
    }
    shapes
}

/// Name prefix of the balls and solid tori appended to the pool (after every other shape,
/// so the default campaign's draws are unchanged).
pub const PRIMITIVE_PREFIX: &str = "prim-";

/// Balls and solid tori of several proportions (one circle per profile): a thin ring that
/// interlocks with itself, a fat one, a small ball, a ball off the origin and a big ball
/// (room for nesting).
fn primitive_profiles() -> Vec<(String, Profile)> {
    use revdist::models::primitives::{arc, deg};
    let torus = |name: &str, rho: f64, z: f64, r: f64| {
        let c = arc([rho, z], r, deg(-90.0), deg(270.0)).expect("valid circle");
        (
            name.to_string(),
            Profile::new(name, vec![c]).expect("valid torus"),
        )
    };
    let ball = |name: &str, z: f64, r: f64| {
        let c = arc([0.0, z], r, deg(-90.0), deg(90.0)).expect("valid half circle");
        (
            name.to_string(),
            Profile::new(name, vec![c]).expect("valid ball"),
        )
    };
    vec![
        torus("prim-torus-thin", 1.0, 0.0, 0.12),
        torus("prim-torus-fat", 0.5, 0.2, 0.45),
        ball("prim-ball", 0.0, 0.3),
        ball("prim-ball-high", 0.7, 0.5),
        ball("prim-ball-big", 0.0, 3.5),
    ]
}

/// A profile with an exactly straight span (a cubic with three collinear control points on
/// rho = 0.57), once answered 0 with a witness below the solid.
pub fn straight_span_profile() -> Profile {
    let pts = [
        [0.0, 0.0],
        [0.57, 0.0],
        [0.57, 0.3],
        [0.57, 0.48],
        [0.57, 1.14],
        [0.0, 1.14],
    ];
    let c = revdist::nurbs::NurbsCurve::new(
        3,
        vec![
            0.0,
            0.0,
            0.0,
            0.0,
            0.3333333333333333,
            0.6666666666666666,
            1.0,
            1.0,
            1.0,
            1.0,
        ],
        pts.iter()
            .map(|q| nalgebra::Point2::new(q[0], q[1]))
            .collect(),
        None,
    )
    .expect("valid curve");
    Profile::new("straight-span", vec![c]).expect("valid profile")
}

/// Which shapes a campaign draws from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeSet {
    /// The whole pool: built-in models, M_t frames, random profiles.
    All,
    /// Balls and solid tori ([`PRIMITIVE_PREFIX`] shapes, `ring`, `sphere`): the closed form.
    Primitives,
    /// Solids whose convexity revdist certifies (`revdist::bvh::convex::certify_convex`):
    /// the GJK path. The oracle knows nothing of convexity.
    Convex,
}

/// Draws a shape index from the pool: built-in, M_t frame or random (of a size class).
pub(super) fn pick(
    rng: &mut SplitMix64,
    shapes: &[Shape],
    class: Option<&str>,
    set: ShapeSet,
) -> usize {
    if set != ShapeSet::All {
        let in_set: Vec<usize> = (0..shapes.len())
            .filter(|&i| {
                let n = &shapes[i].name;
                match set {
                    ShapeSet::Primitives => {
                        n.starts_with(PRIMITIVE_PREFIX) || n == "ring" || n == "sphere"
                    }
                    _ => shapes[i].convex,
                }
            })
            .collect();
        let of_class: Vec<usize> = in_set
            .iter()
            .copied()
            .filter(|&i| match class {
                Some("big") => shapes[i].size >= 3.0,
                Some("tiny") => shapes[i].size < 1.0,
                _ => true,
            })
            .collect();
        let from = if of_class.is_empty() {
            &in_set
        } else {
            &of_class
        };
        return from[rng.int(0, from.len() - 1)];
    }
    let random: Vec<usize> = (0..shapes.len())
        .filter(|&i| shapes[i].random && shapes[i].name.starts_with("rand"))
        .collect();
    let by_class = |lo: f64, hi: f64| -> Vec<usize> {
        random
            .iter()
            .copied()
            .filter(|&i| shapes[i].size >= lo && shapes[i].size < hi)
            .collect()
    };
    let from = |rng: &mut SplitMix64, v: &[usize]| v[rng.int(0, v.len() - 1)];
    match class {
        Some("big") => {
            let v = by_class(3.0, f64::INFINITY);
            if v.is_empty() {
                from(rng, &random)
            } else {
                from(rng, &v)
            }
        }
        Some("tiny") => {
            let v = by_class(0.0, 0.45);
            if v.is_empty() {
                from(rng, &random)
            } else {
                from(rng, &v)
            }
        }
        _ => {
            let u = rng.unit();
            let statics = revdist::models::model_names().len();
            if u < 0.3 || random.is_empty() {
                rng.int(0, statics - 1)
            } else if u < 0.5 {
                rng.int(statics, statics + 20)
            } else {
                let v = by_class(0.45, 3.0);
                from(rng, if v.is_empty() { &random } else { &v })
            }
        }
    }
}
