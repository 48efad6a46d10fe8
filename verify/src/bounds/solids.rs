//! Whole-solid configurations for the two links of the chain that answer without the
//! traversal: the closed forms of balls, capsules and solid tori (`query/closed_form/mod.rs`) and the
//! convex path's certified interval (`query/convex/`, GJK's dual bound). Each configuration
//! is two primitive solids drawn with random proportions at a scale log-uniform in
//! [1e-3, 1e3], built from exact NURBS profiles, and B's pose: mostly a contact of two
//! surface points (often a rim or a pole) with outward normals opposed, at a gap of 0,
//! `+-1e-13..1e-5` of the scale or a free one ([`super::pieces`]'s gaps).
//!
//! **The check.** The query's `lower` is certified for the true solids. The reference is
//! the smallest MPFR distance of realised pairs of the true surfaces (the same exact
//! circles and segments, as [`ProfileArc`] chains; [`super::nearest`], [`super::exact`]),
//! so `lower <= reference + allowance` must hold whatever the pose; overlapping solids must
//! answer `lower <= 0`, which the same inequality checks. The allowance is the rounding of
//! the NURBS control points of the exact circles, `PROFILE_ROUNDING` of the scale, and
//! nothing else.

use super::chain::{lift_vector, planar_normal, point, Pair, SurfacePoint};
use super::checks::pose_text;
use super::exact::pair_distance;
use super::nearest::nearest_pairs;
use super::pieces::{blend_normals, free_pose, gap, neighbour_normal, surface_point};
use super::report::Tally;
use super::Bound;
use crate::contact;
use nalgebra::{Isometry3, Point2, Vector3};
use revdist::bvh::containment::point_in_solid;
use revdist::bvh::ProfileArc;
use revdist::models::primitives::{arc, deg, line, pt};
use revdist::nurbs::NurbsCurve;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::f64::consts::{FRAC_PI_2, TAU};
use std::sync::Arc;

/// Allowance for the profile's representation: exact circles and segments written as NURBS
/// control points and weights in f64 move the surface by a few ulps of the scale.
const PROFILE_ROUNDING: f64 = 1e-14;

/// Realised pairs of a configuration evaluated in MPFR (the best of the search).
const EXACT_PAIRS: usize = 3;

/// The primitive solids.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Primitive {
    Ball,
    Torus,
    Capsule,
    Cylinder,
    Cone,
    Frustum,
}

impl Primitive {
    fn name(self) -> &'static str {
        match self {
            Primitive::Ball => "ball",
            Primitive::Torus => "torus",
            Primitive::Capsule => "capsule",
            Primitive::Cylinder => "cylinder",
            Primitive::Cone => "cone",
            Primitive::Frustum => "frustum",
        }
    }
}

/// Balls, capsules and solid tori: the closed forms (a capsule against a torus: the search).
const CLOSED_FORM: [Primitive; 3] = [Primitive::Ball, Primitive::Capsule, Primitive::Torus];

/// Convex solids: the convex path.
const CONVEX: [Primitive; 5] = [
    Primitive::Ball,
    Primitive::Capsule,
    Primitive::Cylinder,
    Primitive::Cone,
    Primitive::Frustum,
];

/// One primitive: its exact pieces (the reference's surfaces) and the solid built from the
/// same geometry as NURBS.
struct Shape {
    kind: Primitive,
    pieces: Vec<ProfileArc>,
    solid: Solid,
}

/// An arc piece from `phi0` to `phi1` (radians) about `c`: the NURBS and the exact piece.
fn arc_piece(c: [f64; 2], r: f64, phi0: f64, phi1: f64) -> (NurbsCurve, ProfileArc) {
    let curve = arc(c, r, phi0, phi1).expect("valid arc");
    let piece = ProfileArc::Arc {
        center: Point2::new(c[0], c[1]),
        radius: r,
        phi_start: phi0,
        sweep: phi1 - phi0,
    };
    (curve, piece)
}

fn line_piece(a: Point2<f64>, b: Point2<f64>) -> (NurbsCurve, ProfileArc) {
    let curve = line(a, b).expect("valid segment");
    (curve, ProfileArc::Segment { start: a, end: b })
}

/// A primitive of random proportions at `scale`, with the trees' eps drawn in
/// [1e-8, 1e-4] of the scale (the pieces are exact; the eps sets the trees and the
/// requested width).
fn shape(rng: &mut SplitMix64, kind: Primitive, scale: f64) -> Shape {
    let r = scale * rng.range(0.2, 1.0);
    let h = scale * rng.range(0.2, 2.0);
    let z = scale * rng.range(-0.5, 0.5);
    let parts: Vec<(NurbsCurve, ProfileArc)> = match kind {
        Primitive::Ball => vec![arc_piece([0.0, z], r, -FRAC_PI_2, FRAC_PI_2)],
        Primitive::Torus => {
            let tube = r * rng.range(0.1, 0.95);
            vec![arc_piece([r, z], tube, deg(-90.0), deg(270.0))]
        }
        Primitive::Capsule => vec![
            arc_piece([0.0, z - h / 2.0], r, -FRAC_PI_2, 0.0),
            line_piece(pt(r, z - h / 2.0), pt(r, z + h / 2.0)),
            arc_piece([0.0, z + h / 2.0], r, 0.0, FRAC_PI_2),
        ],
        Primitive::Cylinder => vec![
            line_piece(pt(0.0, z - h / 2.0), pt(r, z - h / 2.0)),
            line_piece(pt(r, z - h / 2.0), pt(r, z + h / 2.0)),
            line_piece(pt(r, z + h / 2.0), pt(0.0, z + h / 2.0)),
        ],
        Primitive::Cone => vec![
            line_piece(pt(0.0, z - h / 2.0), pt(r, z - h / 2.0)),
            line_piece(pt(r, z - h / 2.0), pt(0.0, z + h / 2.0)),
        ],
        Primitive::Frustum => {
            let top = r * rng.range(0.05, 0.95);
            vec![
                line_piece(pt(0.0, z - h / 2.0), pt(r, z - h / 2.0)),
                line_piece(pt(r, z - h / 2.0), pt(top, z + h / 2.0)),
                line_piece(pt(top, z + h / 2.0), pt(0.0, z + h / 2.0)),
            ]
        }
    };
    let (curves, pieces): (Vec<NurbsCurve>, Vec<ProfileArc>) = parts.into_iter().unzip();
    let profile = Profile::new(kind.name(), curves).expect("valid primitive profile");
    let eps = scale * rng.log_range(1e-8, 1e-4);
    let solid = Solid::from_profile(Arc::new(profile), eps).expect("primitive tree");
    Shape {
        kind,
        pieces,
        solid,
    }
}

/// An outward unit normal of `shape` at `x` (at a joint, a blend of the two pieces' normals:
/// the normal cone of a rim), oriented by the solid's own containment test.
fn outward_normal(rng: &mut SplitMix64, shape: &Shape, x: &SurfacePoint) -> Vector3<f64> {
    let chain = &shape.pieces;
    let mut n = planar_normal(&chain[x.piece], x.s);
    if let Some(m) = neighbour_normal(chain, x) {
        // Orient both alike before blending: a segment's left normal points into the solid
        // where an arc's points out of it.
        let m = if m.dot(&n) < 0.0 { -m } else { m };
        n = blend_normals(rng, n, m);
    }
    let n3 = lift_vector(n, x.theta);
    let p = point(chain, x);
    let size = shape.solid.tree.nodes[shape.solid.tree.root as usize]
        .bound
        .radius;
    let inside = point_in_solid(&shape.solid.tree, &(p + n3 * (1e-3 * size))).inside;
    if inside {
        -n3
    } else {
        n3
    }
}

/// A configuration: two shapes and B's pose.
struct SolidConfig {
    a: Shape,
    b: Shape,
    pos_ab: Isometry3<f64>,
    scale: f64,
    contact: Option<Pair>,
}

fn draw(rng: &mut SplitMix64, kinds: &[Primitive]) -> SolidConfig {
    let scale = rng.log_range(1e-3, 1e3);
    let kind_a = *rng.pick(kinds);
    let a = shape(rng, kind_a, scale);
    let (kind_b, scale_b) = (*rng.pick(kinds), scale * rng.log_range(0.3, 3.0));
    let b = shape(rng, kind_b, scale_b);
    let g = gap(rng) * scale;
    let (pos_ab, contact) = if rng.chance(0.85) {
        let p = surface_point(rng, &a.pieces);
        let q = surface_point(rng, &b.pieces);
        let (na, nb) = (outward_normal(rng, &a, &p), outward_normal(rng, &b, &q));
        let (pa, qb) = (point(&a.pieces, &p), point(&b.pieces, &q));
        let spin = rng.range(0.0, TAU);
        let pos = contact::contact_pose((pa.coords, na), (qb.coords, nb), g, spin);
        let pair = Pair::new(&a.pieces, &b.pieces, &pos, p, q);
        (pos, Some(pair))
    } else {
        (free_pose(rng, scale), None)
    };
    SolidConfig {
        a,
        b,
        pos_ab,
        scale,
        contact,
    }
}

/// The MPFR reference of a configuration: the smallest realised distance the search finds
/// between the two solids' true surfaces.
fn reference(cfg: &SolidConfig) -> f64 {
    let seeds: Vec<Pair> = cfg.contact.into_iter().collect();
    let found = nearest_pairs(
        &cfg.a.pieces,
        &cfg.b.pieces,
        &cfg.pos_ab,
        &seeds,
        EXACT_PAIRS,
    );
    found
        .iter()
        .map(|p| pair_distance(&cfg.a.pieces, &cfg.b.pieces, &cfg.pos_ab, &p.p, &p.q))
        .fold(f64::INFINITY, f64::min)
}

fn describe(cfg: &SolidConfig, what: &str) -> String {
    format!(
        "{what}; {} vs {}; a = {:?}; b = {:?}; eps {:e}, {:e}; {}",
        cfg.a.kind.name(),
        cfg.b.kind.name(),
        cfg.a.pieces,
        cfg.b.pieces,
        cfg.a.solid.tree.eps,
        cfg.b.solid.tree.eps,
        pose_text(&cfg.pos_ab)
    )
}

/// One configuration of `bound` (`ClosedForm` or `Convex`): the query's `lower` through
/// that path against the MPFR reference.
pub fn check(bound: Bound, rng: &mut SplitMix64, tally: &mut Tally) {
    let (kinds, opts): (&[Primitive], QueryOptions) = match bound {
        Bound::ClosedForm => (
            &CLOSED_FORM,
            QueryOptions {
                convex_path: false,
                ..QueryOptions::default()
            },
        ),
        Bound::Convex => (
            &CONVEX,
            QueryOptions {
                closed_form: false,
                ..QueryOptions::default()
            },
        ),
        _ => return,
    };
    let cfg = draw(rng, kinds);
    let a = cfg.a.solid.clone();
    let b = cfg.b.solid.with_pose(cfg.pos_ab);
    let answer = distance(&a, &b, &opts);
    let reference = reference(&cfg);
    tally.configs += 1;
    let allowance = PROFILE_ROUNDING * cfg.scale;
    tally.record(answer.lower, reference, allowance, cfg.scale, || {
        describe(&cfg, bound.name())
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The outward normal points out of the solid at smooth points (the contacts are
    /// external), and a contact pose realises its gap.
    #[test]
    fn contacts_are_outward_and_realise_their_gap() {
        let root = SplitMix64(5);
        let mut checked = 0;
        for k in 0..300 {
            let mut rng = root.fork(k);
            let kind = *rng.pick(&CONVEX);
            let size = rng.log_range(1e-2, 1e2);
            let s = shape(&mut rng, kind, size);
            let x = SurfacePoint {
                piece: rng.below(s.pieces.len()),
                s: rng.range(0.1, 0.9),
                theta: rng.range(0.0, TAU),
            };
            let n = outward_normal(&mut rng, &s, &x);
            let p = point(&s.pieces, &x);
            let size = s.solid.tree.nodes[s.solid.tree.root as usize].bound.radius;
            let probe = |t: f64| point_in_solid(&s.solid.tree, &(p + n * (t * size))).inside;
            assert!(!probe(1e-4) && probe(-1e-4), "{kind:?} at {x:?}");
            checked += 1;
        }
        assert_eq!(checked, 300);
        for k in 0..100 {
            let mut rng = root.fork(1000 + k);
            let cfg = draw(&mut rng, &CONVEX);
            if let Some(c) = cfg.contact {
                assert!(c.d <= 0.5 * cfg.scale * 1.000001, "{}", c.d);
            }
        }
    }
}
