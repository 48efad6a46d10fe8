//! Contacts of a step (module documentation of [`super`], step 3): the certified contact of
//! a queried pair and the speculative contacts of its small manifold of earlier witnesses.

use super::World;
use nalgebra::{Point3, Vector3};
use revdist::solid::Solid;

/// One contact of a step.
pub(super) struct Contact {
    pub(super) i: usize,
    pub(super) j: usize,
    pub(super) lower: f64,
    pub(super) r_i: Vector3<f64>,
    pub(super) r_j: Vector3<f64>,
    pub(super) n: Vector3<f64>,
    pub(super) t: [Vector3<f64>; 2],
    pub(super) k_n: f64,
    pub(super) k_t: [f64; 2],
    pub(super) target: f64,
    pub(super) lambda_n: f64,
    pub(super) lambda_t: [f64; 2],
    /// The pair's certified contact (its `lower` drives step 4); `false` for the extra
    /// points of the pair's manifold, which only shape the velocities.
    pub(super) certified: bool,
}

/// A witness pair remembered from an earlier step, in the bodies' local frames.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stored {
    a: Point3<f64>,
    b: Point3<f64>,
    /// Normal in body `i`'s frame.
    n: Vector3<f64>,
}

/// Most remembered witness pairs per body pair.
const MANIFOLD_POINTS: usize = 4;

impl World {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn contact(
        &self,
        i: usize,
        j: usize,
        lower: f64,
        pa: Point3<f64>,
        pb: Point3<f64>,
        n: Vector3<f64>,
        h: f64,
    ) -> Contact {
        let (bi, bj) = (&self.bodies[i], &self.bodies[j]);
        let r_i = pa - bi.x;
        let r_j = pb - bj.x;
        let helper = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let t0 = n.cross(&helper).normalize();
        let t1 = n.cross(&t0);
        let (ii, ij) = (bi.inv_inertia(), bj.inv_inertia());
        let (mi, mj) = (bi.inv_mass(), bj.inv_mass());
        let k = |d: &Vector3<f64>| {
            let a = r_i.cross(d);
            let b = r_j.cross(d);
            mi + mj + a.dot(&(ii * a)) + b.dot(&(ij * b))
        };
        let skin = self.skin;
        let target = if lower > skin {
            -(lower - skin) / h
        } else if lower < 0.5 * skin {
            (0.5 * skin - lower) / (4.0 * h)
        } else {
            0.0
        };
        Contact {
            i,
            j,
            lower,
            r_i,
            r_j,
            n,
            t: [t0, t1],
            k_n: k(&n),
            k_t: [k(&t0), k(&t1)],
            target,
            lambda_n: 0.0,
            lambda_t: [0.0; 2],
            certified: false,
        }
    }

    /// The pair's small contact manifold: witness pairs of earlier steps (kept while their
    /// points stay within a few skins of each other and have not slid apart) become extra
    /// speculative contacts at their current estimated gap, and the new witness pair joins
    /// them unless an old one is close to it. These contacts only shape the velocities (a
    /// ring lying on the table is held at several points instead of rocking about one);
    /// the no-overlap guarantee rests on the certified contact alone (step 4).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn manifold_contacts(
        &mut self,
        i: usize,
        j: usize,
        d: &revdist::query::Distance,
        n: Vector3<f64>,
        solids: &[Solid],
        h: f64,
        out: &mut Vec<Contact>,
    ) {
        let (pose_i, pose_j) = (solids[i].pose, solids[j].pose);
        let reach = 3.0 * self.skin;
        let slack = d.upper - d.lower;
        let spread = 0.1 * self.bodies[i].sphere.1.min(self.bodies[j].sphere.1);
        let mut kept: Vec<Stored> = Vec::new();
        let stored = self.manifolds.remove(&(i, j)).unwrap_or_default();
        for st in stored {
            let (pa, pb) = (pose_i * st.a, pose_j * st.b);
            let nw = pose_i.rotation * st.n;
            let sep = pb - pa;
            let gap = sep.dot(&nw);
            let slide = (sep - nw * gap).norm();
            if gap > reach || slide > self.skin || (pa - d.point_a).norm() < spread {
                continue;
            }
            out.push(self.contact(i, j, (gap - slack).max(0.0), pa, pb, nw, h));
            kept.push(st);
        }
        if d.lower < reach {
            if kept.len() >= MANIFOLD_POINTS {
                kept.remove(0);
            }
            kept.push(Stored {
                a: pose_i.inverse_transform_point(&d.point_a),
                b: pose_j.inverse_transform_point(&d.point_b),
                n: pose_i.rotation.inverse_transform_vector(&n),
            });
        }
        if !kept.is_empty() {
            self.manifolds.insert((i, j), kept);
        }
    }
}
