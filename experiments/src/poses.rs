//! Seeded poses of solid B near solid A at a chosen gap, for timing queries near contact
//! (the regime where a distance query does real work).

use crate::shapes::centre;
use crate::Draw;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::sync::Arc;

/// Bisection steps when sliding B towards A to reach the requested gap: the slide range
/// halves each step, so 60 steps reach double precision on any range below 1e15.
const PLACEMENT_STEPS: usize = 60;

/// Relative accuracy at which a placed gap is accepted.
const GAP_ACCEPT_REL: f64 = 0.05;

/// A pose of `b` (relative to `a`, which sits at the identity) with a random rotation and a
/// random approach direction, slid along that direction until the certified distance is
/// within `GAP_ACCEPT_REL` of `gap` (the query's own value is used to place it; timing
/// does not depend on how exactly the gap is hit). `centres` are the mid-height axis points
/// `z` of both solids; `reach` bounds the sum of both solids' radii about them.
pub fn pose_at_gap(
    a: &Solid,
    b: &Solid,
    centres: (f64, f64),
    reach: f64,
    gap: f64,
    rng: &mut SplitMix64,
) -> Option<Isometry3<f64>> {
    let rot = rng.rotation();
    let dir = rng.unit_vector();
    slide_to_gap(a, b, centres, reach, &dir, &rot, gap)
}

/// The pose of `b` with rotation `rot` whose axis point `centres.1` lies on the ray from
/// `a`'s axis point `centres.0` along the unit vector `dir`, slid along the ray until the
/// certified distance is within `GAP_ACCEPT_REL` of `gap`; `None` when no slide reaches it.
pub fn slide_to_gap(
    a: &Solid,
    b: &Solid,
    centres: (f64, f64),
    reach: f64,
    dir: &Vector3<f64>,
    rot: &UnitQuaternion<f64>,
    gap: f64,
) -> Option<Isometry3<f64>> {
    let at = |s: f64| {
        let t =
            Vector3::new(0.0, 0.0, centres.0) + dir * s - rot * Vector3::new(0.0, 0.0, centres.1);
        Isometry3::from_parts(Translation3::from(t), *rot)
    };
    let opts = QueryOptions::default();
    let gap_of = |s: f64| {
        let d = distance(a, &b.with_pose(at(s)), &opts);
        if d.overlap {
            -1.0
        } else {
            d.value
        }
    };
    // Distance is 0 (or overlap) at s = 0 only if the axis points overlap; search from the
    // far side, where the solids are certainly apart.
    let (mut lo, mut hi) = (0.0, reach + 2.0 * gap + 1.0);
    if gap_of(hi) < gap {
        return None;
    }
    for _ in 0..PLACEMENT_STEPS {
        let mid = 0.5 * (lo + hi);
        let g = gap_of(mid);
        if (g - gap).abs() <= GAP_ACCEPT_REL * gap {
            return Some(at(mid));
        }
        if g < gap {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

/// A seeded smooth random rigid motion of B about A for continuous-motion experiments
/// (the paper's Figure 12): at time `u` in [0, 1] the rotation and the approach direction
/// move through `keys` random keyframes (spherical interpolation with smootherstep easing,
/// so both are C1 in time and pause briefly at each keyframe), and the target gap follows a
/// log-sinusoid between `gaps` with a random phase: the pair is often close, never touching.
pub struct SmoothMotion {
    rotations: Vec<UnitQuaternion<f64>>,
    directions: Vec<Vector3<f64>>,
    gaps: (f64, f64),
    phase: f64,
    periods: f64,
}

impl SmoothMotion {
    /// A motion through `keys` (>= 2) keyframes with `periods` gap oscillations.
    pub fn new(seed: u64, keys: usize, gaps: (f64, f64), periods: f64) -> Self {
        let mut rng = SplitMix64(seed);
        let keys = keys.max(2);
        let rotations = (0..keys).map(|_| rng.rotation()).collect();
        let directions = (0..keys).map(|_| rng.unit_vector()).collect();
        let phase = rng.next_f64() * std::f64::consts::TAU;
        SmoothMotion {
            rotations,
            directions,
            gaps,
            phase,
            periods,
        }
    }

    /// Keyframe index and eased blend parameter at time `u`.
    fn segment(&self, u: f64) -> (usize, f64) {
        let x = u.clamp(0.0, 1.0) * (self.rotations.len() - 1) as f64;
        let k = (x.floor() as usize).min(self.rotations.len() - 2);
        let s = x - k as f64;
        (k, s * s * s * (s * (6.0 * s - 15.0) + 10.0))
    }

    /// Rotation, approach direction and target gap at time `u` in [0, 1].
    pub fn at(&self, u: f64) -> (UnitQuaternion<f64>, Vector3<f64>, f64) {
        let (k, s) = self.segment(u);
        let rot = self.rotations[k]
            .try_slerp(&self.rotations[k + 1], s, 1e-12)
            .unwrap_or(self.rotations[k]);
        let (d0, d1) = (self.directions[k], self.directions[k + 1]);
        // Directions: slerp on the sphere; for (nearly) antipodal keyframes, where slerp is
        // undefined, a normalised lerp, or the first keyframe at the exact midpoint.
        let dir = nalgebra::Unit::new_normalize(d0)
            .try_slerp(&nalgebra::Unit::new_normalize(d1), s, 1e-9)
            .map(|u| u.into_inner())
            .unwrap_or_else(|| {
                let m = d0 * (1.0 - s) + d1 * s;
                if m.norm() > 1e-6 {
                    m.normalize()
                } else {
                    d0
                }
            });
        let w = 0.5 + 0.5 * (self.phase + std::f64::consts::TAU * self.periods * u).sin();
        let gap = (self.gaps.0.ln() + (self.gaps.1.ln() - self.gaps.0.ln()) * w).exp();
        (rot, dir, gap)
    }

    /// `frames` poses of `b` about `a` along the motion (trees of placement accuracy), each
    /// slid to its target gap; frames whose slide fails reuse the previous pose.
    pub fn poses(
        &self,
        pa: &Arc<Profile>,
        pb: &Arc<Profile>,
        frames: usize,
        mut on_frame: impl FnMut(),
    ) -> Result<Vec<Isometry3<f64>>, Box<dyn std::error::Error>> {
        let ((za, ra), (zb, rb)) = (centre(pa), centre(pb));
        let place_a = Solid::from_profile(Arc::clone(pa), PLACEMENT_EPS)?;
        let place_b = Solid::from_profile(Arc::clone(pb), PLACEMENT_EPS)?;
        let mut out: Vec<Isometry3<f64>> = Vec::with_capacity(frames);
        for k in 0..frames {
            let u = k as f64 / (frames.max(2) - 1) as f64;
            let (rot, dir, gap) = self.at(u);
            match slide_to_gap(&place_a, &place_b, (za, zb), ra + rb, &dir, &rot, gap) {
                Some(p) => out.push(p),
                None => match out.last() {
                    Some(&p) => out.push(p),
                    None => {
                        return Err(format!(
                            "motion of {} about {}: first frame could not be placed",
                            pb.name(),
                            pa.name()
                        )
                        .into())
                    }
                },
            }
            on_frame();
        }
        Ok(out)
    }
}

/// Log-uniform gap in `[lo, hi]`.
pub fn log_uniform(rng: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    rng.log_range(lo, hi)
}

/// Gap range of the close poses (log-uniform; `docs/protocols.md`).
pub const CLOSE_GAPS: (f64, f64) = (1e-3, 1e-1);

/// Eps of the trees that place the close poses: far below the smallest gap, so the placed gaps
/// are within a few percent of the drawn ones whatever eps the timed solids use.
pub const PLACEMENT_EPS: f64 = 1e-6;

/// Seed of the close-pose sequences of the FCL comparisons (`fcl_bench`, `pareto`): both
/// time the same poses of a pair.
pub const CLOSE_SEED: u64 = 0x12_2026;

/// Draws per pose before [`close_poses`] gives up (a draw fails only when the bisection does
/// not reach the gap, which is rare).
const MAX_DRAWS_PER_POSE: usize = 100;

/// The seed of the pose sequence of the pair named `pair` (e.g. `pawn-cup`): `seed` xor a
/// hash of the name, so every pair has its own sequence and every run the same ones.
pub fn pair_seed(seed: u64, pair: &str) -> u64 {
    seed ^ pair
        .bytes()
        .fold(0u64, |h, c| h.wrapping_mul(31) ^ u64::from(c))
}

/// `n` seeded poses of the solid of `pb` near the solid of `pa` (at the identity), gaps drawn
/// log-uniform in `gaps`, placed by [`pose_at_gap`] with trees of [`PLACEMENT_EPS`]. The same
/// `seed` gives the same poses, and a shorter `n` a prefix of a longer one. `on_pose` is
/// called after each pose is placed (for a progress bar).
pub fn close_poses(
    pa: &Arc<Profile>,
    pb: &Arc<Profile>,
    n: usize,
    gaps: (f64, f64),
    seed: u64,
    mut on_pose: impl FnMut(),
) -> Result<Vec<Isometry3<f64>>, Box<dyn std::error::Error>> {
    let ((za, ra), (zb, rb)) = (centre(pa), centre(pb));
    let place_a = Solid::from_profile(Arc::clone(pa), PLACEMENT_EPS)?;
    let place_b = Solid::from_profile(Arc::clone(pb), PLACEMENT_EPS)?;
    let mut rng = SplitMix64(seed);
    let mut poses = Vec::with_capacity(n);
    let mut draws = 0;
    while poses.len() < n {
        draws += 1;
        if draws > MAX_DRAWS_PER_POSE * n {
            return Err(format!(
                "placed only {} of {n} poses of {} near {} in {draws} draws",
                poses.len(),
                pb.name(),
                pa.name()
            )
            .into());
        }
        let gap = log_uniform(&mut rng, gaps.0, gaps.1);
        if let Some(p) = pose_at_gap(&place_a, &place_b, (za, zb), ra + rb, gap, &mut rng) {
            poses.push(p);
            on_pose();
        }
    }
    Ok(poses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_motion_is_continuous_and_keeps_its_gap_range() {
        let m = SmoothMotion::new(7, 6, (1e-3, 0.3), 3.0);
        let n = 2000;
        let mut last = m.at(0.0);
        for k in 1..=n {
            let u = k as f64 / n as f64;
            let now = m.at(u);
            // Per step of 1/2000 the rotation turns by well under a degree, the direction
            // moves by well under 1e-2 and the gap changes by a few percent at most.
            assert!(now.0.angle_to(&last.0) < 0.02, "rotation jump at u = {u}");
            assert!((now.1 - last.1).norm() < 0.02, "direction jump at u = {u}");
            assert!((now.1.norm() - 1.0).abs() < 1e-12);
            assert!((1e-3 * (1.0 - 1e-12)..=0.3 * (1.0 + 1e-12)).contains(&now.2));
            assert!((now.2 / last.2).ln().abs() < 0.05, "gap jump at u = {u}");
            last = now;
        }
    }

    #[test]
    fn placed_motion_frames_are_separated_and_refine_continuously() {
        let p = Arc::new(revdist::models::model("pawn").unwrap());
        let q = Arc::new(revdist::models::model("cup").unwrap());
        let m = SmoothMotion::new(3, 3, (1e-2, 0.2), 1.0);
        let a = Solid::from_profile(Arc::clone(&p), 1e-4).unwrap();
        let b = Solid::from_profile(Arc::clone(&q), 1e-4).unwrap();
        let mut max_steps = Vec::new();
        for frames in [20, 40] {
            let poses = m.poses(&p, &q, frames, || {}).unwrap();
            let mut max_step = 0.0f64;
            for (k, pose) in poses.iter().enumerate() {
                let d = distance(&a, &b.with_pose(*pose), &QueryOptions::default());
                assert!(!d.overlap && d.lower > 0.0, "frame {k} touches: {d:?}");
                if k > 0 {
                    let step = (pose.translation.vector - poses[k - 1].translation.vector).norm();
                    max_step = max_step.max(step);
                }
            }
            max_steps.push(max_step);
        }
        // A continuous motion sampled twice as densely moves about half as far per frame
        // (up to the 5 % placement tolerance of the gap); a jump would not shrink.
        assert!(
            max_steps[1] < 0.7 * max_steps[0],
            "largest step per frame {max_steps:?} does not shrink with the frame rate"
        );
    }
}
