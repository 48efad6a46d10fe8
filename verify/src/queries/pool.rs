//! The shapes cases draw from: built-in models, M_t frames, the frozen and seeded random
//! profiles, and the balls, capsules and solid tori of the primitive campaign.

use super::frozen::frozen_profiles;
use crate::oracle::{self, PlanarIndex};
use crate::random_profiles::random_profile;
use revdist::profile::Profile;
use revdist::rng::SplitMix64;
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
    push(STRAIGHT_SPAN.into(), straight_span_profile(), true);
    for (name, p) in frozen_profiles() {
        push(format!("{FROZEN_PREFIX}{name}"), p, true);
    }
    for k in 0..n_random {
        push(random_name(seed, k), random_pool_profile(seed, k), true);
    }
    for (name, p) in primitive_profiles() {
        push(name, p, false);
    }
    shapes
}

/// Mixed into the campaign's seed for the random profiles' stream (so that it differs from
/// the cases' streams drawn from the same seed).
const RANDOM_PROFILES_STREAM: u64 = 0x05EE_D0FF_11E5;

/// Name prefix of the seeded random profiles: `rand-s<SEED>-<K>`.
const RANDOM_PREFIX: &str = "rand-s";

/// Name prefix of the frozen random profiles (`verify/regressions/<name>.toml`).
pub const FROZEN_PREFIX: &str = "frozen-";

/// Name of the profile with an exactly straight span ([`straight_span_profile`]).
const STRAIGHT_SPAN: &str = "straight-span";

/// The pool's name of random profile `k` of campaign seed `seed`.
fn random_name(seed: u64, k: usize) -> String {
    format!("{RANDOM_PREFIX}{seed}-{k}")
}

/// Random profile `k` of campaign seed `seed`: each is drawn from its own fork of the seed's
/// stream, so one can be rebuilt alone (by name, for `verify oracle`) exactly as the pool
/// holds it.
fn random_pool_profile(seed: u64, k: usize) -> Profile {
    let mut rng = SplitMix64(seed ^ RANDOM_PROFILES_STREAM).fork(k as u64);
    // Mostly unit-sized; every fifth large (outer solids for nesting), every fifth tiny.
    let size = match k % 5 {
        3 => rng.range(3.0, 5.0),
        4 => rng.range(0.08, 0.3),
        _ => rng.range(0.6, 2.0),
    };
    random_profile(&mut rng, &random_name(seed, k), size).0
}

/// `(seed, k)` of a name `rand-s<SEED>-<K>`.
fn parse_random_name(name: &str) -> Option<(u64, usize)> {
    let (seed, k) = name.strip_prefix(RANDOM_PREFIX)?.split_once('-')?;
    Some((seed.parse().ok()?, k.parse().ok()?))
}

/// A shape of the pool by the name the campaigns print (`verify queries` in every mode,
/// `verify toi`, `verify crosscheck`), rebuilt alone: a built-in model or `morph@T`,
/// `straight-span`, a primitive (`prim-...`), a frozen profile (`frozen-<name>`) or a seeded
/// random profile (`rand-s<SEED>-<K>`). `None`: not a pool name; `Some(Err)`: a pool name
/// whose profile cannot be built (a bad `morph@T`).
pub fn pool_shape(name: &str) -> Option<Result<Profile, String>> {
    match revdist::models::model(name) {
        Ok(p) => return Some(Ok(p)),
        Err(revdist::models::ModelError::UnknownModel { .. }) => {}
        Err(e) => return Some(Err(e.to_string())),
    }
    if name == STRAIGHT_SPAN {
        return Some(Ok(straight_span_profile()));
    }
    let known = |list: Vec<(String, Profile)>, wanted: &str| {
        list.into_iter()
            .find(|(n, _)| n == wanted)
            .map(|(_, p)| Ok(p))
    };
    if name.starts_with(PRIMITIVE_PREFIX) {
        return known(primitive_profiles(), name);
    }
    if let Some(frozen) = name.strip_prefix(FROZEN_PREFIX) {
        return known(frozen_profiles(), frozen);
    }
    let (seed, k) = parse_random_name(name)?;
    Some(Ok(random_pool_profile(seed, k)))
}

/// The names [`pool_shape`] accepts, for error messages.
pub fn pool_shape_names() -> String {
    let listed = |list: Vec<(String, Profile)>, prefix: &str| {
        list.into_iter()
            .map(|(n, _)| format!("{prefix}{n}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "the built-in models ({}), {}T with T a number, {STRAIGHT_SPAN}, the primitives ({}), \
         the frozen profiles ({}), or {RANDOM_PREFIX}<SEED>-<K> (random profile K of seed SEED)",
        revdist::models::model_names().join(", "),
        revdist::models::MORPH_PREFIX,
        listed(primitive_profiles(), ""),
        listed(frozen_profiles(), FROZEN_PREFIX),
    )
}

/// Name prefix of the balls and solid tori appended to the pool (after every other shape,
/// so the default campaign's draws are unchanged).
pub const PRIMITIVE_PREFIX: &str = "prim-";

/// Balls, capsules and solid tori of several proportions (offsets of a point, a segment of
/// the axis or a circle): a thin ring that interlocks with itself, a fat one, a small ball, a
/// ball off the origin, a big ball (room for nesting), a long thin capsule and a short fat
/// one.
fn primitive_profiles() -> Vec<(String, Profile)> {
    use revdist::models::primitives::{arc, deg, line, pt};
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
    let capsule = |name: &str, z0: f64, z1: f64, r: f64| {
        let pieces = vec![
            arc([0.0, z0], r, deg(-90.0), 0.0).expect("valid quarter circle"),
            line(pt(r, z0), pt(r, z1)).expect("valid side"),
            arc([0.0, z1], r, 0.0, deg(90.0)).expect("valid quarter circle"),
        ];
        (
            name.to_string(),
            Profile::new(name, pieces).expect("valid capsule"),
        )
    };
    vec![
        capsule("prim-capsule-long", -0.8, 0.9, 0.1),
        capsule("prim-capsule-fat", 0.1, 0.4, 0.6),
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
    Profile::new(STRAIGHT_SPAN, vec![c]).expect("valid profile")
}

/// Which shapes a campaign draws from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeSet {
    /// The whole pool: built-in models, M_t frames, random profiles.
    All,
    /// Balls, capsules and solid tori ([`PRIMITIVE_PREFIX`] shapes, `ring`, `sphere`,
    /// `capsule`): the closed form (capsules against solid tori take the traversal).
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
                        n.starts_with(PRIMITIVE_PREFIX)
                            || ["ring", "sphere", "capsule"].contains(&n.as_str())
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
            let u = rng.next_f64();
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every shape of a campaign's pool (built-in, M_t frames, straight span, frozen,
    /// seeded random, primitives) is rebuilt by its name exactly as the pool holds it.
    #[test]
    fn every_pool_name_rebuilds_its_shape() {
        let shapes = build_pool(5, 6);
        for prefix in [
            "morph@",
            STRAIGHT_SPAN,
            FROZEN_PREFIX,
            RANDOM_PREFIX,
            PRIMITIVE_PREFIX,
        ] {
            assert!(
                shapes.iter().any(|s| s.name.starts_with(prefix)),
                "{prefix}"
            );
        }
        for sh in &shapes {
            let p = pool_shape(&sh.name)
                .unwrap_or_else(|| panic!("'{}' is not a pool name", sh.name))
                .unwrap();
            assert!(p == *sh.profile, "'{}' rebuilds another profile", sh.name);
        }
    }

    #[test]
    fn other_names_are_not_pool_names() {
        for name in [
            "prim-ball-huge",
            "frozen-rand-s1-0",
            "rand-s5",
            "rand-sx-1",
            "rand-s5-1-2",
            "spheres",
            "shapes/sphere.toml",
        ] {
            assert!(pool_shape(name).is_none(), "{name}");
        }
        assert!(pool_shape("morph@x").unwrap().is_err());
        let names = pool_shape_names();
        for listed in [
            "sphere",
            "prim-ball-big",
            "frozen-rand-s1-25",
            "rand-s<SEED>-<K>",
        ] {
            assert!(names.contains(listed), "{listed} missing from: {names}");
        }
    }
}
