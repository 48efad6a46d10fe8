//! The solid level's cases: each family's pair at its relative pose with the closed form of
//! its exact distance, stated beside its construction.

use super::exact::{ball_torus_gap, exact, float, hypot, ExactPose};
use super::solids::{cylinder, ring, Shapes};
use super::{Error, SOLID_FAMILIES};
use crate::Draw;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use rug::{Float, Rational};
use verify::exact_circle::PREC;

/// A pair at its relative pose `P` (B in A's frame) with the exact distance for `P`.
pub(super) struct SolidCase {
    pub(super) variant: &'static str,
    pub(super) a: Solid,
    pub(super) b: Solid,
    pub(super) rel: Isometry3<f64>,
    pub(super) exact: Float,
}

fn spin(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::TAU * rng.next_f64())
}

/// A random horizontal unit vector.
fn horizontal(rng: &mut SplitMix64) -> Vector3<f64> {
    let phi = std::f64::consts::TAU * rng.next_f64();
    Vector3::new(phi.cos(), phi.sin(), 0.0)
}

/// A random spin about z followed by a tilt of `angle` about a random horizontal axis.
fn tilted(rng: &mut SplitMix64, angle: f64) -> UnitQuaternion<f64> {
    let axis = nalgebra::Unit::new_normalize(horizontal(rng));
    UnitQuaternion::from_axis_angle(&axis, angle) * spin(rng)
}

/// The pose with rotation `r` that puts the local axis point (0, 0, `z`) (a ball's centre) at
/// `c`.
fn centred_at(c: Vector3<f64>, r: UnitQuaternion<f64>, z: f64) -> Isometry3<f64> {
    pose(c - r * Vector3::new(0.0, 0.0, z), r)
}

pub(super) fn pose(t: Vector3<f64>, r: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), r)
}

/// Builds variant `vi` of solid family `fi` at perturbation `d` (0 for the degenerate
/// configuration). Every closed form is stated next to its construction; `max(0, .)` is
/// applied by the caller (solids that touch or overlap have distance 0).
pub(super) fn solid_case(
    shapes: &Shapes,
    fi: usize,
    vi: usize,
    d: f64,
    rng: &mut SplitMix64,
) -> Result<SolidCase, Error> {
    let (family, variants) = SOLID_FAMILIES[fi];
    let variant = variants[vi];
    let s = shapes;
    let zero = || Float::with_val(PREC, 0);
    let case = |a: &Solid, b: &Solid, rel: Isometry3<f64>, exact: Float| SolidCase {
        variant,
        a: a.clone(),
        b: b.clone(),
        rel,
        exact,
    };
    // The built-in sphere (radius 0.75) centred at `c`, turned by `rot`, against the ring:
    // the exact gap of [`ball_torus_gap`].
    let sphere_at = |c: Vector3<f64>, rot: UnitQuaternion<f64>| {
        let rel = centred_at(c, rot, 0.75);
        let p = ExactPose::of(&rel).place([0.0, 0.0, 0.75]);
        let gap = ball_torus_gap(&p, 0.75, 0.9, 0.6, 0.6);
        case(&s.ring, &s.sphere, rel, gap)
    };
    Ok(match (family, variant) {
        // Coaxial stacks, moved d off the coaxial configuration: B above A with a gap d.
        // Sphere on the cylinder (top disk z = 1.5, radius 0.5), its centre c d off the axis,
        // B turned at random (a ball is invariant): every point of B has z >= c_z - 0.75,
        // every point of A z <= 1.5, and the sphere's lowest point lies above the disk
        // (|c_xy| = d < 0.5), so d_exact = c_z - 2.25.
        ("coaxial stacks", "sphere on cylinder (off axis)") => {
            let rot = rng.rotation();
            let c = d * horizontal(rng) + Vector3::new(0.0, 0.0, 2.25 + d);
            let rel = centred_at(c, rot, 0.75);
            let cz = float(&ExactPose::of(&rel).place([0.0, 0.0, 0.75])[2]);
            case(&s.cylinder, &s.sphere, rel, cz - 2.25)
        }
        // A cylinder (radius 0.5) on the cylinder's top disk, B's axis tilted by d about a
        // random horizontal axis. B's lowest point is on its bottom rim: the height of
        // R (x, y, 0) + t over the rim x^2 + y^2 = 0.25 is at least t_z - 0.5 |((R e_x)_z,
        // (R e_y)_z)|, and that point is within 0.5 of the axis, above A's top disk, while A
        // stays below z = 1.5: d_exact = t_z - 0.5 |((R e_x)_z, (R e_y)_z)| - 1.5. The gap is
        // d by construction (t_z = 1.5 + d + 0.5 sin d).
        ("coaxial stacks", "cylinder on cylinder (tilted)") => {
            let rel = pose(
                Vector3::new(0.0, 0.0, 1.5 + d + 0.5 * d.sin()),
                tilted(rng, d),
            );
            let e = ExactPose::of(&rel);
            let drop = hypot(&float(&e.rot[0][2]), &float(&e.rot[1][2])) * 0.5f64;
            case(&s.cylinder, &s.cylinder, rel, float(&e.t[2]) - drop - 1.5)
        }
        // A cylinder tilted by d, its bottom centre d above the cone's apex p = (0, 0, 1.5).
        // The apex is the cone's extreme point in every direction within 68 degrees of its
        // axis (half-angle atan(0.6 / 1.5)), so the cone's nearest point to B's bottom plane
        // (normal n = R e_z) is p, at height (t - p) . n below it, and its foot lies inside
        // B's bottom disk (d off centre): d_exact = (t - p) . n.
        ("coaxial stacks", "cylinder on cone apex (tilted)") => {
            let rel = pose(Vector3::new(0.0, 0.0, 1.5 + d), tilted(rng, d));
            let e = ExactPose::of(&rel);
            let mut h = Float::with_val(PREC, 0);
            for (k, apex) in [0.0, 0.0, 1.5].into_iter().enumerate() {
                let dk: Rational = &e.t[k] - exact(apex);
                h += float(&Rational::from(&dk * &e.rot[2][k]));
            }
            case(&s.cone, &s.cylinder, rel, h)
        }
        // Ring on ring, exactly coaxial (a spin about z keeps B's axis exactly z): equal
        // tubes one above the other, tube circles of radius 0.9 at z = 0.6 and t_z + 0.6:
        // d_exact = t_z - 2 * 0.6 (a continuum of closest pairs along a circle).
        ("coaxial stacks", _) => {
            let rel = pose(Vector3::new(0.0, 0.0, 1.2 + d), spin(rng));
            let tz = float(&ExactPose::of(&rel).t[2]);
            case(&s.ring, &s.ring, rel, tz - float(&exact(2.0 * 0.6)))
        }
        // Touching spheres (radius 0.75, centres (0, 0, 0.75) in their frames): B's centre
        // at (0, 0, 0.75) + (1.5 + d) u, u random: d = |c_b - c_a| - 1.5.
        ("touching", "sphere-sphere") => {
            let (rot, u) = (rng.rotation(), rng.unit_vector());
            let c_a = Vector3::new(0.0, 0.0, 0.75);
            let t = c_a + (1.5 + d) * u - rot * c_a;
            let rel = pose(t, rot);
            let c_b = ExactPose::of(&rel).place([0.0, 0.0, 0.75]);
            let dx = |k: usize| float(&(&c_b[k] - exact(c_a[k])));
            let dist = Float::with_val(PREC, dx(0).square() + dx(1).square() + dx(2).square());
            case(&s.sphere, &s.sphere, rel, dist.sqrt() - 1.5)
        }
        // The sphere's centre at distance 0.6 + 0.75 + d from the ring's tube circle, in a
        // random meridian half-plane at a random angle a in [-90, 90] degrees from the
        // outward radial direction: d = gap of [`ball_torus_gap`].
        ("touching", "sphere-torus") => {
            let rot = rng.rotation();
            let (phi, a) = (
                std::f64::consts::TAU * rng.next_f64(),
                std::f64::consts::PI * (rng.next_f64() - 0.5),
            );
            let reach = 0.6 + 0.75 + d;
            let (rho, z) = (0.9 + reach * a.cos(), 0.6 + reach * a.sin());
            sphere_at(Vector3::new(rho * phi.cos(), rho * phi.sin(), z), rot)
        }
        // Two cylinders (radius 0.5, height 1.5) with parallel axes 1 + d apart and heights
        // offset by at most 1 (their sides overlap in z): the closest points are on the two
        // sides, d = |axis offset| - 2 * 0.5 (a continuum along a segment).
        ("touching", _) => {
            let phi = std::f64::consts::TAU * rng.next_f64();
            let dz = 2.0 * rng.next_f64() - 1.0;
            let t = Vector3::new((1.0 + d) * phi.cos(), (1.0 + d) * phi.sin(), dz);
            let rel = pose(t, spin(rng));
            let e = ExactPose::of(&rel);
            let off = hypot(&float(&e.t[0]), &float(&e.t[1]));
            case(&s.cylinder, &s.cylinder, rel, off - 1.0)
        }
        // Nested: the inner surface d inside the outer one; the solids' distance is 0.
        // Ball of radius 0.5 in the sphere of radius 0.75, centres 0.25 - d apart.
        ("nested", "ball in sphere") => {
            let (rot, u) = (rng.rotation(), rng.unit_vector());
            let c = Vector3::new(0.0, 0.0, 0.75) + (0.25 - d) * u;
            let rel = centred_at(c, rot, 0.5);
            case(&s.sphere, &s.ball_05, rel, zero())
        }
        // Ball of radius 0.4 in the cylinder (radius 0.5, height 1.5), its centre 0.1 - d
        // from the axis at height 0.5..1.0: d from the side, >= 0.1 from the disks.
        ("nested", "ball in cylinder") => {
            let rot = rng.rotation();
            let phi = std::f64::consts::TAU * rng.next_f64();
            let z = 0.5 + 0.5 * rng.next_f64();
            let c = Vector3::new((0.1 - d) * phi.cos(), (0.1 - d) * phi.sin(), z);
            let rel = centred_at(c, rot, 0.4);
            case(&s.cylinder, &s.ball_04, rel, zero())
        }
        // The cone (base radius 0.6, height 1.5) in a cylinder of radius 0.6 + d and height
        // 1.5 + 2 d, its base d above the cylinder's bottom: the base rim is d from the side
        // and the bottom all along a circle.
        ("nested", _) => {
            let outer = s.build(cylinder(0.6 + d, 1.5 + 2.0 * d)?)?;
            let rel = pose(Vector3::new(0.0, 0.0, d), spin(rng));
            case(&outer, &s.cone, rel, zero())
        }
        // Tangent along a circle, moved d off it. The sphere (radius 0.75) in the ring's
        // hole, its centre d off the ring's axis and at height h above the tube circle's
        // plane with sqrt((0.9 - d)^2 + h^2) = 0.6 + 0.75 + d, above or below: at d = 0 it
        // touches the tube along a circle; d_exact = gap of [`ball_torus_gap`] (= d).
        ("tangent along a circle", "sphere in torus hole (off axis)") => {
            let sign = if rng.next_f64() < 0.5 { -1.0 } else { 1.0 };
            let h = sign * ((1.35 + d).powi(2) - (0.9 - d).powi(2)).sqrt();
            let rot = rng.rotation();
            sphere_at(d * horizontal(rng) + Vector3::new(0.0, 0.0, 0.6 + h), rot)
        }
        // The ring (tube circle radius 0.9 at local height 0.6, tube radius 0.6) coaxial with
        // the cone, resting on its slant. Coaxial solids are closest in a common meridian
        // half-plane (|p - q|^2 >= (rho_p - rho_q)^2 + (z_p - z_q)^2, equality at equal
        // azimuth), so d = dist((0.9, zc), slant line) - 0.6, the slant through (0.6, 0) and
        // (0, 1.5): dist = |(-0.6, 1.5) x (0.3, zc)| / |(-0.6, 1.5)| = (0.6 zc + 0.45) /
        // sqrt(2.61). Its foot (0.9, zc) - dist n, n = (1.5, 0.6) / sqrt(2.61), lies inside
        // the slant for every d <= 0.1, and the base disk (z = 0) and rim are farther.
        ("tangent along a circle", "ring around cone") => {
            let zc = ((0.6 + d) * 2.61f64.sqrt() - 0.45) / 0.6;
            let rel = pose(Vector3::new(0.0, 0.0, zc - 0.6), spin(rng));
            let zc = float(&ExactPose::of(&rel).place([0.0, 0.0, 0.6])[2]);
            let (rim, apex) = ((0.6, 0.0), (0.0, 1.5));
            let (dx, dz) = (
                float(&exact(apex.0)) - float(&exact(rim.0)),
                float(&exact(apex.1)) - float(&exact(rim.1)),
            );
            let (px, pz) = (float(&exact(0.9)) - float(&exact(rim.0)), zc);
            let cross = Float::with_val(PREC, &dx * &pz - &dz * &px).abs();
            let dist = cross / hypot(&dx, &dz);
            case(&s.cone, &s.ring, rel, dist - float(&exact(0.6)))
        }
        // A ring of tube radius 0.3 coaxial and coplanar with the ring (0.9, 0.6), its tube
        // circle radius 1.8 + d: the inner equator (radius 1.8 + d - 0.3) faces the outer
        // equator (0.9 + 0.6) all along a circle: d = (R_b - 0.3) - (0.9 + 0.6).
        ("tangent along a circle", _) => {
            let big_r = 1.8 + d;
            let outer = s.build(ring(big_r, 0.3, 0.6)?)?;
            let rel = pose(Vector3::zeros(), spin(rng));
            let gap = (float(&exact(big_r)) - float(&exact(0.3)))
                - (float(&exact(0.9)) + float(&exact(0.6)));
            case(&s.ring, &outer, rel, gap)
        }
        _ => return Err(format!("unknown solid family {family} / {variant}").into()),
    })
}
