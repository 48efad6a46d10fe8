//! One direction of the search: the map from the source solid's frame to the target's, the
//! realised pairs, the running state and the inside census (module documentation of
//! [`super`], "The reduction" and "Inside census").

use crate::oracle::planar::PlanarIndex;
use nalgebra::{Isometry3, Matrix3, Point3, Vector3};

/// A map from the source solid's frame to the target's, with both profiles.
pub(super) struct Dir<'a> {
    pub(super) src: &'a PlanarIndex,
    pub(super) dst: &'a PlanarIndex,
    pub(super) rot: Matrix3<f64>,
    pub(super) trans: Vector3<f64>,
    /// Inside-census margin.
    pub(super) margin: f64,
}

impl<'a> Dir<'a> {
    /// Search over `src`'s surface against `dst`, `src_to_dst` mapping src's frame into dst's.
    pub(super) fn new(
        src: &'a PlanarIndex,
        dst: &'a PlanarIndex,
        src_to_dst: &Isometry3<f64>,
        margin: f64,
    ) -> Dir<'a> {
        Dir {
            src,
            dst,
            rot: *src_to_dst.rotation.to_rotation_matrix().matrix(),
            trans: src_to_dst.translation.vector,
            margin,
        }
    }
}

/// A realised pair in the source frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pair {
    pub(super) d: f64,
    pub(super) y: Point3<f64>,
    /// Target surface point, in the *source* frame.
    pub(super) x: Point3<f64>,
}

/// Running state of one direction.
pub(super) struct State {
    pub(super) best: Option<Pair>,
    pub(super) min_signed: f64,
    /// Where `min_signed` was found (source frame).
    pub(super) deep: Option<Point3<f64>>,
    pub(super) inside: bool,
    pub(super) cells: usize,
    pub(super) refinements: usize,
}

impl State {
    /// Nothing found yet.
    pub(super) fn new() -> State {
        State {
            best: None,
            min_signed: f64::INFINITY,
            deep: None,
            inside: false,
            cells: 0,
            refinements: 0,
        }
    }
}

impl<'a> Dir<'a> {
    pub(super) fn to_dst(&self, y: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rot * y.coords + self.trans)
    }

    pub(super) fn to_src(&self, x: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rot.transpose() * (x.coords - self.trans))
    }

    pub(super) fn surface_point(&self, k: usize, t: f64, th: f64) -> Point3<f64> {
        let p = self.src.geom.point(k, t);
        Point3::new(p[0] * th.cos(), p[0] * th.sin(), p[1])
    }

    /// `f` and its gradient at `(k, t, th)`: the realised pair and `(df/dt, df/dth)`.
    pub(super) fn f_grad(&self, k: usize, t: f64, th: f64) -> (Pair, [f64; 2]) {
        let j = self.src.geom.jet(k, t);
        let (c, s) = (th.cos(), th.sin());
        let y = Point3::new(j.p[0] * c, j.p[0] * s, j.p[1]);
        let dy_dt = Vector3::new(j.d1[0] * c, j.d1[0] * s, j.d1[1]);
        let dy_dth = Vector3::new(-j.p[0] * s, j.p[0] * c, 0.0);
        let q = self.to_dst(&y);
        let x = surface_foot(self.dst, &q);
        let v = q - x;
        let d = v.norm();
        let grad = if d > 0.0 {
            let n = self.rot.transpose() * (v / d);
            [n.dot(&dy_dt), n.dot(&dy_dth)]
        } else {
            [0.0, 0.0]
        };
        (
            Pair {
                d,
                y,
                x: self.to_src(&x),
            },
            grad,
        )
    }

    /// Signed census at a realised source point.
    pub(super) fn census_at(&self, y: &Point3<f64>, st: &mut State) {
        let q = self.to_dst(y);
        let s = self.dst.signed([q.x.hypot(q.y), q.z]);
        if s.value < 0.0 {
            if s.value < st.min_signed {
                st.min_signed = s.value;
                st.deep = Some(*y);
            }
            if -s.value > self.margin {
                st.inside = true;
            }
        }
    }
}

pub(super) trait BetterThan {
    fn is_none_or_worse(&self, d: f64) -> bool;
}

impl BetterThan for Option<Pair> {
    fn is_none_or_worse(&self, d: f64) -> bool {
        match self {
            None => true,
            Some(p) => d < p.d,
        }
    }
}

/// The closest point of `idx`'s surface of revolution to `q` (its frame): the planar closest
/// point of `q`'s meridian coordinates, lifted into `q`'s meridian plane.
pub(super) fn surface_foot(idx: &PlanarIndex, q: &Point3<f64>) -> Point3<f64> {
    let rho = q.x.hypot(q.y);
    let cp = idx.closest([rho, q.z]);
    let (c, s) = if rho > 0.0 {
        (q.x / rho, q.y / rho)
    } else {
        (1.0, 0.0)
    };
    Point3::new(cp.p[0] * c, cp.p[0] * s, cp.p[1])
}
