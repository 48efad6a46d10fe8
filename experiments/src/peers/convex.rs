//! The convex solids of revolution of the peers' convex table (`revdist::models::basic`:
//! sphere, capsule, cylinder, cone) as the exact primitives coal and parry3d know, in the
//! solid's own frame: axis z, centre of the primitive at height `zc` on the axis.

/// An exact primitive with its axis on z, centred at `(0, 0, zc)`; `lz` is the length along
/// the axis as coal counts it (capsule: its segment; cylinder and cone: the height; the cone's
/// base is at `zc - lz/2`, its apex at `zc + lz/2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    Sphere { r: f64, zc: f64 },
    Capsule { r: f64, lz: f64, zc: f64 },
    Cylinder { r: f64, lz: f64, zc: f64 },
    Cone { r: f64, lz: f64, zc: f64 },
}

/// The models of the convex table, in table order.
pub const CONVEX_MODELS: [&str; 4] = ["sphere", "capsule", "cylinder", "cone"];

/// The primitive of the built-in model `name`, with the dimensions `revdist::models::basic`
/// gives it (the doc comments there; the test below checks them against the profiles).
pub fn primitive(name: &str) -> Option<Primitive> {
    Some(match name {
        "sphere" => Primitive::Sphere { r: 0.75, zc: 0.75 },
        "capsule" => Primitive::Capsule {
            r: 0.4,
            lz: 0.8,
            zc: 0.8,
        },
        "cylinder" => Primitive::Cylinder {
            r: 0.5,
            lz: 1.5,
            zc: 0.75,
        },
        "cone" => Primitive::Cone {
            r: 0.6,
            lz: 1.5,
            zc: 0.75,
        },
        _ => return None,
    })
}

impl Primitive {
    /// The profile's extent `(rho max, z min, z max)` this primitive has.
    pub fn extent(&self) -> (f64, f64, f64) {
        match *self {
            Primitive::Sphere { r, zc } => (r, zc - r, zc + r),
            Primitive::Capsule { r, lz, zc } => (r, zc - 0.5 * lz - r, zc + 0.5 * lz + r),
            Primitive::Cylinder { r, lz, zc } | Primitive::Cone { r, lz, zc } => {
                (r, zc - 0.5 * lz, zc + 0.5 * lz)
            }
        }
    }

    /// The radius GJK sweeps around the primitive's core (coal runs GJK on a sphere's centre
    /// and a capsule's segment and adds the radius afterwards): the `||x^k||` of coal's
    /// convergence test is the core distance, the distance plus these radii.
    pub fn swept_radius(&self) -> f64 {
        match *self {
            Primitive::Sphere { r, .. } | Primitive::Capsule { r, .. } => r,
            Primitive::Cylinder { .. } | Primitive::Cone { .. } => 0.0,
        }
    }

    /// Radius of the solid at height `z` (its meridian), `None` outside its extent.
    pub fn radius_at(&self, z: f64) -> Option<f64> {
        let (_, lo, hi) = self.extent();
        if z < lo || z > hi {
            return None;
        }
        Some(match *self {
            Primitive::Sphere { r, zc } => (r * r - (z - zc).powi(2)).max(0.0).sqrt(),
            Primitive::Capsule { r, lz, zc } => {
                let dz = ((z - zc).abs() - 0.5 * lz).max(0.0);
                (r * r - dz * dz).max(0.0).sqrt()
            }
            Primitive::Cylinder { r, .. } => r,
            Primitive::Cone { r, lz, .. } => r * (hi - z) / lz,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use revdist::solid::Solid;
    use std::f64::consts::FRAC_PI_2;
    use std::sync::Arc;

    /// Each primitive is the model's solid: same bounding box of the profile, and a small ball
    /// just outside the primitive's meridian is just outside the revdist solid (a cone
    /// standing the wrong way up, or a wrong radius, puts it inside or too far).
    #[test]
    fn primitives_match_the_models() {
        for name in CONVEX_MODELS {
            let p = primitive(name).unwrap();
            let profile = revdist::models::model(name).unwrap();
            let b = profile.bounding_box();
            let (r, lo, hi) = p.extent();
            assert!(
                (b.max.x - r).abs() < 1e-12,
                "{name}: radius {} vs {r}",
                b.max.x
            );
            assert!(
                (b.min.y - lo).abs() < 1e-12 && (b.max.y - hi).abs() < 1e-12,
                "{name}"
            );
            // Meridian points: a small ball (radius `R`, centred on its frame's origin) whose
            // centre is `gap + R` out from the primitive's side point (rho, z) is at most `gap`
            // from the solid, and apart from it (the solids are convex and the centre is
            // outside).
            const R: f64 = 0.01;
            let ball = revdist::profile::Profile::new(
                "probe",
                vec![
                    revdist::models::primitives::arc([0.0, 0.0], R, -FRAC_PI_2, FRAC_PI_2).unwrap(),
                ],
            )
            .unwrap();
            let solid = Solid::from_profile(Arc::new(profile), 1e-9).unwrap();
            let probe = Solid::from_profile(Arc::new(ball), 1e-9).unwrap();
            for k in 1..8 {
                let z = lo + (hi - lo) * k as f64 / 8.0;
                let rho = p.radius_at(z).unwrap();
                let gap = 0.1;
                let pose = nalgebra::Isometry3::translation(rho + gap + R, 0.0, z);
                let d = revdist::query::distance(
                    &solid,
                    &probe.with_pose(pose),
                    &revdist::query::QueryOptions::default(),
                );
                assert!(
                    !d.overlap && d.lower > 0.0 && d.upper <= gap + 1e-6,
                    "{name} at z {z}: distance interval [{}, {}] vs gap {gap}",
                    d.lower,
                    d.upper
                );
            }
        }
        assert!(primitive("pawn").is_none());
    }
}
