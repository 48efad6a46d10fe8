//! Solids that are offsets of a point, a segment of the axis or a circle: a ball (an open
//! profile that is a half circle centred on the axis), a capsule (an open profile of a
//! quarter circle, a straight side parallel to the axis and a quarter circle, both circles of
//! one radius centred on the axis) or a solid torus (a closed profile that is one full
//! circle off the axis) is the set of points within `r` of its *core*, a point or a segment
//! of the axis or a circle coaxial with it. The tree detects such a chain once, when it is
//! built; the query answers pairs of them in closed form ([`crate::query::closed_form`]).
//!
//! Certification: the tree's approximating chain (biarcs) lies within the tree's `eps` of
//! the true profile, and is detected to lie within `detect_error` of the circle (each arc's
//! centre and radius off by at most that, consecutive arcs joined, sweeps of one sign adding
//! up to the full or half turn). So the true boundary is within `h = eps + detect_error` of
//! the offset surface, and the true solid contains the core's offset by `r - h` and lies in
//! its offset by `r + h` (the profile curve winds once about the circle's centre). The
//! distance between the true solids is therefore within `h_a + h_b` of the closed form.

use super::patch::ProfileArc;
use crate::profile::ProfileKind;
use crate::tolerances::DETECT_REL;
use nalgebra::Point2;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The core of an offset solid, in the solid's own frame (axis z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Core {
    /// A point on the axis at height `z` (the solid is a ball).
    Point { z: f64 },
    /// The segment of the axis from height `z0` to `z1 > z0` (the solid is a capsule).
    Segment { z0: f64, z1: f64 },
    /// The circle of radius `rho` at height `z` about the axis (a solid torus).
    Circle { rho: f64, z: f64 },
}

/// A solid that is, within `error`, the set of points within `radius` of its core.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetSolid {
    pub core: Core,
    pub radius: f64,
    /// Two-sided Hausdorff bound between the true boundary and the offset surface: the
    /// tree's eps plus the detection error (module doc).
    pub error: f64,
}

/// Detects a chain of profile pieces that is the offset of a point, a segment of the axis
/// or a circle: `detect_circle`, else `detect_capsule`. `tree_eps` is the chain's
/// Hausdorff bound to the true profile.
pub fn detect(chain: &[ProfileArc], kind: ProfileKind, tree_eps: f64) -> Option<OffsetSolid> {
    detect_circle(chain, kind, tree_eps).or_else(|| detect_capsule(chain, kind, tree_eps))
}

/// Detects a chain of profile pieces that is one circle: a closed loop around a circle off
/// the axis (solid torus) or a half circle centred on the axis from axis to axis (ball).
fn detect_circle(chain: &[ProfileArc], kind: ProfileKind, tree_eps: f64) -> Option<OffsetSolid> {
    let (center, radius) = match chain.first()? {
        ProfileArc::Arc { center, radius, .. } => (*center, *radius),
        ProfileArc::Segment { .. } => return None,
    };
    if radius.is_nan() || radius <= 0.0 || !center.coords.iter().all(|x| x.is_finite()) {
        return None;
    }
    // Every arc, each within `off` of the circle (`|c - center| + |r - radius|`), turning
    // one way.
    let (arcs, off, sweep_sum, _) = lead_arcs(chain.iter(), center, radius, f64::INFINITY)?;
    if arcs != chain.len() {
        return None;
    }
    // Gaps between consecutive pieces (and the closing one for a loop) leave parts of the
    // circle uncovered by at most the gap.
    let mut gap = largest_gap(chain);
    let (turn, core, axis_off) = match kind {
        ProfileKind::Closed => {
            gap = gap.max((chain[0].start() - chain[chain.len() - 1].end()).norm());
            if center.x < radius {
                return None;
            }
            (
                TAU,
                Core::Circle {
                    rho: center.x,
                    z: center.y,
                },
                0.0,
            )
        }
        ProfileKind::OpenOnAxis => (PI, Core::Point { z: center.y }, center.x.abs()),
    };
    let coverage = radius * (sweep_sum - turn).abs();
    let detect_error = off + gap + coverage + axis_off;
    let scale = 1.0 + center.coords.norm() + radius;
    if detect_error.is_nan() || detect_error > DETECT_REL * scale {
        return None;
    }
    Some(OffsetSolid {
        core,
        radius,
        error: tree_eps + detect_error,
    })
}

/// The largest gap between consecutive pieces of `chain`.
fn largest_gap(chain: &[ProfileArc]) -> f64 {
    chain
        .windows(2)
        .map(|w| (w[1].start() - w[0].end()).norm())
        .fold(0.0, f64::max)
}

/// The lead arcs of `pieces` about one centre (a capsule's end, or a whole circle): how many
/// lead pieces are arcs about `center` (within `tol`), the largest distance of their points
/// from the circle of radius `radius` about it (`|c - center| + |r - radius|`), their total
/// sweep and its sign (0 for none); `None` when their sweeps change sign.
fn lead_arcs<'a>(
    pieces: impl Iterator<Item = &'a ProfileArc>,
    center: Point2<f64>,
    radius: f64,
    tol: f64,
) -> Option<(usize, f64, f64, f64)> {
    let (mut count, mut off, mut sweep_sum, mut sign) = (0, 0.0f64, 0.0, 0.0f64);
    for p in pieces {
        let ProfileArc::Arc {
            center: c,
            radius: r,
            sweep,
            ..
        } = *p
        else {
            break;
        };
        let piece_off = (c - center).norm() + (r - radius).abs();
        if piece_off.is_nan() || piece_off > tol {
            break;
        }
        off = off.max(piece_off);
        if sweep != 0.0 {
            if sign == 0.0 {
                sign = sweep.signum();
            } else if sweep.signum() != sign {
                return None;
            }
            sweep_sum += sweep.abs();
        }
        count += 1;
    }
    Some((count, off, sweep_sum, sign))
}

/// Detects a capsule: an open chain of arcs about a point `c0` of the axis sweeping a
/// quarter turn, segments at distance `r` from the axis between the heights of `c0` and
/// `c1`, and arcs about a second point `c1` of the axis sweeping a quarter turn the same way,
/// every arc of radius `r`.
///
/// Certification, as for the ball (module doc): every point of an end's arcs is within
/// their `off` of the circle of radius `r` about its centre, and the arcs run monotonically
/// from the axis through a quarter turn (within the coverage error), so within `off` plus
/// the coverage of the capsule's spherical cap; every point of a segment whose end points
/// are `|rho - r| <= off` from the side and within the core's heights is that close to the
/// side. The detection error adds those, the gaps between pieces, the centres' distance
/// from the axis and the chain's ends' distance from the poles (a chain starting at the
/// other pole of `c0` would dent the capsule).
fn detect_capsule(chain: &[ProfileArc], kind: ProfileKind, tree_eps: f64) -> Option<OffsetSolid> {
    if kind != ProfileKind::OpenOnAxis {
        return None;
    }
    let (
        ProfileArc::Arc {
            center: c0, radius, ..
        },
        ProfileArc::Arc { center: c1, .. },
    ) = (*chain.first()?, *chain.last()?)
    else {
        return None;
    };
    if radius.is_nan()
        || radius <= 0.0
        || !c0
            .coords
            .iter()
            .chain(c1.coords.iter())
            .all(|x| x.is_finite())
    {
        return None;
    }
    let scale = 1.0 + c0.coords.norm() + c1.coords.norm() + radius;
    let tol = DETECT_REL * scale;
    let (lead, off0, sweep0, sign0) = lead_arcs(chain.iter(), c0, radius, tol)?;
    let (trail, off1, sweep1, sign1) = lead_arcs(chain.iter().rev(), c1, radius, tol)?;
    // The chain runs from the pole of `c0` away from `c1` to the pole of `c1` away from
    // `c0`, turning towards the side: counter-clockwise when it climbs.
    let climb = (c1.y - c0.y).signum();
    if lead + trail >= chain.len() || sign0 != climb || sign1 != climb {
        // One circle (a ball, or not an offset), no side between the caps, or caps that
        // turn the wrong way.
        return None;
    }
    let poles_off = (chain[0].start() - Point2::new(0.0, c0.y - climb * radius)).norm()
        + (chain[chain.len() - 1].end() - Point2::new(0.0, c1.y + climb * radius)).norm();
    let (zlo, zhi) = (c0.y.min(c1.y), c0.y.max(c1.y));
    let mut side_off = 0.0f64;
    for p in &chain[lead..chain.len() - trail] {
        let ProfileArc::Segment { start, end } = *p else {
            return None;
        };
        for q in [start, end] {
            let beyond = (zlo - q.y).max(q.y - zhi).max(0.0);
            side_off = side_off.max((q.x - radius).abs() + beyond);
        }
    }
    let gap = largest_gap(chain);
    let coverage = radius * ((sweep0 - FRAC_PI_2).abs() + (sweep1 - FRAC_PI_2).abs());
    let axis_off = c0.x.abs().max(c1.x.abs());
    let detect_error = off0.max(off1).max(side_off) + gap + coverage + axis_off + poles_off;
    if detect_error.is_nan() || detect_error > tol {
        return None;
    }
    Some(OffsetSolid {
        core: Core::Segment { z0: zlo, z1: zhi },
        radius,
        error: tree_eps + detect_error,
    })
}
