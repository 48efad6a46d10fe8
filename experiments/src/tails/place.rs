//! Placement of a drawn query: its models and B's pose, per configuration kind, redrawn until
//! the slide reaches the gap.

use super::nesting::Nest;
use super::query::{Kind, Placed, Spec};
use super::slide::{extent, flip, on_axis, slide, z_range};
use super::{CUPS, CUP_GAPS, CUP_GUESTS, GAPS, MAX_DRAWS, OFFSETS};
use crate::poses::log_uniform;
use crate::{Draw, SplitMix};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::Arc;

/// What placement needs.
pub(super) struct Ctx<'a> {
    pub(super) models: &'a [String],
    pub(super) profiles: &'a HashMap<String, Arc<Profile>>,
    pub(super) fine: &'a HashMap<String, Solid>,
    /// (outer, inner, inner upside down, the inner's centred axis offset, clearance).
    pub(super) nests: &'a [Nest],
}

impl Ctx<'_> {
    fn pick<'m>(&self, rng: &mut SplitMix, from: &'m [String]) -> &'m String {
        &from[((rng.next_f64() * from.len() as f64) as usize).min(from.len() - 1)]
    }

    pub(super) fn place(&self, spec: Spec) -> Result<Placed, String> {
        let mut rng = SplitMix(spec.seed);
        for _ in 0..MAX_DRAWS {
            if let Some(p) = self.try_place(&spec, &mut rng) {
                return Ok(p);
            }
        }
        Err(format!(
            "query {} ({}): no placement in {MAX_DRAWS} draws",
            spec.index,
            spec.kind.name()
        ))
    }

    /// One draw of a query's models and pose; `None` when the placement missed.
    fn try_place(&self, spec: &Spec, rng: &mut SplitMix) -> Option<Placed> {
        let placed = |a: &str, b: &str, gap: f64, pose: Isometry3<f64>| {
            let t = pose.translation.vector;
            let q = pose.rotation.quaternion();
            Placed {
                spec: spec.clone(),
                a: a.to_owned(),
                b: b.to_owned(),
                gap,
                translation: [t.x, t.y, t.z],
                rotation: [q.w, q.i, q.j, q.k],
            }
        };
        match spec.kind {
            Kind::Random => {
                let (a, b) = (self.pick(rng, self.models), self.pick(rng, self.models));
                let gap = log_uniform(rng, GAPS.0, GAPS.1);
                let rot = rng.rotation();
                let dir = rng.unit_vector();
                let (pa, pb) = (&self.profiles[a], &self.profiles[b]);
                let (a0, a1, ra) = extent(pa);
                let (b0, b1, rb) = extent(pb);
                let (ca, cb) = (0.5 * (a0 + a1), 0.5 * (b0 + b1));
                let reach = ra.hypot(0.5 * (a1 - a0)) + rb.hypot(0.5 * (b1 - b0));
                let at = |s: f64| {
                    let t = Vector3::new(0.0, 0.0, ca) + dir * s - rot * Vector3::new(0.0, 0.0, cb);
                    Isometry3::from_parts(Translation3::from(t), rot)
                };
                let far = reach + 2.0 * gap + 1.0;
                let pose = slide(&self.fine[a], &self.fine[b], at, (far, 0.0), gap)?;
                Some(placed(a, b, gap, pose))
            }
            Kind::Coaxial | Kind::Flipped | Kind::CupRest => {
                let (a, b, flipped, gap) = if spec.kind == Kind::CupRest {
                    let cups: Vec<String> = CUPS.iter().map(|s| s.to_string()).collect();
                    let guests: Vec<String> = CUP_GUESTS.iter().map(|s| s.to_string()).collect();
                    let a = self.pick(rng, &cups).clone();
                    let b = self.pick(rng, &guests).clone();
                    let flipped = rng.next_f64() < 0.5;
                    (a, b, flipped, log_uniform(rng, CUP_GAPS.0, CUP_GAPS.1))
                } else {
                    let a = self.pick(rng, self.models).clone();
                    let b = self.pick(rng, self.models).clone();
                    let gap = log_uniform(rng, GAPS.0, GAPS.1);
                    (a, b, spec.kind == Kind::Flipped, gap)
                };
                let (_, a1, _) = extent(&self.profiles[&a]);
                let (a0, _, _) = extent(&self.profiles[&a]);
                let (b0, b1) = z_range(&self.profiles[&b], flipped);
                let rot = if flipped {
                    flip()
                } else {
                    UnitQuaternion::identity()
                };
                // From B's bottom above A's top by gap + 1 down to B's top at A's bottom.
                let s_far = a1 - b0 + 2.0 * gap + 1.0;
                let s_through = a0 - b1;
                let pose = slide(
                    &self.fine[&a],
                    &self.fine[&b],
                    on_axis(rot),
                    (s_far, s_through),
                    gap,
                )?;
                Some(placed(&a, &b, gap, pose))
            }
            Kind::Identical => {
                let a = self.pick(rng, self.models).clone();
                let offset = log_uniform(rng, OFFSETS.0, OFFSETS.1);
                let dir = rng.unit_vector();
                let turn = UnitQuaternion::from_axis_angle(
                    &Vector3::z_axis(),
                    std::f64::consts::PI * (2.0 * rng.next_f64() - 1.0),
                );
                let pose = Isometry3::from_parts(Translation3::from(dir * offset), turn);
                Some(placed(&a, &a, offset, pose))
            }
            Kind::Nested => {
                if self.nests.is_empty() {
                    return None;
                }
                let nest = &self.nests[((rng.next_f64() * self.nests.len() as f64) as usize)
                    .min(self.nests.len() - 1)];
                let gap = log_uniform(rng, GAPS.0, 0.5 * nest.clearance);
                let rot = if nest.flipped {
                    flip()
                } else {
                    UnitQuaternion::identity()
                };
                // From the centred offset upwards (or downwards) until the surfaces are at gap.
                let up = rng.next_f64() < 0.5;
                let (o0, o1, _) = extent(&self.profiles[&nest.outer]);
                let span = o1 - o0;
                let end = if up { nest.z + span } else { nest.z - span };
                let pose = slide(
                    &self.fine[&nest.outer],
                    &self.fine[&nest.inner],
                    on_axis(rot),
                    (nest.z, end),
                    gap,
                )?;
                Some(placed(&nest.outer, &nest.inner, gap, pose))
            }
        }
    }
}
