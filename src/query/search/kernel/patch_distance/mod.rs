//! Exact minimum distance between two revolved profile pieces in arbitrary relative pose
//! (paper section 3: "the distance between two toroidal patches is l +- r1 +- r2").
//!
//! The minimum of the distance between two compact surfaces with boundary is attained
//! (a) at an interior common normal, (b) at a boundary parallel of one patch against the
//! interior of the other, (c) between two boundary parallels, or (d) at an intersection
//! point (distance 0). We enumerate a superset of every case and measure each candidate as
//! the exact distance between two points that lie on the patches, so extra candidates never
//! make the answer too small, and completeness makes it exact:
//!
//! * (a) toroidal patch vs anything: a common normal meets the major circle `M` of the
//!   toroidal patch at a right angle, so its foot `P` on `M` is a critical point of the
//!   distance from `M(theta)` to the other patch's core (profile-circle centre or cone
//!   line, both mirrored branches); [`crate::query::angles::radial_field::critical_angles`] finds those angles. From `P`
//!   the critical feet `q` on the other patch give the line, and the toroidal patch's
//!   points on that line are `P +- r u` (the signs l +- r1 +- r2 of the paper), kept when
//!   their arc angle is in range (inclusive).
//! * (a) cone vs cone (two straight pieces): normals of a cone at revolution angle theta
//!   are all parallel to `n_rho e_rho(theta) + n_z e_z`; the Gauss image is a circle of
//!   latitude. A common normal direction lies on both latitude circles (at most two points
//!   per sign choice); the two generators are then both orthogonal to it and their closest
//!   points give the normal. Parallel axes and flat disks are handled explicitly.
//! * (b) a boundary parallel `G` against a patch: critical points of the distance from
//!   `G(theta)` to the patch's core, then the critical feet; and the level sets where `G`
//!   crosses the extended surface, measured with the exact point-to-patch distance (this
//!   finds boundary/surface crossings, i.e. case (d) whenever the intersection curve
//!   reaches a boundary). A parallel of radius 0 (a point on the axis) uses the exact
//!   point-to-patch distance directly.
//! * (c) parallel vs parallel: critical points of the distance from one to the other.
//! * Coaxial patches reduce exactly to the planar distance of the profile pieces.
//!
//! Where a polynomial kernel reports a degenerate configuration that has no closed form
//! here (intersecting major circles, non-coaxial continua of binormals), the critical angles
//! come from the sampled scan of [`crate::query::angles::radial_field`] and [`PatchDistance::sampled`] is set: the
//! distance is then a realised pair (an upper bound) and the caller bounds the pair from
//! below by subdivision ([`crate::query::search::leaf::subdivision`]). The continua with a closed form are exact:
//! coaxial circles (constant distance), a circle parallel to a flat annulus, a sphere centre
//! on the other patch's axis.
//!
//! Interior intersection loops that touch no boundary are found by the crossing scan (d),
//! which samples every interior candidate's meridian at the candidate itself; a loop the
//! scan misses encloses a *lens* whose extremum is an interior candidate at a local maximum
//! of the distance along its patch, and such a candidate (`second_order`) makes the
//! answer `sampled` (docs/verification.md, "Crossing lenses"). The interior pairs are also
//! reported through [`PatchDistance::interior_pairs`]: at the deepest point of a loop the
//! common normal may have both points inside the other solid, which the caller (who knows
//! the solids) tests as an interpenetration.
//!
//! **Layout.** This file is the driver ([`patch_distance_memo`]: coaxial pairs, the order of
//! the cases, the best pair); each case has its own file: `interior.rs` (a) for a toroidal
//! patch, `cones.rs` (a) for two cones, `boundary.rs` (b), `parallels.rs` (c),
//! `crossings.rs` (d) and `second_order.rs` (the lens test).

use super::planar;
use crate::biarc::Disk;
use crate::bvh::patch::{e_rho, lift, Core, Patch, ProfileArc};
use crate::circle::min_distance;
use crate::num::norm2;
use crate::query::angles::common_normals::{
    circle_torus_critical, interior_torus_torus, parallel_circle, parallel_pair_closest,
};
use crate::query::angles::meridian_line::{line_field_critical, line_field_levels, FieldAngles};
use crate::query::angles::radial_field::{
    critical_angles, level_angles, level_crossings, ParamCircle, RadialField,
};
use crate::query::bound::hull_bound::hull_bound_until;
use crate::query::bound::node_pair::{node_pair_bound, BoundKind};
use crate::tolerances::{AXIS_TOLERANCE, POINT_SNAP};
use nalgebra::{Isometry3, Point2, Point3, Vector3};
use std::collections::HashMap;

mod boundary;
mod cones;
mod crossings;
mod interior;
mod parallels;
mod second_order;

use crate::tolerances::{FAST_PATH_REL, MERIDIAN_DEDUP};
use boundary::{boundary_vs_patch, flat_annulus_angle, parallel_lower_bound};
use cones::cone_cone;
use crossings::{meridian_crossings, Meridian, FIXED_MERIDIANS};
use interior::{core_field, interior_via_core};
use parallels::parallel_pair;
use second_order::may_be_lens_extremum;

/// Result of a patch-pair distance: the distance and the closest points (frame of patch A).
#[derive(Debug, Clone, PartialEq)]
pub struct PatchDistance {
    pub distance: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Interior common normals (point on A, point on B), for penetration tests.
    pub interior_pairs: Vec<(Point3<f64>, Point3<f64>)>,
    /// Some candidates came from a sampled scan ([`crate::query::angles::radial_field`]): `distance` is then only an
    /// upper bound of the patch distance (two real surface points), and a lower bound must
    /// come from elsewhere ([`crate::query::search::leaf::subdivision`]).
    pub sampled: bool,
}

struct Best {
    d: f64,
    p: Point3<f64>,
    q: Point3<f64>,
}

impl Best {
    fn consider(&mut self, p: Point3<f64>, q: Point3<f64>) {
        let d = (p - q).norm();
        if d < self.d {
            *self = Best { d, p, q };
        }
    }
}

/// How critical angles along circles are found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kernel {
    /// Binormals of circles from the degree-8 polynomial (paper 3.2, [`crate::query::angles::common_normals`]),
    /// with the sampled scan only where a continuum of binormals makes it ill-posed.
    #[default]
    Binormals,
    /// The sampled scan of [`crate::query::angles::radial_field`] everywhere (an independent second method for tests).
    Sweep,
}

/// Options of the patch distance (for testing the Gauss-map restriction and the like).
#[derive(Debug, Clone, Copy)]
pub struct PatchOptions {
    /// Skip the interior-interior candidates (tests only).
    pub skip_interior: bool,
    /// Kernel for critical angles.
    pub kernel: Kernel,
    /// Narrow the major-circle angles of torus/torus common normals by the Gauss map
    /// (paper 3.3); results agree with and without it.
    pub gauss_restriction: bool,
    /// The patches may intersect. A caller that has a positive lower bound of their
    /// distance (e.g. the solid-torus bound of their disks) sets `false`: disjoint patches
    /// have no intersection loop, so the crossing scan (d) is skipped.
    pub may_intersect: bool,
}

impl Default for PatchOptions {
    fn default() -> Self {
        Self {
            skip_interior: false,
            kernel: Kernel::Binormals,
            gauss_restriction: true,
            may_intersect: true,
        }
    }
}

/// Exact distance between patch `a` (frame A) and patch `b` placed by `pos_ab` (a point
/// `x` of B's frame is at `pos_ab * x` in A's frame).
pub fn patch_distance(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> PatchDistance {
    patch_distance_with(a, b, pos_ab, PatchOptions::default())
}

/// [`patch_distance`] with options.
pub fn patch_distance_with(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    opts: PatchOptions,
) -> PatchDistance {
    patch_distance_memo(a, b, pos_ab, opts, None)
}

/// Closest pair `(point on a parallel, point on a patch)`, in the patch's frame.
type ClosestPair = (Point3<f64>, Point3<f64>);

/// The closest pair a candidate generator found, and whether it sampled.
type Found = (Option<ClosestPair>, bool);

/// Results of the boundary cases (b) and (c) shared by the patch pairs of one query (one
/// pose): a boundary parallel meets the same patch, and the same parallel of the other
/// solid, in every leaf pair that contains both, and neighbouring pieces share their end
/// parallels. A parallel is keyed by the bits of its `(rho, z)`, a patch by its index in
/// its tree.
#[derive(Debug, Default)]
pub struct BoundaryMemo {
    /// (parallel of B?, rho bits, z bits, index of the other patch) -> closest pair.
    circle_patch: HashMap<(bool, u64, u64, u32), Found>,
    /// (A's parallel bits, B's parallel bits) -> closest pair (A's frame).
    circle_circle: HashMap<(u64, u64, u64, u64), Found>,
}

/// A memo with the indices of the two patches in their trees.
pub struct MemoSlot<'m> {
    pub memo: &'m mut BoundaryMemo,
    pub index_a: u32,
    pub index_b: u32,
}

/// [`patch_distance_with`] sharing boundary results through `memo` (same pose only).
pub fn patch_distance_memo(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    opts: PatchOptions,
    mut memo: Option<MemoSlot<'_>>,
) -> PatchDistance {
    if let Some(r) = coaxial(a, b, pos_ab) {
        return r;
    }
    let pos_ba = pos_ab.inverse();
    let mut best = Best {
        d: f64::INFINITY,
        p: Point3::origin(),
        q: Point3::origin(),
    };
    let mut pairs = Vec::new();
    let mut sampled = opts.kernel == Kernel::Sweep;
    if !opts.skip_interior {
        let via_binormals = opts.kernel == Kernel::Binormals
            && matches!(
                (a.arc, b.arc),
                (ProfileArc::Arc { .. }, ProfileArc::Arc { .. })
            )
            && interior_torus_torus(a, b, pos_ab, opts.gauss_restriction, &mut |p, q| {
                best.consider(p, q);
                pairs.push((p, q));
            })
            .is_ok();
        match (a.arc, b.arc) {
            _ if via_binormals => {}
            (ProfileArc::Arc { .. }, _) => {
                sampled |= interior_via_core(a, b, pos_ab, opts.kernel, &mut |p, q| {
                    best.consider(p, q);
                    pairs.push((p, q));
                });
            }
            (_, ProfileArc::Arc { .. }) => {
                sampled |= interior_via_core(b, a, &pos_ba, opts.kernel, &mut |q, p| {
                    let (p, q) = (pos_ab * p, pos_ab * q);
                    best.consider(p, q);
                    pairs.push((p, q));
                });
            }
            _ => {
                sampled |= cone_cone(a, b, pos_ab, &mut |p, q| {
                    best.consider(p, q);
                    pairs.push((p, q));
                })
            }
        }
    }
    // (b) boundary parallels of B against A, and of A against B.
    let bits = |e: Point2<f64>| (e.x.to_bits(), e.y.to_bits());
    for (of_b, e) in b
        .boundary()
        .map(|e| (true, e))
        .into_iter()
        .chain(a.boundary().map(|e| (false, e)))
    {
        let compute = || {
            if of_b {
                closest(|emit| boundary_vs_patch(e, a, pos_ab, opts.kernel, emit))
            } else {
                closest(|emit| boundary_vs_patch(e, b, &pos_ba, opts.kernel, emit))
            }
        };
        // A parallel whose cheap lower bound already reaches the best candidate cannot
        // lower the minimum (nor cross the patch, the bound being positive): no solve.
        let bounded_away = || {
            if !best.d.is_finite() {
                // No candidate yet: no bound can reach it.
                return false;
            }
            let (o, pos_og) = if of_b { (a, *pos_ab) } else { (b, pos_ba) };
            let lower = parallel_lower_bound(e, o, &pos_og, best.d);
            lower > 0.0 && lower >= best.d
        };
        let found = match memo.as_mut() {
            Some(m) => {
                let (rb, zb) = bits(e);
                let other = if of_b { m.index_a } else { m.index_b };
                let key = (of_b, rb, zb, other);
                match m.memo.circle_patch.get(&key) {
                    Some(f) => *f,
                    None if bounded_away() => continue,
                    None => *m.memo.circle_patch.entry(key).or_insert_with(compute),
                }
            }
            None if bounded_away() => continue,
            None => compute(),
        };
        sampled |= found.1;
        match found.0 {
            Some((x, c)) if of_b => best.consider(c, x),
            Some((x, c)) => best.consider(pos_ab * x, pos_ab * c),
            None => {}
        }
    }
    // (c) parallel pairs.
    for ea in a.boundary() {
        for eb in b.boundary() {
            let compute = || closest(|emit| parallel_pair(ea, eb, pos_ab, opts.kernel, emit));
            let found = match memo.as_mut() {
                Some(m) => {
                    let ((r1, z1), (r2, z2)) = (bits(ea), bits(eb));
                    *m.memo
                        .circle_circle
                        .entry((r1, z1, r2, z2))
                        .or_insert_with(compute)
                }
                None => compute(),
            };
            sampled |= found.1;
            if let Some((p, q)) = found.0 {
                best.consider(p, q);
            }
        }
    }
    // (d) intersection loops inside both patches: sign changes of the other surface's
    // implicit function along meridians (through every interior candidate and four
    // fixed ones).
    if best.d > 0.0 && opts.may_intersect {
        let mut on_a: Vec<Meridian> = FIXED_MERIDIANS.map(Meridian::fixed).to_vec();
        let mut on_b: Vec<Meridian> = FIXED_MERIDIANS.map(Meridian::fixed).to_vec();
        for (p, q) in &pairs {
            on_a.push(Meridian::through(a, p));
            on_b.push(Meridian::through(b, &(pos_ba * q)));
        }
        let (on_a, on_b) = (Meridian::merged(on_a), Meridian::merged(on_b));
        meridian_crossings(b, a, pos_ab, &on_b, &mut |q, p| best.consider(p, q));
        meridian_crossings(a, b, &pos_ba, &on_a, &mut |p, q| {
            best.consider(pos_ab * p, pos_ab * q)
        });
        // Patches that cross in a loop inside both have an interior candidate at the loop's
        // lens, a local maximum of the distance along a patch (`second_order`). When the
        // scan through it found no crossing, the shortest candidate cannot be certified:
        // the caller subdivides.
        if best.d > 0.0
            && pairs
                .iter()
                .any(|(p, q)| may_be_lens_extremum(a, b, pos_ab, &pos_ba, p, q))
        {
            sampled = true;
        }
    }
    PatchDistance {
        distance: best.d,
        point_a: best.p,
        point_b: best.q,
        interior_pairs: pairs,
        sampled,
    }
}

/// The closest of the pairs a candidate generator emits.
fn closest(gen: impl FnOnce(&mut dyn FnMut(Point3<f64>, Point3<f64>)) -> bool) -> Found {
    let mut best: Option<(f64, ClosestPair)> = None;
    let sampled = gen(&mut |x, c| {
        let d = (x - c).norm();
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, (x, c)));
        }
    });
    (best.map(|(_, pair)| pair), sampled)
}

/// Coaxial solids: the distance is the planar distance of the pieces.
fn coaxial(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> Option<PatchDistance> {
    let axis = pos_ab.rotation * Vector3::z();
    let t = pos_ab.translation.vector;
    let scale = 1.0 + t.norm();
    if axis.x.hypot(axis.y) > AXIS_TOLERANCE || t.x.hypot(t.y) > AXIS_TOLERANCE * scale {
        return None;
    }
    let sign = axis.z.signum();
    let bm = b.arc.mapped_z(sign, t.z);
    let (d, pa, pb) = planar::piece_distance(&a.arc, &bm);
    let e = Vector3::x();
    Some(PatchDistance {
        distance: d,
        point_a: lift(pa, &e),
        point_b: lift(pb, &e),
        interior_pairs: Vec::new(),
        sampled: false,
    })
}

#[cfg(test)]
pub(crate) mod tests;
