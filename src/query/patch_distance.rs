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
//!   line, both mirrored branches); [`super::sweep::critical_angles`] finds those angles. From `P`
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
//! come from the sampled scan of [`super::sweep`] and [`PatchDistance::sampled`] is set: the
//! distance is then a realised pair (an upper bound) and the caller bounds the pair from
//! below by subdivision ([`super::certify`]). The continua with a closed form are exact:
//! coaxial circles (constant distance), a circle parallel to a flat annulus, a sphere centre
//! on the other patch's axis.
//!
//! Interior intersection loops that touch no boundary are reported through
//! [`PatchDistance::interior_pairs`]: at the deepest point of such a loop the common normal
//! has both points inside the other solid, which the caller (who knows the solids) tests.

use super::binormal_kernel::{
    circle_torus_critical, interior_torus_torus, parallel_circle, parallel_pair_closest,
};
use super::bounds::{hull_bound_until, node_pair_bound, BoundKind};
use super::line_field::{line_field_critical, line_field_levels};
use super::patch::{e_rho, lift, Core, Patch, ProfileArc, POINT_SNAP};
use super::planar;
use super::sweep::{critical_angles, level_angles, level_crossings, ParamCircle, RadialField};
use super::tree::Disk;
use crate::circle::min_distance;
use crate::num::norm2;
use nalgebra::{Isometry3, Point2, Point3, Vector3};
use std::collections::HashMap;

/// Relative tolerance for deciding that two axes are the same line (coaxial solids) or
/// parallel; relative to the size of the configuration. Round-off in composing a pose is
/// ~1e-15; 1e-12 leaves margin and is far below any eps used by trees.
pub const AXIS_TOLERANCE: f64 = 1e-12;

/// Result of a patch-pair distance: the distance and the closest points (frame of patch A).
#[derive(Debug, Clone, PartialEq)]
pub struct PatchDistance {
    pub distance: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Interior common normals (point on A, point on B), for penetration tests.
    pub interior_pairs: Vec<(Point3<f64>, Point3<f64>)>,
    /// Some candidates came from a sampled scan ([`super::sweep`]): `distance` is then only an
    /// upper bound of the patch distance (two real surface points), and a lower bound must
    /// come from elsewhere ([`super::certify`]).
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
    /// Binormals of circles from the degree-8 polynomial (paper 3.2, [`super::binormal_kernel`]),
    /// with the sampled scan only where a continuum of binormals makes it ill-posed.
    #[default]
    Binormals,
    /// The sampled scan of [`super::sweep`] everywhere (an independent second method for tests).
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
            _ => cone_cone(a, b, pos_ab, &mut |p, q| {
                best.consider(p, q);
                pairs.push((p, q));
            }),
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
        let mut th_a: Vec<f64> = FIXED_MERIDIANS.to_vec();
        let mut th_b: Vec<f64> = FIXED_MERIDIANS.to_vec();
        for (p, q) in &pairs {
            th_a.push(p.y.atan2(p.x));
            let qb = pos_ba * q;
            th_b.push(qb.y.atan2(qb.x));
        }
        // The four sign combinations of a common normal share its meridians.
        for th in [&mut th_a, &mut th_b] {
            th.sort_by(f64::total_cmp);
            th.dedup_by(|x, y| (*x - *y).abs() <= MERIDIAN_DEDUP);
        }
        meridian_crossings(b, a, pos_ab, &th_b, &mut |q, p| best.consider(p, q));
        meridian_crossings(a, b, &pos_ba, &th_a, &mut |p, q| {
            best.consider(pos_ab * p, pos_ab * q)
        });
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

/// Meridians always scanned for crossings (an intersection loop that winds around a
/// patch's axis meets every meridian of that patch).
const FIXED_MERIDIANS: [f64; 4] = [
    0.0,
    std::f64::consts::FRAC_PI_2,
    std::f64::consts::PI,
    3.0 * std::f64::consts::FRAC_PI_2,
];

/// Meridian angles closer than this (radians) are scanned once: the crossing scan's
/// samples along a meridian do not resolve finer angular differences.
const MERIDIAN_DEDUP: f64 = 1e-12;

/// Samples along a meridian for the crossing scan.
const MERIDIAN_SAMPLES: usize = 32;

/// Implicit functions of the two mirror halves of the extended surface of `o` at `x`
/// (o's frame): each is zero exactly on one half of the revolved full circle (or line) of
/// the piece, so that their union is the extended surface. The halves are kept apart: their
/// product, zero on the same set, becomes a square with no sign change when the halves
/// nearly coincide (an arc centred near the axis, a segment within rounding of flat), and a
/// crossing scan on it missed a cone tip poking through a flat disk (campaign seed 1206).
fn implicit_halves(o: &Patch, x: &Point3<f64>) -> [f64; 2] {
    let rho = norm2(x.x, x.y);
    match o.core() {
        Core::Circle {
            r_major,
            z,
            r_minor,
        } => [
            norm2(rho - r_major, x.z - z) - r_minor,
            norm2(rho + r_major, x.z - z) - r_minor,
        ],
        Core::Line { n, c } => [n.x * rho + n.y * x.z - c, -n.x * rho + n.y * x.z - c],
    }
}

/// Points of `g`'s meridians (at angles `thetas`, frame G) where an implicit function of
/// `o`'s halves changes sign ([`implicit_halves`]), each emitted with its closest point on
/// `o` (O's frame): a crossing of the two patches when that distance is zero. Every
/// emitted pair is two real points of the patches, so extra candidates never undercut the
/// distance. `pos_og` places G in O.
fn meridian_crossings(
    g: &Patch,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    thetas: &[f64],
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let n = MERIDIAN_SAMPLES;
    // The meridian's profile samples do not depend on the meridian: computed once.
    let mut samples = [Point2::origin(); MERIDIAN_SAMPLES + 1];
    for (i, m) in samples.iter_mut().enumerate() {
        *m = g.arc.point_at(i as f64 / n as f64);
    }
    for &th in thetas {
        let e = e_rho(th);
        let at = |s: f64| pos_og * lift(g.arc.point_at(s), &e);
        let mut prev = implicit_halves(o, &(pos_og * lift(samples[0], &e)));
        for (i, m) in samples.iter().enumerate().skip(1) {
            let (s0, s1) = ((i - 1) as f64 / n as f64, i as f64 / n as f64);
            let cur = implicit_halves(o, &(pos_og * lift(*m, &e)));
            for half in 0..2 {
                if prev[half] != 0.0 && prev[half].signum() == cur[half].signum() {
                    continue;
                }
                let f = |s: f64| implicit_halves(o, &at(s))[half];
                let (mut lo, mut hi, mut flo) = (s0, s1, prev[half]);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    let fm = f(mid);
                    if fm == 0.0 {
                        lo = mid;
                        hi = mid;
                        break;
                    }
                    if fm.signum() == flo.signum() {
                        lo = mid;
                        flo = fm;
                    } else {
                        hi = mid;
                    }
                }
                let x = at(0.5 * (lo + hi));
                let (_, c) = o.point_distance(&x);
                emit(x, c);
            }
            prev = cur;
        }
    }
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

/// Field of the distance to the core of `patch` for mirror branch `s` (see `sweep`).
fn core_field(patch: &Patch, s: f64) -> RadialField {
    match patch.core() {
        Core::Circle { r_major, z, .. } => RadialField {
            a: -2.0 * s * r_major,
            b: 1.0,
            c1: -2.0 * z,
            c2: 1.0,
        },
        Core::Line { n, .. } => RadialField {
            a: s * n.x,
            b: 0.0,
            c1: n.y,
            c2: 0.0,
        },
    }
}

/// Interior common normals with `t` a toroidal patch (frame T) and `o` any patch placed in
/// T's frame by `pos_to`. Emits (point on t, point on o) in T's frame; returns whether the
/// critical angles came from the sampled scan.
fn interior_via_core(
    t: &Patch,
    o: &Patch,
    pos_to: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let Core::Circle { r_major, z, .. } = t.core() else {
        return false;
    };
    let mut sampled = false;
    let pos_ot = pos_to.inverse();
    // Major circle of t in o's frame.
    let major = ParamCircle::parallel(r_major, z, &pos_ot);
    let mut thetas = Vec::with_capacity(32);
    if r_major == 0.0 {
        thetas.push(0.0);
    } else {
        let exact = match (kernel, o.core()) {
            (Kernel::Binormals, Core::Line { n, .. }) => {
                line_field_critical(&major, n, &mut thetas)
                    || (n.x == 0.0 && {
                        // A horizontal major circle over a flat annulus: every angle is
                        // critical, and the common normals are vertical; the one whose
                        // foot is in the annulus (if any) comes from the closed form.
                        flat_annulus_angle(&major, o, &mut thetas);
                        true
                    })
            }
            _ => false,
        };
        if !exact {
            sampled = true;
            for s in [1.0, -1.0] {
                critical_angles(&major, &core_field(o, s), &mut thetas);
            }
        }
    }
    let mut feet = Vec::with_capacity(8);
    let mut pts = Vec::with_capacity(4);
    for &th in &thetas {
        let core_t = lift(Point2::new(r_major, z), &e_rho(th)); // in t's frame
        let core_o = pos_ot * core_t;
        feet.clear();
        o.critical_feet(&core_o, &mut feet);
        if r_major == 0.0 {
            sphere_centre_feet(t, pos_to, &core_o, &mut feet);
        }
        for f in &feet {
            let q = pos_to * f;
            let w = q - core_t;
            let n = w.norm();
            let dir = if n > 1e-300 {
                w / n
            } else {
                // q on the major circle: the common normal is the surface normal of o at q.
                pos_to.rotation * surface_normal(o, f)
            };
            pts.clear();
            t.points_on_normal_line(&core_t, &dir, &mut pts);
            for p in &pts {
                emit(*p, q);
            }
        }
    }
    sampled
}

/// Feet on `o` seen from the centre of the sphere patch `t` when that centre (`x`, o's
/// frame) lies on o's axis (`pos_to` places O in T's frame).
///
/// **Exactness.** Each critical foot `f` of `o` from a point on its axis lies on a parallel
/// of `o`, all of whose points are feet at the same distance `|f - x|`; the common normal
/// through a foot is the line from the sphere centre, and `t` keeps it when the direction's
/// latitude in T's frame lies in t's arc range (`sin phi` in `[s_lo, s_hi]`). Along the
/// parallel the direction's z component in T's frame is `(A + K cos(psi - psi0)) / |w|`,
/// so for each sign of the direction the kept feet form an interval of `psi`, found in
/// closed form; the foot at its middle is emitted (every kept foot gives the same
/// distance). No meridian is sampled.
fn sphere_centre_feet(
    t: &Patch,
    pos_to: &Isometry3<f64>,
    x: &Point3<f64>,
    feet: &mut Vec<Point3<f64>>,
) {
    if x.x.hypot(x.y) > 1e-13 * (1.0 + x.coords.norm()) {
        return;
    }
    let ProfileArc::Arc {
        phi_start, sweep, ..
    } = t.arc
    else {
        return;
    };
    let half_pi = std::f64::consts::FRAC_PI_2;
    let latitude = |phi: f64| phi.sin().atan2(phi.cos()).clamp(-half_pi, half_pi).sin();
    let (l0, l1) = (latitude(phi_start), latitude(phi_start + sweep));
    let (s_lo, s_hi) = (l0.min(l1), l0.max(l1));
    let core_t = pos_to * x;
    let (ex, ey) = (
        pos_to.rotation * Vector3::x(),
        pos_to.rotation * Vector3::y(),
    );
    let base: Vec<Point3<f64>> = feet.clone();
    for f in &base {
        let rho_f = f.x.hypot(f.y);
        let alpha = f.y.atan2(f.x);
        let w_len = (f - x).norm();
        let a = (pos_to * Point3::new(0.0, 0.0, f.z)).z - core_t.z;
        let (p, q) = (ex.z * rho_f, ey.z * rho_f);
        let k = p.hypot(q);
        let psi0 = q.atan2(p);
        for sgn in [1.0, -1.0] {
            // Direction sgn * w / |w| has z in [s_lo, s_hi]  <=>  w_z in [lo, hi].
            let (b0, b1) = (sgn * s_lo * w_len, sgn * s_hi * w_len);
            let (lo, hi) = (b0.min(b1).max(a - k), b0.max(b1).min(a + k));
            if lo > hi {
                continue;
            }
            let target = 0.5 * (lo + hi);
            let psi = if k > 0.0 {
                psi0 + ((target - a) / k).clamp(-1.0, 1.0).acos()
            } else {
                psi0
            };
            let rot = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi - alpha);
            feet.push(rot * f);
        }
    }
}

/// Unit surface normal (from the core side) of patch `o` at its point `f` (o's frame).
fn surface_normal(o: &Patch, f: &Point3<f64>) -> Vector3<f64> {
    let rho = f.x.hypot(f.y);
    let e = if rho > 0.0 {
        Vector3::new(f.x / rho, f.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    let n2 = o.planar_normal(Point2::new(rho, f.z));
    e * n2.x + Vector3::z() * n2.y
}

/// Fast exact path of [`boundary_vs_patch`] for a toroidal patch `o` (issue 11: no degree-8
/// solve in the common case). Let `m` be the minimum distance between the parallel `G` and
/// the patch's major circle `M` (the circle module's certified minimum) and `x` its point
/// on `G`. When `m` exceeds the tube radius `r`, `G` lies outside the solid torus (no
/// crossing), every point of `G` is at least `m - r` from the torus surface, hence from
/// the patch; if the patch's closest point `c` to `x` is at distance `m - r` (up to
/// [`FAST_PATH_REL`] of the scale), `(x, c)` realises that bound and is the exact answer.
/// Otherwise `None`: the minimum lies where the torus' closest point is off the patch.
fn parallel_torus_fast(
    e: Point2<f64>,
    o: &Patch,
    pos_og: &Isometry3<f64>,
) -> Option<(Point3<f64>, Point3<f64>)> {
    let Core::Circle {
        r_major,
        z,
        r_minor,
    } = o.core()
    else {
        return None;
    };
    if r_major == 0.0 {
        return None;
    }
    let g = parallel_circle(e.x, e.y, pos_og);
    let core = parallel_circle(r_major, z, &Isometry3::identity());
    let m = min_distance(&g, &core);
    let scale = 1.0 + g.center.coords.norm() + g.radius + r_major.abs() + z.abs() + r_minor;
    let tol = FAST_PATH_REL * scale;
    let bound = m.distance - r_minor;
    if bound <= tol {
        return None;
    }
    let (d, c) = o.point_distance(&m.point_a);
    (d <= bound + tol).then_some((m.point_a, c))
}

/// Relative agreement (to the configuration scale) between a realised distance and the
/// torus bound for `parallel_torus_fast` to accept it: the circle module guarantees its
/// minimum to [`crate::circle::TIE_REL_TOL`] (`1e-12`) of the scale, and the query's
/// slack ([`super::distance::POSE_SLACK_REL`], `2e-11`) covers both with margin.
pub const FAST_PATH_REL: f64 = 1e-12;

/// A lower bound of the distance from the boundary parallel `e` (frame G, placed in O's
/// frame by `pos_og`) to the patch `o`, from circle/circle minima only: the parallel against
/// the solid torus of the disk around `o`'s piece and, for an arc, of the arc's own circle
/// (both contain the patch; [`super::bounds`] and [`super::patch_bound`] give the proofs),
/// after the closed-form hull bound of [`hull_bound`].
/// Returns early once a bound reaches `enough`. A parallel that is a point gets no bound
/// (its exact distance is cheaper).
fn parallel_lower_bound(e: Point2<f64>, o: &Patch, pos_og: &Isometry3<f64>, enough: f64) -> f64 {
    if e.x.abs() <= POINT_SNAP * (1.0 + e.y.abs()) {
        return f64::NEG_INFINITY;
    }
    // The convex-hull bound first (closed form): the parallel against the hull of the
    // patch's chord frustum grown by its sagitta.
    let m = o.arc.point_at(0.5);
    let dir = pos_og * Point3::new(0.0, 0.0, e.y) - Point3::new(0.0, 0.0, m.y);
    let parallel = ProfileArc::Segment { start: e, end: e };
    let hull = hull_bound_until(&o.arc, &parallel, pos_og, &dir, enough);
    if hull >= enough {
        return hull;
    }
    let parallel = Disk {
        center: e,
        radius: 0.0,
    };
    let around = hull.max(node_pair_bound(
        &Disk::around(&o.arc),
        &parallel,
        pos_og,
        BoundKind::Torus,
        enough,
        None,
    ));
    match o.arc {
        ProfileArc::Arc { center, radius, .. } if around < enough => {
            let tube = Disk { center, radius };
            around.max(node_pair_bound(
                &tube,
                &parallel,
                pos_og,
                BoundKind::Torus,
                enough,
                None,
            ))
        }
        _ => around,
    }
}

/// The boundary parallel `e` (meridian coordinates of frame G) against patch `o` (frame O);
/// `pos_og` places G in O. Emits (point on the parallel, point on o) in O's frame.
fn boundary_vs_patch(
    e: Point2<f64>,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let mut feet = Vec::with_capacity(8);
    // The closest point of `o` to `x` and every critical foot.
    let mut emit_feet = |x: Point3<f64>| {
        let (_, c) = o.point_distance(&x);
        emit(x, c);
        feet.clear();
        o.critical_feet(&x, &mut feet);
        for f in &feet {
            emit(x, *f);
        }
    };
    if e.x.abs() <= POINT_SNAP * (1.0 + e.y.abs()) {
        emit_feet(pos_og * Point3::new(0.0, 0.0, e.y));
        return false;
    }
    if kernel == Kernel::Binormals {
        if let Some((x, c)) = parallel_torus_fast(e, o, pos_og) {
            emit(x, c);
            return false;
        }
    }
    let mut thetas = Vec::with_capacity(48);
    let circle = ParamCircle::parallel(e.x, e.y, pos_og);
    let exact = match (kernel, o.core()) {
        (Kernel::Binormals, Core::Circle { .. }) if coaxial_circle(&circle) => {
            // Coaxial with the torus: the distance to the patch is the same at every angle.
            thetas.push(0.0);
            true
        }
        (Kernel::Binormals, Core::Circle { r_major, z, .. }) => {
            circle_torus_critical(&circle, r_major, z, &mut thetas) && {
                // Crossings of the torus lie between consecutive critical angles.
                let level = surface_level(o);
                let n_crit = thetas.len();
                let mut crossings = Vec::new();
                for s in [1.0, -1.0] {
                    let f = core_field(o, s);
                    level_crossings(&circle, &f, level, &thetas[..n_crit], &mut crossings);
                }
                thetas.extend(crossings);
                true
            }
        }
        (Kernel::Binormals, Core::Line { n, c }) => {
            let ok = line_field_critical(&circle, n, &mut thetas)
                && line_field_levels(&circle, n, c, &mut thetas);
            if !ok {
                thetas.clear();
                // The line field is constant along the circle: a flat annulus and a circle
                // in a parallel plane (closed form), else a circle coaxial with the cone or
                // cylinder, whose distance to the patch is the same at every angle.
                if n.x == 0.0 {
                    flat_annulus_angle(&circle, o, &mut thetas);
                } else {
                    thetas.push(0.0);
                }
            }
            true
        }
        _ => false,
    };
    if !exact {
        sampled_boundary_angles(&circle, o, &mut thetas);
    }
    for &th in &thetas {
        emit_feet(circle.point(th));
    }
    !exact
}

/// Whether the circle (frame O) is coaxial with O's z axis, to [`AXIS_TOLERANCE`].
fn coaxial_circle(c: &ParamCircle) -> bool {
    let n = c.u.cross(&c.v);
    let scale = 1.0 + c.o.coords.norm() + c.radius();
    c.o.x.hypot(c.o.y) <= AXIS_TOLERANCE * scale && n.x.hypot(n.y) <= AXIS_TOLERANCE * n.norm()
}

/// The closest angle of a circle lying in a plane `z = const` (frame O) to the flat annulus
/// `o` (a horizontal segment revolved: `z = z_o`, `rho` in `[r0, r1]`).
///
/// **Exactness.** The squared distance from a point to the annulus is
/// `(z - z_o)^2 + dist(rho, [r0, r1])^2`; along the circle `z` is constant and
/// `rho(theta)^2 = d^2 + r^2 + 2 d r cos(theta - theta0)` (`d` the centre's distance to the
/// axis, `r` the radius) sweeps `[|d - r|, d + r]` continuously. The minimum is at the
/// `rho` of that interval nearest to `[r0, r1]` (the middle of their overlap when they
/// overlap), whose angle is solved in closed form.
fn flat_annulus_angle(circle: &ParamCircle, o: &Patch, out: &mut Vec<f64>) {
    let (a, b) = (o.arc.start(), o.arc.end());
    let (r0, r1) = (a.x.min(b.x), a.x.max(b.x));
    let (ox, oy) = (circle.o.x, circle.o.y);
    let (pu, pv) = (
        ox * circle.u.x + oy * circle.u.y,
        ox * circle.v.x + oy * circle.v.y,
    );
    let amp = pu.hypot(pv); // d r
    let base = ox * ox + oy * oy + circle.radius() * circle.radius(); // d^2 + r^2
    if amp == 0.0 {
        out.push(0.0);
        return;
    }
    let (lo, hi) = (
        (base - 2.0 * amp).max(0.0).sqrt(),
        (base + 2.0 * amp).sqrt(),
    );
    let target = if hi < r0 {
        hi
    } else if lo > r1 {
        lo
    } else {
        0.5 * (lo.max(r0) + hi.min(r1))
    };
    let theta0 = pv.atan2(pu);
    let c = ((target * target - base) / (2.0 * amp)).clamp(-1.0, 1.0);
    out.push(theta0 + c.acos());
}

/// Critical and crossing angles of the parallel `circle` against `o` by the sampled scan.
fn sampled_boundary_angles(circle: &ParamCircle, o: &Patch, thetas: &mut Vec<f64>) {
    for s in [1.0, -1.0] {
        critical_angles(circle, &core_field(o, s), thetas);
    }
    // Crossings of the extended surface: F = level.
    let level = surface_level(o);
    for s in [1.0, -1.0] {
        level_angles(circle, &core_field(o, s), level, thetas);
    }
}

/// The value of [`core_field`] (either branch) on the extended surface of `o`.
fn surface_level(o: &Patch) -> f64 {
    match o.core() {
        Core::Circle {
            r_major,
            z,
            r_minor,
        } => r_minor * r_minor - r_major * r_major - z * z,
        Core::Line { c, .. } => c,
    }
}

/// Closest points between the parallel `ea` of A and the parallel `eb` of B.
fn parallel_pair(
    ea: Point2<f64>,
    eb: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let closest_on_a = |x: &Point3<f64>| {
        let rho = x.x.hypot(x.y);
        let e = if rho > 0.0 {
            Vector3::new(x.x / rho, x.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        lift(ea, &e)
    };
    if eb.x.abs() <= POINT_SNAP * (1.0 + eb.y.abs()) {
        let x = pos_ab * Point3::new(0.0, 0.0, eb.y);
        emit(closest_on_a(&x), x);
        return false;
    }
    let circle = ParamCircle::parallel(eb.x, eb.y, pos_ab);
    if ea.x.abs() <= POINT_SNAP * (1.0 + ea.y.abs()) {
        // A's parallel is a point: closest point of B's circle to it.
        let pa = Point3::new(0.0, 0.0, ea.y);
        let pos_ba = pos_ab.inverse();
        let local = pos_ba * pa;
        let rho = local.x.hypot(local.y);
        let e = if rho > 0.0 {
            Vector3::new(local.x / rho, local.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        emit(pa, pos_ab * lift(eb, &e));
        return false;
    }
    if kernel == Kernel::Binormals {
        let (p, q) = parallel_pair_closest((ea.x, ea.y), (eb.x, eb.y), pos_ab);
        emit(p, q);
        return false;
    }
    let field = RadialField {
        a: -2.0 * ea.x,
        b: 1.0,
        c1: -2.0 * ea.y,
        c2: 1.0,
    };
    let mut thetas = Vec::with_capacity(24);
    critical_angles(&circle, &field, &mut thetas);
    for &th in &thetas {
        let x = circle.point(th);
        emit(closest_on_a(&x), x);
    }
    true
}

/// Interior common normals of two straight pieces (cones, cylinders, annuli) via their
/// Gauss images (circles of latitude). Emits (point on a, point on b) in A's frame.
fn cone_cone(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (ProfileArc::Segment { start: a0, end: a1 }, ProfileArc::Segment { start: b0, end: b1 }) =
        (a.arc, b.arc)
    else {
        return;
    };
    let Core::Line { n: na, .. } = a.core() else {
        return;
    };
    let Core::Line { n: nb, .. } = b.core() else {
        return;
    };
    let ez = Vector3::z();
    let axis_b = pos_ab.rotation * ez;
    let k = axis_b.z;
    // Generator of a straight piece at radial direction e (frame-local), as a 3-D segment.
    let gen = |p0: Point2<f64>, p1: Point2<f64>, e: &Vector3<f64>| (lift(p0, e), lift(p1, e));
    let mut try_dir = |dir: Vector3<f64>| {
        // Radial directions where a's (resp. b's) normal is +-dir.
        let ea = radial_for_normal(na, &dir);
        let dir_b = pos_ab.inverse_transform_vector(&dir);
        let eb = radial_for_normal(nb, &dir_b);
        for e1 in ea.iter().flatten() {
            for e2 in eb.iter().flatten() {
                let (p0, p1) = gen(a0, a1, e1);
                let (q0, q1) = gen(b0, b1, e2);
                let (q0, q1) = (pos_ab * q0, pos_ab * q1);
                segment_common_normal(p0, p1, q0, q1, &dir, emit);
            }
        }
    };
    if 1.0 - k.abs() > AXIS_TOLERANCE {
        // Latitudes: dir . ez = sa * na.y, dir . axis_b = sb * nb.y.
        let m = ez.cross(&axis_b);
        let det = 1.0 - k * k;
        for sa in [1.0, -1.0] {
            for sb in [1.0, -1.0] {
                let (al, be) = (sa * na.y, sb * nb.y);
                let lam = (al - be * k) / det;
                let mu = (be - al * k) / det;
                let base = ez * lam + axis_b * mu;
                let rem = 1.0 - base.norm_squared();
                if rem < -1e-12 {
                    continue;
                }
                let nu = rem.max(0.0).sqrt() / det.sqrt();
                for sn in [1.0, -1.0] {
                    try_dir(base + m * (sn * nu));
                    if nu == 0.0 {
                        break;
                    }
                }
            }
        }
    } else {
        // Parallel axes: common normals lie in the plane of both axes (or are the axis
        // direction for two flat annuli, handled by the annulus overlap below).
        let off = pos_ab.translation.vector;
        let w = Vector3::new(off.x, off.y, 0.0);
        if w.norm() > 0.0 {
            let w = w.normalize();
            for sw in [1.0, -1.0] {
                for sz in [1.0, -1.0] {
                    let dir = w * (sw * na.x) + ez * (sz * na.y);
                    if dir.norm() > 0.0 {
                        try_dir(dir.normalize());
                    }
                }
            }
        }
        if na.x.abs() < 1e-15 && nb.x.abs() < 1e-15 {
            annulus_overlap(a0, a1, b0, b1, pos_ab, emit);
        }
    }
    // A flat annulus of one piece against a generator parallel to its plane.
    if na.x.abs() < 1e-15 {
        disk_vs_generators(a0, a1, b0, b1, pos_ab, emit);
    }
    if nb.x.abs() < 1e-15 {
        let pos_ba = pos_ab.inverse();
        disk_vs_generators(b0, b1, a0, a1, &pos_ba, &mut |q, p| {
            emit(pos_ab * p, pos_ab * q)
        });
    }
}

/// Radial directions `e` (horizontal unit vectors) where the normal line of a straight piece
/// with planar normal `n` is parallel to `dir` (frame-local); none for flat annuli.
fn radial_for_normal(n: nalgebra::Vector2<f64>, dir: &Vector3<f64>) -> [Option<Vector3<f64>>; 2] {
    let mut out = [None, None];
    if n.x.abs() < 1e-15 {
        return out;
    }
    for (i, s) in [1.0, -1.0].into_iter().enumerate() {
        // s * dir = n.x e + n.y ez  =>  e = (s dir - n.y ez) / n.x
        if (s * dir.z - n.y).abs() > 1e-9 {
            continue;
        }
        let e = Vector3::new(s * dir.x / n.x, s * dir.y / n.x, 0.0);
        let en = e.norm();
        if en > 0.0 {
            out[i] = Some(e / en);
        }
    }
    out
}

/// Closest points of two segments when both are interior and the connecting vector is
/// parallel to `dir`; for parallel segments, the middle of their overlap.
fn segment_common_normal(
    p0: Point3<f64>,
    p1: Point3<f64>,
    q0: Point3<f64>,
    q1: Point3<f64>,
    dir: &Vector3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let (b, c) = (d1.dot(&d2), d1.dot(&r));
    let den = a * e - b * b;
    if den > 1e-14 * a * e {
        let s = (b * f - c * e) / den;
        let t = (a * f - b * c) / den;
        if (-1e-9..=1.0 + 1e-9).contains(&s) && (-1e-9..=1.0 + 1e-9).contains(&t) {
            emit(p0 + d1 * s.clamp(0.0, 1.0), q0 + d2 * t.clamp(0.0, 1.0));
        }
    } else if a > 0.0 {
        // Parallel generators: offset orthogonal to the lines must be parallel to dir.
        let u = d1 / a.sqrt();
        let (t0, t1) = ((q0 - p0).dot(&u), (q1 - p0).dot(&u));
        let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(a.sqrt()));
        if lo <= hi {
            let tm = 0.5 * (lo + hi);
            let p = p0 + u * tm;
            let s = if (t1 - t0).abs() > 0.0 {
                (tm - t0) / (t1 - t0)
            } else {
                0.0
            };
            let q = q0 + d2 * s.clamp(0.0, 1.0);
            let _ = dir;
            emit(p, q);
        }
    }
}

/// Two flat annuli with parallel axes: a point in the overlap of their projections.
fn annulus_overlap(
    a0: Point2<f64>,
    a1: Point2<f64>,
    b0: Point2<f64>,
    b1: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (ra0, ra1) = (a0.x.min(a1.x), a0.x.max(a1.x));
    let (rb0, rb1) = (b0.x.min(b1.x), b0.x.max(b1.x));
    let cb = pos_ab * Point3::new(0.0, 0.0, b0.y);
    let w = nalgebra::Vector2::new(cb.x, cb.y);
    let d = w.norm();
    let u = if d > 0.0 {
        w / d
    } else {
        nalgebra::Vector2::x()
    };
    // Points on the line of centres: x = t u, |x| = |t|, |x - w| = |t - d|.
    let cands = [
        ra0,
        ra1,
        -ra0,
        -ra1,
        d + rb0,
        d - rb0,
        d + rb1,
        d - rb1,
        0.5 * d,
    ];
    for t in cands {
        let ta = t.abs();
        let tb = (t - d).abs();
        if ta >= ra0 - 1e-12 && ta <= ra1 + 1e-12 && tb >= rb0 - 1e-12 && tb <= rb1 + 1e-12 {
            let p = Point3::new(t * u.x, t * u.y, a0.y);
            let q = Point3::new(t * u.x, t * u.y, cb.z);
            emit(p, q);
            return;
        }
    }
}

/// A flat annulus `(a0, a1)` (frame A, horizontal) against the generators of the straight
/// piece `(b0, b1)` whose normal is the annulus normal: such a generator is parallel to the
/// annulus plane, so each of its points over the annulus is on a common normal.
/// Emits (point on annulus, point on generator) in A's frame.
fn disk_vs_generators(
    a0: Point2<f64>,
    a1: Point2<f64>,
    b0: Point2<f64>,
    b1: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (ra0, ra1) = (a0.x.min(a1.x), a0.x.max(a1.x));
    let db = b1 - b0;
    let nb = nalgebra::Vector2::new(-db.y, db.x).normalize();
    let ez_b = pos_ab.inverse_transform_vector(&Vector3::z());
    for e in radial_for_normal(nb, &ez_b).iter().flatten() {
        let (q0, q1) = (pos_ab * lift(b0, e), pos_ab * lift(b1, e));
        let d = q1 - q0;
        let (p0h, dh) = (
            nalgebra::Vector2::new(q0.x, q0.y),
            nalgebra::Vector2::new(d.x, d.y),
        );
        let a2 = dh.norm_squared();
        let tmin = if a2 > 0.0 {
            (-p0h.dot(&dh) / a2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let mut ts = vec![tmin, 0.0, 1.0, 0.5];
        // Radius crossings ra0, ra1 along the segment.
        for rr in [ra0, ra1] {
            let (qa, qb, qc) = (a2, 2.0 * p0h.dot(&dh), p0h.norm_squared() - rr * rr);
            let disc = qb * qb - 4.0 * qa * qc;
            if qa > 0.0 && disc >= 0.0 {
                ts.push((-qb - disc.sqrt()) / (2.0 * qa));
                ts.push((-qb + disc.sqrt()) / (2.0 * qa));
            }
        }
        for t in ts {
            if !(0.0..=1.0).contains(&t) {
                continue;
            }
            let x = q0 + d * t;
            let r = x.x.hypot(x.y);
            if r >= ra0 * (1.0 - 1e-12) && r <= ra1 * (1.0 + 1e-12) + 1e-300 {
                emit(Point3::new(x.x, x.y, a0.y), x);
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests;
