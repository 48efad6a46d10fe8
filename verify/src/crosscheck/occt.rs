//! The OpenCASCADE sweep: revdist's certified interval against OCCT's B-rep distance on the
//! true curved surfaces (`crate::baselines::occt`), over the 15 pairs of the paper models, the
//! 15 pairs of their freeform variants and the M_t frames against each paper model.
//!
//! # Criterion
//!
//! OCCT's distance `d_o` is the distance between two points it evaluated on the surfaces, the
//! minimum over its candidate extrema; we hold it to `|d_o - D_S| <= OCCT_TOLERANCE` (its
//! deflection, see [`crate::baselines::occt`]), `D_S` the surfaces' distance. With
//! `InnerSolution()` (a vertex of one solid inside the other) it answers the solids' 0. So the
//! test is the mesh check's ([`super::criterion::judge`]) with OCCT's tolerance in place of the
//! meshes' bounds: **passed** when `[lower, upper]` meets `[d_o - tol, d_o + tol]` (clipped at 0,
//! plus the rounding slack). **Explained**: revdist certifies that the solids share a point
//! (`lower = 0`, OCCT's point on one surface certified inside the other solid) while OCCT,
//! whose inner-solution test classifies only vertices, reports the surfaces' distance.
//!
//! # Which side is wrong
//!
//! Every other disjoint case is **failed**, and its note says which side the evidence blames,
//! except when the evidence proves OCCT wrong (`occt-missed-minimum`, then **explained**):
//! * revdist *above* OCCT: OCCT's two points are checked against the true profiles by the
//!   oracle's own evaluation (`crate::oracle`); if both lie on their surfaces, `|p_a - p_b|`
//!   bounds the surfaces' distance from above and revdist's lower bound is wrong
//!   (`revdist-lower-wrong`); otherwise OCCT's points are off its surfaces (`occt-points-off`).
//! * revdist *below* OCCT: revdist's witnesses, checked the same way, realise a distance below
//!   OCCT's minus its tolerance, so OCCT missed the minimum (`occt-missed-minimum`, explained:
//!   two points on the true surfaces closer than OCCT's minimum), or the oracle's own search
//!   of the true surfaces realises such a pair (the same label); otherwise the evidence is
//!   `inconclusive` (failed).
//! * OCCT's `InnerSolution()` (distance 0) against revdist's positive lower bound: the vertex
//!   OCCT found inside is classified by the oracle; on one surface and outside the other solid
//!   by more than OCCT's own tolerance 1e-3, it proves OCCT's classifier wrong
//!   (`occt-false-inner`, explained).
//!
//! # Poses
//!
//! [`super::poses::make_pose_in`] with near-touching gaps [`OCCT_NEAR_GAPS`], placed with the
//! trees of the finest eps (a gap of 1e-6 needs trees well below it); one OCCT query per pose,
//! revdist judged at every eps of [`super::Options::occt_eps`].

use super::criterion::{judge, Baseline, Certified, Verdict, SLACK_REL};
use super::options::Options;
use super::poses::{make_pose_in, PoseKind, PoseTarget};
use super::record::{CaseContext, CaseRecord, Check};
use crate::baselines::occt::{thread_cpu_time, OcctSolid, OCCT_TOLERANCE};
use nalgebra::{Isometry3, Point3};
use revdist::bvh::containment::point_in_solid;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Gap range of the OCCT sweep's near-touching poses (`docs/verification.md`, "OpenCASCADE on the true curved surfaces": 1e-2..1e-6).
pub const OCCT_NEAR_GAPS: (f64, f64) = (1e-6, 1e-2);

/// Poses per job (an OCCT query takes 5-20 ms: small blocks balance the threads).
const BLOCK: usize = 10;

/// A point counts as on its true surface when the oracle's distance from it to the profile is
/// at most this, relative to the configuration scale: OCCT evaluates its surfaces in double
/// precision (a few ulps of the coordinates) and revdist's witnesses lie within eps of theirs
/// (added separately).
pub const ON_SURFACE_REL: f64 = 1e-9;

/// The note of a case where OCCT missed the minimum (counted as explained, see the module
/// documentation).
pub const OCCT_MISSED: &str = "occt-missed-minimum";

/// The note of a case where OCCT's inner-solution vertex lies outside the other solid by more
/// than OCCT's classification tolerance (counted as explained).
pub const OCCT_FALSE_INNER: &str = "occt-false-inner";

/// OCCT's tolerance when it classifies a vertex against a solid
/// (`BRepExtrema_DistShapeShape::Perform`, 7.6: `tol = 0.001`).
pub const OCCT_INNER_TOLERANCE: f64 = 1e-3;

/// One model: its profile and a revdist solid per eps of the sweep.
struct Shape {
    name: String,
    profile: Profile,
    /// Same order as `Options::occt_eps`.
    solids: Vec<Solid>,
    /// Index of the finest eps (poses are placed with it).
    finest: usize,
    centre_z: f64,
    radius: f64,
}

impl PoseTarget for Shape {
    fn solid(&self) -> &Solid {
        &self.solids[self.finest]
    }
    fn centre_z(&self) -> f64 {
        self.centre_z
    }
    fn radius(&self) -> f64 {
        self.radius
    }
}

fn shape(name: &str, eps: &[f64]) -> Result<Shape, String> {
    let profile = revdist::models::model(name).map_err(|e| format!("model '{name}': {e}"))?;
    let b = profile.bounding_box();
    let solids = eps
        .iter()
        .map(|&e| {
            Solid::from_profile(Arc::new(profile.clone()), e)
                .map_err(|err| format!("tree of '{name}' at eps {e:e}: {err}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let finest = (0..eps.len())
        .min_by(|&i, &j| eps[i].total_cmp(&eps[j]))
        .ok_or("no eps for the OCCT sweep")?;
    Ok(Shape {
        name: name.to_owned(),
        profile,
        solids,
        finest,
        centre_z: 0.5 * (b.min.y + b.max.y),
        radius: b.max.x.hypot(0.5 * (b.max.y - b.min.y)),
    })
}

/// The jobs of the OCCT sweep of `opts`: (pair, first pose, end of the poses), numbered as
/// listed.
fn job_list(opts: &Options) -> Vec<(usize, usize, usize)> {
    let mut jobs = Vec::new();
    for pair in 0..opts.occt_pairs.len() {
        for start in (0..opts.occt_poses).step_by(BLOCK) {
            jobs.push((pair, start, (start + BLOCK).min(opts.occt_poses)));
        }
    }
    jobs
}

/// How many jobs the OCCT sweep of `opts` has.
pub fn jobs(opts: &Options) -> usize {
    job_list(opts).len()
}

/// Runs the OCCT sweep of `opts` (nothing when `occt_poses` is 0): job `j` is work unit
/// `first_unit + j`, run when `keep` accepts that unit; each record with its unit. Errors:
/// OCCT missing, a model OCCT cannot build, or an OCCT query that fails.
pub fn run(
    opts: &Options,
    threads: usize,
    (first_unit, keep): (usize, &dyn Fn(usize) -> bool),
) -> Result<Vec<(usize, CaseRecord)>, String> {
    let jobs: Vec<(usize, (usize, usize, usize))> = job_list(opts)
        .into_iter()
        .enumerate()
        .map(|(j, job)| (first_unit + j, job))
        .filter(|(u, _)| keep(*u))
        .collect();
    if jobs.is_empty() {
        return Ok(Vec::new());
    }
    crate::baselines::occt::version().map_err(|e| e.to_string())?;
    if opts.occt_eps.is_empty() || opts.occt_eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(format!(
            "OCCT eps must be positive numbers, got {:?}",
            opts.occt_eps
        ));
    }
    let mut shapes: HashMap<String, Arc<Shape>> = HashMap::new();
    for (_, (pair, _, _)) in &jobs {
        let (a, b) = &opts.occt_pairs[*pair];
        for n in [a, b] {
            if !shapes.contains_key(n) {
                shapes.insert(n.clone(), Arc::new(shape(n, &opts.occt_eps)?));
            }
        }
    }
    let next = AtomicUsize::new(0);
    let records = Mutex::new(Vec::new());
    let errors = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..threads.max(1) {
            scope.spawn(|| {
                // OCCT solids are per thread (`OcctSolid` is Send, not Sync).
                let mut solids: HashMap<String, OcctSolid> = HashMap::new();
                loop {
                    let j = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&(unit, (pair, start, end))) = jobs.get(j) else {
                        break;
                    };
                    let (na, nb) = &opts.occt_pairs[pair];
                    let out = occt_job(&shapes[na], &shapes[nb], start..end, opts, &mut solids);
                    match out {
                        Ok(v) => records
                            .lock()
                            .expect("records lock")
                            .extend(v.into_iter().map(|r| (unit, r))),
                        Err(e) => errors.lock().expect("errors lock").push(e),
                    }
                }
            });
        }
    });
    let errors = errors.into_inner().expect("errors lock");
    if !errors.is_empty() {
        return Err(errors.join("\n"));
    }
    Ok(records.into_inner().expect("records lock"))
}

fn occt_solid<'m>(
    cache: &'m mut HashMap<String, OcctSolid>,
    s: &Shape,
) -> Result<&'m OcctSolid, String> {
    if !cache.contains_key(&s.name) {
        let solid = OcctSolid::from_profile(&s.profile).map_err(|e| e.to_string())?;
        cache.insert(s.name.clone(), solid);
    }
    Ok(&cache[&s.name])
}

/// The pose generator of pose `index` of a pair (independent of the job split and of eps).
fn pose_rng(seed: u64, a: &str, b: &str, index: usize) -> SplitMix64 {
    let mut h = SplitMix64(seed ^ 0x0CC7);
    for byte in a.bytes().chain([b'/']).chain(b.bytes()) {
        h = h.fork(u64::from(byte));
    }
    h.fork(index as u64)
}

/// Distance from world point `p` to the true surface of `s` placed by `pose` (the oracle's
/// own profile evaluation, in the meridian half-plane of `p`).
/// Signed distance (negative inside) from world point `p` to the solid of `s` placed by
/// `pose`, by the oracle's winding-number containment and its own profile evaluation.
fn signed(s: &Shape, pose: &Isometry3<f64>, p: &Point3<f64>) -> f64 {
    let l = pose.inverse_transform_point(p);
    crate::oracle::index(&s.profile)
        .signed([l.x.hypot(l.y), l.z])
        .value
}

fn off_surface(s: &Shape, pose: &Isometry3<f64>, p: &Point3<f64>) -> f64 {
    let l = pose.inverse_transform_point(p);
    let q = [l.x.hypot(l.y), l.z];
    crate::oracle::index(&s.profile).closest(q).dist
}

fn occt_job(
    a: &Shape,
    b: &Shape,
    range: std::ops::Range<usize>,
    opts: &Options,
    cache: &mut HashMap<String, OcctSolid>,
) -> Result<Vec<CaseRecord>, String> {
    occt_solid(cache, a)?;
    occt_solid(cache, b)?;
    let (oa, ob) = (&cache[&a.name], &cache[&b.name]);
    let qopts = QueryOptions::default();
    let mut out = Vec::new();
    for index in range {
        let mut rng = pose_rng(opts.seed, &a.name, &b.name, index);
        let kind = PoseKind::of_index(index);
        let pose = make_pose_in(a, b, kind, OCCT_NEAR_GAPS, &mut rng);
        let iso = pose.isometry();
        let o = oa
            .distance(ob, &iso)
            .map_err(|e| format!("OCCT {} / {} pose {index}: {e}", a.name, b.name))?;
        let scale = 1.0 + iso.translation.vector.norm() + a.radius + b.radius;
        let slack = SLACK_REL * scale;
        for (k, &eps) in opts.occt_eps.iter().enumerate() {
            let (sa, sb) = (&a.solids[k], &b.solids[k]);
            let (tq, cq) = (Instant::now(), thread_cpu_time());
            let d = distance(sa, &sb.with_pose(iso), &qopts);
            // The thread's CPU time, like OCCT's (wall-clock only if that clock is missing).
            let query_time = match (cq, thread_cpu_time()) {
                (Some(c0), Some(c1)) => c1.saturating_sub(c0),
                _ => tq.elapsed(),
            };
            let base = Baseline {
                distance: o.distance,
                mesh_bounds: OCCT_TOLERANCE,
                slack,
            };
            let rev = Certified {
                lower: d.lower,
                upper: d.upper,
                overlap: d.overlap,
            };
            let mut nested = false;
            let judgement = judge(rev, d.value, base, || {
                let inside = |s: &Solid, pose: &Isometry3<f64>, p: &Point3<f64>| {
                    let r = point_in_solid(&s.tree, &pose.inverse_transform_point(p));
                    r.inside && r.margin > s.tree.target_eps + OCCT_TOLERANCE + slack
                };
                nested =
                    inside(sa, &Isometry3::identity(), &o.point_b) || inside(sb, &iso, &o.point_a);
                nested
            });
            let mut judgement = judgement;
            let note = if judgement.verdict == Verdict::Failed {
                let note = blame(a, b, &iso, &o, &d, slack);
                if note == OCCT_MISSED || note == OCCT_FALSE_INNER {
                    // revdist's witnesses, on the true surfaces by the oracle's evaluation,
                    // realise a smaller distance: OCCT's answer is not the minimum.
                    judgement.verdict = Verdict::Explained;
                }
                note
            } else if nested {
                "nested (OCCT: surfaces)"
            } else if o.inner {
                "occt-inner-solution"
            } else {
                ""
            };
            let ctx = CaseContext {
                a: &a.name,
                b: &b.name,
                eps,
                index,
                kind,
                pose,
                answer: &d,
                mesh_bounds: OCCT_TOLERANCE,
                query_time,
            };
            let mut r = CaseRecord::new(&ctx, Check::Occt, o.distance, judgement, note);
            r.baseline_time = Some(o.cpu_time);
            out.push(r);
        }
    }
    Ok(out)
}

/// Which side the evidence blames for a failed case (see the module documentation).
fn blame(
    a: &Shape,
    b: &Shape,
    iso: &Isometry3<f64>,
    o: &crate::baselines::occt::OcctDistance,
    d: &revdist::query::Distance,
    slack: f64,
) -> &'static str {
    let on = ON_SURFACE_REL * (1.0 + a.radius + b.radius + iso.translation.vector.norm());
    // A pair of points within `off_a`, `off_b` of the surfaces realises an upper bound
    // |p_a - p_b| + off_a + off_b of the surfaces' distance (and so of the solids').
    let realised = |pa: &Point3<f64>, pb: &Point3<f64>| {
        (pa - pb).norm()
            + off_surface(a, &Isometry3::identity(), pa)
            + off_surface(b, iso, pb)
            + 2.0 * on
    };
    if o.inner && d.lower > 0.0 {
        // The vertex OCCT found inside lies on one solid's surface; the oracle classifies it
        // against both: outside both by more than OCCT's tolerance means OCCT misclassified.
        let p = &o.point_a;
        let outside = signed(a, &Isometry3::identity(), p).max(signed(b, iso, p));
        let own = signed(a, &Isometry3::identity(), p)
            .abs()
            .min(signed(b, iso, p).abs());
        if own <= on && outside > OCCT_INNER_TOLERANCE {
            OCCT_FALSE_INNER
        } else {
            "inconclusive"
        }
    } else if d.lower > o.distance {
        if d.lower > realised(&o.point_a, &o.point_b) + slack {
            "revdist-lower-wrong"
        } else {
            "occt-points-off"
        }
    } else if d.overlap {
        "revdist-overlap-occt-apart"
    } else if realised(&d.point_a, &d.point_b) < o.distance - OCCT_TOLERANCE - slack {
        OCCT_MISSED
    } else {
        // revdist's witnesses lie on its approximating surfaces (within eps of the true ones),
        // too coarse to show a miss just past OCCT's tolerance: the oracle's own search of
        // the true surfaces (`crate::oracle::surface_distance`, a realised pair of points on
        // them) decides. Run only here: rare, and it costs milliseconds.
        let (ia, ib) = (
            crate::oracle::index(&a.profile),
            crate::oracle::index(&b.profile),
        );
        let r =
            crate::oracle::surface_distance(&ia, &ib, iso, &crate::oracle::OracleOptions::full());
        // The oracle's pair is evaluated on the profiles themselves (no projection), so
        // only rounding separates it from the surfaces: the slack, once per point.
        if r.upper + 2.0 * slack < o.distance - OCCT_TOLERANCE - slack {
            OCCT_MISSED
        } else {
            "inconclusive"
        }
    }
}
