//! Random motions for the time-of-impact campaign: head-on, grazing, rotating (B turns
//! about its own origin in place), never touching (B passes outside the bounding spheres)
//! and both moving, with contact distances 0, 0.01 and 0.1.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;

/// The families of motions, in the order the generator cycles through them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    HeadOn,
    Grazing,
    Rotating,
    NeverTouching,
    BothMoving,
}

impl Family {
    pub const ALL: [Family; 5] = [
        Family::HeadOn,
        Family::Grazing,
        Family::Rotating,
        Family::NeverTouching,
        Family::BothMoving,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Family::HeadOn => "head-on",
            Family::Grazing => "grazing",
            Family::Rotating => "rotating",
            Family::NeverTouching => "never-touching",
            Family::BothMoving => "both-moving",
        }
    }
}

/// Where a shape sits in its own frame: the centre and radius of a sphere containing it.
#[derive(Debug, Clone, Copy)]
pub struct Extent {
    pub centre: Point3<f64>,
    pub radius: f64,
}

/// One motion of the campaign: start and end poses of both solids.
#[derive(Debug, Clone)]
pub struct MotionCase {
    pub family: Family,
    pub contact_distance: f64,
    pub a: [Isometry3<f64>; 2],
    pub b: [Isometry3<f64>; 2],
}

fn vec(rng: &mut SplitMix64) -> Vector3<f64> {
    rng.direction()
}

fn rotation(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    let q = rng.quaternion();
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
}

/// A turn by at most `max` radians (kept below pi: at half a turn the shortest arc is not
/// unique).
fn turn(rng: &mut SplitMix64, max: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(vec(rng) * rng.range(0.0, max.min(3.0)))
}

/// The pose with rotation `r` that puts the shape's centre at `c`.
fn centred(e: &Extent, r: UnitQuaternion<f64>, c: Point3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(c - r * e.centre), r)
}

/// A random motion of `family` for shapes of extents `ea`, `eb`.
pub fn random_motion(rng: &mut SplitMix64, family: Family, ea: &Extent, eb: &Extent) -> MotionCase {
    let contact_distance = [0.0, 0.0, 0.01, 0.1][rng.int(0, 3)];
    let reach = ea.radius + eb.radius;
    let a0 = Isometry3::identity();
    let ca = ea.centre;
    let u = vec(rng);
    // A unit vector perpendicular to u.
    let w = u
        .cross(&vec(rng))
        .try_normalize(1e-9)
        .unwrap_or_else(|| u.cross(&Vector3::x()).normalize());
    let r0 = rotation(rng);
    let (a, b) = match family {
        Family::HeadOn => {
            let start = ca + u * (reach + rng.range(0.2, 2.0));
            let end = ca + u * reach * rng.range(-0.3, 0.6);
            let r1 = turn(rng, 0.5) * r0;
            ([a0, a0], [centred(eb, r0, start), centred(eb, r1, end)])
        }
        Family::Grazing => {
            let off = reach * rng.range(0.15, 0.8);
            let len = reach + rng.range(0.5, 1.5);
            let r1 = turn(rng, 0.8) * r0;
            (
                [a0, a0],
                [
                    centred(eb, r0, ca + w * off + u * len),
                    centred(eb, r1, ca + w * off - u * len),
                ],
            )
        }
        Family::Rotating => {
            let c = ca + u * reach * rng.range(0.3, 0.9);
            let r1 = UnitQuaternion::from_scaled_axis(vec(rng) * rng.range(1.0, 3.0)) * r0;
            let p0 = centred(eb, r0, c);
            // Turn about B's frame origin: same translation at both ends.
            ([a0, a0], [p0, Isometry3::from_parts(p0.translation, r1)])
        }
        Family::NeverTouching => {
            let d = reach + contact_distance + rng.range(0.05, 1.0);
            let s = rng.range(0.5, 3.0);
            let r1 = turn(rng, 3.0) * r0;
            (
                [a0, a0],
                [
                    centred(eb, r0, ca + u * d + w * s),
                    centred(eb, r1, ca + u * d - w * s),
                ],
            )
        }
        Family::BothMoving => {
            let a1 = Isometry3::from_parts(
                Translation3::from(vec(rng) * rng.range(0.0, 0.8)),
                turn(rng, 1.5),
            );
            let target = a1 * ca;
            let start = ca + u * (reach + rng.range(0.2, 2.0));
            let end = target + vec(rng) * reach * rng.range(0.0, 0.6);
            let r1 = turn(rng, 1.5) * r0;
            ([a0, a1], [centred(eb, r0, start), centred(eb, r1, end)])
        }
    };
    MotionCase {
        family,
        contact_distance,
        a,
        b,
    }
}
