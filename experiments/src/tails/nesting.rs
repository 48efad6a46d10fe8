//! The pairs of built-in models that nest (the `nested` kind draws from them), found at
//! start-up.

use super::slide::{extent, flip, on_axis, surface_gap, z_range};
use super::NEST_SCREEN_EPS;
use nalgebra::UnitQuaternion;
use rayon::prelude::*;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::Arc;

/// A pair of models that nest: `inner` (upside down if `flipped`) inside `outer`, coaxial,
/// at axis offset `z`, with `clearance` between their surfaces.
#[derive(Debug, Clone)]
pub(super) struct Nest {
    pub(super) outer: String,
    pub(super) inner: String,
    pub(super) flipped: bool,
    pub(super) z: f64,
    pub(super) clearance: f64,
}

/// The ordered pairs of distinct models that nest when coaxial and centred at mid-height
/// (either way up): their surfaces are at least `MIN_CLEARANCE` apart (on trees of eps
/// [`NEST_SCREEN_EPS`] first, cheap where the surfaces cross) while the query certifies an
/// overlap.
pub(super) fn nesting_pairs(
    models: &[String],
    profiles: &HashMap<String, Arc<Profile>>,
    fine: &HashMap<String, Solid>,
) -> Vec<Nest> {
    const MIN_CLEARANCE: f64 = 1e-3;
    let coarse: HashMap<&String, Solid> = models
        .iter()
        .filter_map(|m| {
            Solid::from_profile(Arc::clone(&profiles[m]), NEST_SCREEN_EPS)
                .ok()
                .map(|s| (m, s))
        })
        .collect();
    let mut cands = Vec::new();
    for outer in models {
        for inner in models {
            if outer != inner {
                for flipped in [false, true] {
                    cands.push((outer.clone(), inner.clone(), flipped));
                }
            }
        }
    }
    let mut nests: Vec<Nest> = cands
        .into_par_iter()
        .filter_map(|(outer, inner, flipped)| {
            let (o0, o1, ro) = extent(&profiles[&outer]);
            let (i0, i1) = z_range(&profiles[&inner], flipped);
            let (_, _, ri) = extent(&profiles[&inner]);
            if ri >= ro || i1 - i0 >= o1 - o0 {
                return None;
            }
            let z = 0.5 * (o0 + o1) - 0.5 * (i0 + i1);
            let rot = if flipped {
                flip()
            } else {
                UnitQuaternion::identity()
            };
            let pose = on_axis(rot)(z);
            let (co, ci) = (coarse.get(&outer)?, coarse.get(&inner)?);
            if surface_gap(co, ci, &pose, NEST_SCREEN_EPS).0 < MIN_CLEARANCE {
                return None;
            }
            let (so, si) = (&fine[&outer], &fine[&inner]);
            let d = distance(
                so,
                &si.with_pose(pose),
                &QueryOptions {
                    tolerance: Tolerance::Absolute(1e-6),
                    ..QueryOptions::default()
                },
            );
            let (lower, upper) = surface_gap(so, si, &pose, 1e-6);
            (d.overlap && lower >= MIN_CLEARANCE).then_some(Nest {
                outer,
                inner,
                flipped,
                z,
                clearance: 0.5 * (lower + upper),
            })
        })
        .collect();
    nests.sort_by(|x, y| (&x.outer, &x.inner, x.flipped).cmp(&(&y.outer, &y.inner, y.flipped)));
    nests
}
