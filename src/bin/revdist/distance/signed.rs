//! `revdist distance --signed`: the signed distance and the penetration depth's certified
//! interval ([`revdist::query::penetration`]) in the JSON and text answers.

use nalgebra::{Point3, Vector3};
use revdist::query::{LowerCertificate, Penetration, SignedDistance};
use serde::Serialize;

use super::{GradientJson, Output};

/// A certified interval.
#[derive(Debug, Serialize)]
pub(crate) struct IntervalJson {
    lower: f64,
    upper: f64,
}

/// [`Penetration`] as written in JSON (A's frame).
#[derive(Debug, Serialize)]
pub(crate) struct PenetrationJson {
    /// Certified lower bound of the translational penetration depth.
    lower: f64,
    /// Certified upper bound: B moved by more than this along `direction` is apart from A.
    upper: f64,
    /// Unit translation of B that achieves `upper`.
    direction: [f64; 3],
    /// The point whose signed margins give `lower` (absent when `lower` is 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    point: Option<[f64; 3]>,
    /// Which certificate gives `lower`: `none`, `point`, `ball_covering` or
    /// `translation_covering`.
    certificate: LowerCertificate,
    /// `upper - lower <= max(2 (eps_A + eps_B), 5 % of upper)`: the gradient is given.
    narrow: bool,
    /// Points classified by the deepest-point search.
    probes: usize,
    /// Cells of the covering of B's translations (0 when the interval was narrow without it).
    cover_cells: usize,
    /// Distance queries spent, the first at the given pose included.
    distance_queries: usize,
    budget_exhausted: bool,
}

fn array(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl From<&Penetration> for PenetrationJson {
    fn from(p: &Penetration) -> Self {
        PenetrationJson {
            lower: p.lower,
            upper: p.upper,
            direction: array(&p.direction),
            point: p.point.map(|x| array(&x.coords)),
            certificate: p.certificate,
            narrow: p.narrow,
            probes: p.stats.probes,
            cover_cells: p.stats.cover_cells,
            distance_queries: p.stats.distance_queries,
            budget_exhausted: p.stats.budget_exhausted,
        }
    }
}

impl Output {
    /// Adds the signed distance, the penetration depth (when not certified apart) and the
    /// signed distance's gradient ([`SignedDistance::gradient`]), B's origin at `origin_b`.
    pub(crate) fn with_signed(mut self, s: &SignedDistance, origin_b: &Vector3<f64>) -> Self {
        self.signed_distance = Some(IntervalJson {
            lower: s.lower,
            upper: s.upper,
        });
        self.penetration = s.penetration.as_ref().map(PenetrationJson::from);
        self.gradient = s.gradient(&Point3::from(*origin_b)).map(|g| GradientJson {
            normal: g.normal.into(),
            translation: g.translation.into(),
            rotation: g.rotation.into(),
        });
        self
    }
}

/// The text answer's lines for the signed distance.
pub(crate) fn print_text(s: &SignedDistance) {
    println!("signed    [{:.12e}, {:.12e}]", s.lower, s.upper);
    if let Some(p) = &s.penetration {
        println!("depth     [{:.12e}, {:.12e}]", p.lower, p.upper);
        let d = p.direction;
        println!("direction {:.9} {:.9} {:.9}", d.x, d.y, d.z);
        if let Some(x) = p.point {
            println!("deepest   {:.9} {:.9} {:.9}", x.x, x.y, x.z);
        }
        println!("lower by  {:?}", p.certificate);
        println!(
            "search    {} probes, {} cover cells, {} distance queries{}",
            p.stats.probes,
            p.stats.cover_cells,
            p.stats.distance_queries,
            if p.stats.budget_exhausted {
                " (budget exhausted)"
            } else {
                ""
            }
        );
    }
}
