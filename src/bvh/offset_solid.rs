//! Solids that are offsets of a point or a circle: a ball (an open profile that is a half
//! circle centred on the axis) or a solid torus (a closed profile that is one full circle
//! off the axis) is the set of points within `r` of its *core*, a point on the axis or a
//! circle coaxial with it. The tree detects such a chain once, when it is built; the
//! query answers pairs of them in closed form ([`crate::query::closed_form`]).
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
use std::f64::consts::{PI, TAU};

/// The core of an offset solid, in the solid's own frame (axis z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Core {
    /// A point on the axis at height `z` (the solid is a ball).
    Point { z: f64 },
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

/// Detects a chain of profile pieces that is one circle: a closed loop around a circle off
/// the axis (solid torus) or a half circle centred on the axis from axis to axis (ball).
/// `tree_eps` is the chain's Hausdorff bound to the true profile.
pub fn detect(chain: &[ProfileArc], kind: ProfileKind, tree_eps: f64) -> Option<OffsetSolid> {
    let (center, radius) = match chain.first()? {
        ProfileArc::Arc { center, radius, .. } => (*center, *radius),
        ProfileArc::Segment { .. } => return None,
    };
    if radius.is_nan() || radius <= 0.0 || !center.coords.iter().all(|x| x.is_finite()) {
        return None;
    }
    let mut off = 0.0f64;
    let mut sweep_sum = 0.0;
    let mut sign = 0.0f64;
    for p in chain {
        let ProfileArc::Arc {
            center: c,
            radius: r,
            sweep,
            ..
        } = *p
        else {
            return None;
        };
        // Every point of this arc is within |c - center| + |r - radius| of the circle.
        off = off.max((c - center).norm() + (r - radius).abs());
        if sweep == 0.0 {
            continue;
        }
        if sign == 0.0 {
            sign = sweep.signum();
        } else if sweep.signum() != sign {
            return None;
        }
        sweep_sum += sweep.abs();
    }
    // Gaps between consecutive pieces (and the closing one for a loop) leave parts of the
    // circle uncovered by at most the gap.
    let mut gap = 0.0f64;
    for w in chain.windows(2) {
        gap = gap.max((w[1].start() - w[0].end()).norm());
    }
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
