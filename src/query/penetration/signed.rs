//! The public entry points: [`penetration`] (the certified interval of the translational
//! penetration depth) and [`signed_distance`] (the distance when apart, minus the depth
//! when overlapping), with the signed distance's gradient where it is one.

use super::stages::penetration_after;
use crate::query::front::distance::{check_query, distance, Distance, QueryError, QueryOptions};
use crate::query::front::gradient::Gradient;
use crate::solid::Solid;
use nalgebra::{Point3, Vector3};
use std::time::Instant;

/// Depth relative to which an interval counts as narrow for the gradient (the interval
/// is narrow when `upper - lower <= max(2 (eps_a + eps_b), NARROW_REL * upper)`).
pub const NARROW_REL: f64 = 0.05;

/// Counters of one penetration query.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct PenetrationStats {
    /// Points classified: against both solids by the deepest-point ascent, against one by a
    /// ball's covering.
    pub probes: usize,
    /// Cells of the covering of translations ([`super::translation_cover`]), 0 when the
    /// interval met the width asked without it.
    pub cover_cells: usize,
    /// Distance queries, the first (at the given pose) included.
    pub distance_queries: usize,
    /// The time budget ran out before the interval met the requested width.
    pub budget_exhausted: bool,
}

/// The certificate of a penetration depth's lower bound (module doc of
/// [`mod@crate::query::penetration`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LowerCertificate {
    /// No positive lower bound was certified (`lower` is 0).
    None,
    /// The signed margins of `point` ([`super::deepest`]).
    Point,
    /// The covering of a detected ball's ways out, the ball centred at `point`
    /// ([`super::ball_depth`]).
    BallCovering,
    /// The covering of the translations shorter than `lower` by Lipschitz balls of
    /// several points' margins ([`super::translation_cover`]); `point`'s own certificate
    /// is the ball about no translation.
    TranslationCovering,
}

impl LowerCertificate {
    /// Its name in the JSON answers and the harness's tables: `none`, `point`,
    /// `ball_covering` or `translation_covering`.
    pub fn name(self) -> &'static str {
        match self {
            LowerCertificate::None => "none",
            LowerCertificate::Point => "point",
            LowerCertificate::BallCovering => "ball_covering",
            LowerCertificate::TranslationCovering => "translation_covering",
        }
    }
}

impl serde::Serialize for LowerCertificate {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// The certified interval of the penetration depth (module doc of
/// [`mod@crate::query::penetration`]). Points and directions are in the world frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Penetration {
    /// Certified lower bound: the sum of the true signed margins of a point (positive
    /// inside; the point inside at least one solid), 0 when no positive sum was certified,
    /// e.g. for solids apart or touching within the trees' accuracy.
    pub lower: f64,
    /// Certified upper bound: B moved by `s * direction`, any `s > upper`, is apart from A.
    pub upper: f64,
    /// Unit translation of B that achieves `upper` (zero when the solids are apart).
    pub direction: Vector3<f64>,
    /// The point of `lower`'s certificate, when there is one: the point whose signed
    /// margins give it, or the centre of the ball whose covering gives it (when a covering
    /// of translations raised `lower`, the point of its ball about no translation).
    pub point: Option<Point3<f64>>,
    /// Which certificate gives `lower`.
    pub certificate: LowerCertificate,
    /// The point of B (at its pose) that touches A last along `direction`: the contact of
    /// the separating translation, used by the gradient.
    pub contact_b: Option<Point3<f64>>,
    /// `upper - lower <= max(2 (eps_a + eps_b), NARROW_REL * upper)`: narrow enough for
    /// [`SignedDistance::gradient`].
    pub narrow: bool,
    pub stats: PenetrationStats,
}

/// The signed distance: the distance when apart, `-PD` when overlapping, as a certified
/// interval, with the distance query and (unless certified apart) the penetration query
/// it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct SignedDistance {
    pub lower: f64,
    pub upper: f64,
    pub distance: Distance,
    pub penetration: Option<Penetration>,
}

impl SignedDistance {
    /// The gradient with respect to B's pose (world frame; B's frame origin at `origin_b`).
    ///
    /// Apart: the distance's gradient ([`Distance::gradient`]). Overlapping, with a narrow
    /// interval: moving B by `v` changes the depth by `-direction . v` to first order where
    /// the minimal separating translation is unique and parallel to its contact normal
    /// (`PD(v) = min |t - v|` over separating `t`), so the signed distance's derivative is
    /// `direction` in translation and `(contact_b - origin_b) x direction` in a rotation
    /// vector about B's origin (the contact point moving with B). Where several
    /// translations are minimal the depth has no gradient and this is one of its one-sided
    /// derivatives; the direction is that of the upper bound's translation, whose angle to
    /// the minimal one shrinks with the interval's width. `None` when the interval is not
    /// narrow or the solids touch within the trees' accuracy.
    pub fn gradient(&self, origin_b: &Point3<f64>) -> Option<Gradient> {
        if self.distance.lower > 0.0 {
            return self.distance.gradient(origin_b);
        }
        let p = self.penetration.as_ref()?;
        if !p.narrow || p.lower.is_nan() || p.lower <= 0.0 {
            return None;
        }
        let contact = p.contact_b?;
        let u = p.direction;
        Some(Gradient {
            normal: u,
            translation: u,
            rotation: (contact - origin_b).cross(&u),
        })
    }
}

/// An answer for solids certified apart: depth 0.
fn apart() -> Penetration {
    Penetration {
        lower: 0.0,
        upper: 0.0,
        direction: Vector3::zeros(),
        point: None,
        certificate: LowerCertificate::None,
        contact_b: None,
        narrow: true,
        stats: PenetrationStats {
            distance_queries: 1,
            ..PenetrationStats::default()
        },
    }
}

/// Certified interval of the translational penetration depth of two posed solids
/// (module doc of [`mod@crate::query::penetration`]): `lower <= PD <= upper`.
///
/// `opts.tolerance` asks for `upper - lower` (the default, [`Tolerance::Trees`](crate::query::Tolerance::Trees), for
/// `2 (eps_a + eps_b)`; the lower bound alone loses up to twice the larger leaf bound);
/// `opts.budget.max_time` bounds the whole query, `max_node_pairs` each distance query.
/// Solids certified apart have depth `[0, 0]`.
///
/// # Errors
/// [`QueryError`] for poses outside the representable range.
pub fn penetration(a: &Solid, b: &Solid, opts: &QueryOptions) -> Result<Penetration, QueryError> {
    Ok(signed_distance(a, b, opts)?
        .penetration
        .unwrap_or_else(apart))
}

/// Certified interval of the signed distance: `[lower, upper]` of the distance when the
/// solids are certified apart; `[-PD upper, -PD lower]` when they overlap; and
/// `[-PD upper, distance upper]` when they touch within the trees' accuracy.
///
/// # Errors
/// [`QueryError`] for poses outside the representable range.
pub fn signed_distance(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
) -> Result<SignedDistance, QueryError> {
    check_query(a, b)?;
    let started = Instant::now();
    let d = distance(a, b, opts);
    if d.lower > 0.0 {
        return Ok(SignedDistance {
            lower: d.lower,
            upper: d.upper,
            distance: d,
            penetration: None,
        });
    }
    let p = penetration_after(a, b, opts, &d, started);
    let overlap = d.overlap || p.lower > 0.0;
    Ok(SignedDistance {
        lower: -p.upper,
        upper: if overlap { -p.lower } else { d.upper },
        distance: d,
        penetration: Some(p),
    })
}
