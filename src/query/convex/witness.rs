//! Witness points of the convex fast path on the approximating surfaces.
//!
//! GJK's closest points are convex combinations of support points: points of the hulls,
//! inside a curved solid by up to GJK's duality gap. Each is moved to the nearest point of
//! its solid's approximating surface (the tree's chain revolved about the axis), which lies
//! within the tree's eps of the true surface, as the query's contract asks of witnesses.
//!
//! **How far it moves.** Let `v = p_A - p_B` be GJK's final vector and `s` the separation of
//! the hulls along `v / |v|` (the lower bound of that iteration). `p_A` lies inside `H_A` at
//! most `|v| - s` behind A's supporting plane orthogonal to `v`, and so at most that far from
//! `H_A`'s boundary (the segment from `p_A` to that plane leaves `H_A`); the same holds for
//! `p_B`. `H_A`'s boundary is the revolved chain when the chain is convex, and within the
//! certificate's dent of it otherwise. So the two moves add at most the gap plus the dents to
//! `|v|`, and the witnesses' distance exceeds the hulls' distance by at most twice the gap
//! plus the dents ([`super::convex_distance`] asks GJK for a gap that fits the tolerance).
//!
//! The nearest point of a surface of revolution to `x` lies in `x`'s meridian half-plane, at
//! the nearest point of the planar chain to `x`'s meridian coordinates `(rho, z)`: a descent
//! of the tree's disks, nearer child first ([`crate::bvh::descent::nearest_chain_point`]),
//! over the pieces a convex tree keeps for it (no `atan2` or `sin`/`cos`,
//! [`crate::bvh::convex::nearest`]) or over any other tree's patches.

use crate::bvh::descent::nearest_chain_point as nearest_in_chain;
use crate::bvh::QueryTree;
use nalgebra::{Point2, Point3, Vector3};

/// The point of `tree`'s approximating surface (the chain revolved, frame of the tree)
/// nearest to `x`. A point on the axis has every azimuth; `toward` (a direction in the
/// tree's frame, e.g. towards the other solid) then picks the meridian to lift to.
pub fn nearest_surface_point(
    tree: &QueryTree,
    x: &Point3<f64>,
    toward: &Vector3<f64>,
) -> Point3<f64> {
    let rho = (x.x * x.x + x.y * x.y).sqrt();
    let m = Point2::new(rho, x.z);
    let q = nearest_chain_point(tree, m).unwrap_or(m);
    // The meridian of `x`, or of `toward` when `x` is (numerically) on the axis.
    let (c, s) = if rho > 0.0 {
        (x.x / rho, x.y / rho)
    } else {
        let t = toward.x.hypot(toward.y);
        if t > 0.0 {
            (toward.x / t, toward.y / t)
        } else {
            (1.0, 0.0)
        }
    };
    Point3::new(q.x * c, q.x * s, q.y)
}

/// The point of the tree's planar chain nearest to the meridian point `m`; `None` for an
/// empty tree. A convex tree keeps its pieces in the form without `atan2`
/// ([`crate::bvh::convex::MeridianPiece`]); any other tree's patches answer for themselves.
pub fn nearest_chain_point(tree: &QueryTree, m: Point2<f64>) -> Option<Point2<f64>> {
    let found = match &tree.convex {
        Some(c) => nearest_in_chain(tree, &c.pieces, m),
        None => nearest_in_chain(tree, &tree.patches, m),
    };
    found.map(|(_, p)| p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use crate::nearest::NearestPoint;
    use crate::solid::Solid;
    use crate::test_rng::SplitMix64;
    use std::sync::Arc;

    /// The descent finds the same nearest chain point as a scan of every piece.
    #[test]
    fn descent_agrees_with_a_scan() {
        let mut rng = SplitMix64(7);
        for (name, eps) in [
            ("capsule", 1e-4),
            ("pawn", 1e-4),
            ("cup", 1e-5),
            ("cone", 1e-3),
        ] {
            let s = Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap();
            let t = &s.tree;
            for _ in 0..200 {
                let m = Point2::new(rng.next_f64() * 2.0, rng.next_f64() * 4.0 - 1.0);
                let got = nearest_chain_point(t, m).unwrap();
                let scan = t
                    .patches
                    .iter()
                    .map(|p| p.arc.nearest(m).0)
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    ((got - m).norm() - scan).abs() <= 1e-14 * (1.0 + scan),
                    "{name}: {m:?} {} vs {scan}",
                    (got - m).norm()
                );
            }
        }
    }

    /// A point off the axis is moved in its meridian; one on the axis to the meridian of
    /// `toward`.
    #[test]
    fn lifted_in_the_right_meridian() {
        let s = Solid::from_profile(Arc::new(model("cylinder").unwrap()), 1e-4).unwrap();
        // The cylinder: radius 0.5, z in [0, 1.5].
        let q = nearest_surface_point(&s.tree, &Point3::new(0.12, 0.16, 0.75), &Vector3::x());
        assert!((q - Point3::new(0.3, 0.4, 0.75)).norm() < 1e-14, "{q:?}");
        let q = nearest_surface_point(&s.tree, &Point3::new(0.0, 0.0, 1.4), &Vector3::y());
        assert!((q - Point3::new(0.0, 0.0, 1.5)).norm() < 1e-14, "{q:?}");
        let q = nearest_surface_point(&s.tree, &Point3::new(0.0, 0.0, 0.75), &Vector3::y());
        assert!((q - Point3::new(0.0, 0.5, 0.75)).norm() < 1e-14, "{q:?}");
    }
}
