//! Runs the cross-check: prepares the shapes, spreads (pair, eps, block of poses) jobs over
//! threads, each with its own FCL BVHs (an `FclMesh` is `Send`, not `Sync`).

use super::convex;
use super::criterion::{judge, Baseline, Certified, SLACK_REL};
use super::options::Options;
use super::poses::{make_pose, PoseKind};
use super::record::{CaseContext, CaseRecord, Check};
use super::report::Report;
use super::shapes::{prepare, scale, Prepared};
use crate::baselines::fcl::{Bv, FclMesh};
use nalgebra::{Isometry3, Point3};
use revdist::bvh::containment::point_in_solid;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Poses per job: small enough to balance two threads, large enough to reuse the BVHs.
const BLOCK: usize = 25;

/// One unit of work.
#[derive(Debug, Clone, Copy)]
struct Job {
    convex: bool,
    pair: usize,
    eps: usize,
    start: usize,
    end: usize,
}

type Key = (String, u64);

fn key(name: &str, eps: f64) -> Key {
    (name.to_owned(), eps.to_bits())
}

/// Runs the cross-check.
pub fn run(opts: &Options) -> Result<Report, String> {
    let r = run_units(opts)?;
    Ok(Report::new(
        r.records.into_iter().map(|(_, c)| c).collect(),
        opts.clone(),
        r.threads,
        (r.prepare_time, r.wall),
    ))
}

/// What [`run_units`] computed.
pub struct UnitRecords {
    /// Each record with its job's number (its work unit for `--shard`).
    pub records: Vec<(usize, CaseRecord)>,
    /// Jobs of the whole campaign: the mesh and convex jobs, then the OCCT sweep's.
    pub units: usize,
    pub threads: usize,
    pub prepare_time: Duration,
    pub wall: Duration,
}

/// Runs the jobs of `opts.shard` (every job without one): jobs are numbered as listed (mesh
/// pairs x eps x blocks of poses, then the convex pairs', then the OCCT sweep's), each case
/// seeded by its pair, eps and pose number, so a shard's cases are those of the unsharded run.
pub fn run_units(opts: &Options) -> Result<UnitRecords, String> {
    if opts.eps.is_empty() || opts.eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(format!("eps must be positive numbers, got {:?}", opts.eps));
    }
    if opts.occt_poses > 0 {
        // Before minutes of mesh checks: "OCCT missing: run scripts/deps.sh ...".
        crate::baselines::occt::version().map_err(|e| e.to_string())?;
    }
    let t0 = Instant::now();
    let mut all_jobs = Vec::new();
    for (convex, pairs, n) in [
        (false, &opts.pairs, opts.poses),
        (true, &opts.convex_pairs, opts.convex_poses),
    ] {
        for pair in 0..pairs.len() {
            for eps in 0..opts.eps.len() {
                for start in (0..n).step_by(BLOCK) {
                    all_jobs.push(Job {
                        convex,
                        pair,
                        eps,
                        start,
                        end: (start + BLOCK).min(n),
                    });
                }
            }
        }
    }
    let units = all_jobs.len() + super::occt::jobs(opts);
    let mut keep = vec![opts.shard.is_none(); units];
    for u in opts.shard.map(|s| s.units(units)).unwrap_or_default() {
        keep[u] = true;
    }
    let owns = |u: usize| keep[u];
    let jobs: Vec<(usize, Job)> = all_jobs
        .into_iter()
        .enumerate()
        .filter(|(u, _)| owns(*u))
        .collect();
    // Shapes of the jobs that run, built once and shared read-only by the workers
    // (tessellations are not free).
    let mut prepared: HashMap<Key, Arc<Prepared>> = HashMap::new();
    for (_, job) in &jobs {
        let pairs = if job.convex {
            &opts.convex_pairs
        } else {
            &opts.pairs
        };
        let (a, b) = &pairs[job.pair];
        let eps = opts.eps[job.eps];
        for name in [a, b] {
            if let std::collections::hash_map::Entry::Vacant(e) = prepared.entry(key(name, eps)) {
                e.insert(Arc::new(prepare(name, eps)?));
            }
        }
    }
    let prepare_time = t0.elapsed();

    let threads = if opts.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        opts.threads
    };
    let next = AtomicUsize::new(0);
    let records = Mutex::new(Vec::new());
    let errors = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                let mut bvhs: HashMap<Key, FclMesh> = HashMap::new();
                loop {
                    let j = next.fetch_add(1, Ordering::Relaxed);
                    let Some((unit, job)) = jobs.get(j) else {
                        break;
                    };
                    let pairs = if job.convex {
                        &opts.convex_pairs
                    } else {
                        &opts.pairs
                    };
                    let (na, nb) = &pairs[job.pair];
                    let eps = opts.eps[job.eps];
                    let a = &prepared[&key(na, eps)];
                    let b = &prepared[&key(nb, eps)];
                    let out = if job.convex {
                        convex_job(a, b, job, opts.seed)
                    } else {
                        mesh_job(a, b, job, opts.seed, &mut bvhs)
                    };
                    match out {
                        Ok(v) => records
                            .lock()
                            .expect("records lock")
                            .extend(v.into_iter().map(|r| (*unit, r))),
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
    let mut records = records.into_inner().expect("records lock");
    let first_occt = units - super::occt::jobs(opts);
    records.extend(super::occt::run(opts, threads, (first_occt, &owns))?);
    Ok(UnitRecords {
        records,
        units,
        threads,
        prepare_time,
        wall: t0.elapsed(),
    })
}

/// The pose generator of case `index` of a pair (independent of the job split).
fn case_rng(seed: u64, a: &str, b: &str, eps: f64, index: usize) -> SplitMix64 {
    let mut h = SplitMix64(seed);
    for byte in a.bytes().chain([b'/']).chain(b.bytes()) {
        h = h.fork(u64::from(byte));
    }
    h.fork(eps.to_bits()).fork(index as u64)
}

/// Whether world point `p` certainly lies inside `s`'s solid, `margin` beyond its chain.
fn inside_by(s: &Prepared, pose: &Isometry3<f64>, p: &Point3<f64>, margin: f64) -> bool {
    let local = pose.inverse_transform_point(p);
    let r = point_in_solid(&s.solid.tree, &local);
    r.inside && r.margin > margin
}

fn fcl_mesh<'m>(bvhs: &'m mut HashMap<Key, FclMesh>, s: &Prepared) -> Result<&'m FclMesh, String> {
    let k = key(&s.name, s.eps);
    if !bvhs.contains_key(&k) {
        let m = FclMesh::new(&s.mesh, Bv::Obbrss)
            .map_err(|e| format!("FCL BVH of {} at eps {:e}: {e}", s.name, s.eps))?;
        bvhs.insert(k.clone(), m);
    }
    Ok(&bvhs[&k])
}

fn mesh_job(
    a: &Prepared,
    b: &Prepared,
    job: &Job,
    seed: u64,
    bvhs: &mut HashMap<Key, FclMesh>,
) -> Result<Vec<CaseRecord>, String> {
    fcl_mesh(bvhs, a)?;
    fcl_mesh(bvhs, b)?;
    let (ma, mb) = (&bvhs[&key(&a.name, a.eps)], &bvhs[&key(&b.name, b.eps)]);
    let opts = QueryOptions::default();
    let mut out = Vec::with_capacity(job.end - job.start);
    for index in job.start..job.end {
        let mut rng = case_rng(seed, &a.name, &b.name, a.eps, index);
        let kind = PoseKind::of_index(index);
        let pose = make_pose(a, b, kind, &mut rng);
        let iso = pose.isometry();
        let tq = Instant::now();
        let d = distance(&a.solid, &b.solid.with_pose(iso), &opts);
        let query_time = tq.elapsed();
        let f = ma
            .distance(mb, &Isometry3::identity(), &iso)
            .map_err(|e| format!("FCL {} / {}: {e}", a.name, b.name))?;
        let h = a.bound + b.bound;
        let base = Baseline {
            distance: f.distance,
            mesh_bounds: h,
            slack: SLACK_REL * scale(a, b, &iso),
        };
        let rev = Certified {
            lower: d.lower,
            upper: d.upper,
            overlap: d.overlap,
        };
        let mut nested = false;
        let judgement = judge(rev, d.value, base, || {
            nested = inside_by(
                a,
                &Isometry3::identity(),
                &f.point_b,
                a.solid.tree.target_eps + b.bound,
            ) || inside_by(b, &iso, &f.point_a, b.solid.tree.target_eps + a.bound);
            nested
        });
        let ctx = CaseContext {
            a: &a.name,
            b: &b.name,
            eps: a.eps,
            index,
            kind,
            pose,
            answer: &d,
            mesh_bounds: h,
            query_time,
        };
        let note = if nested { "nested" } else { "" };
        out.push(CaseRecord::new(
            &ctx,
            Check::Fcl,
            f.distance,
            judgement,
            note,
        ));
    }
    Ok(out)
}

fn convex_job(a: &Prepared, b: &Prepared, job: &Job, seed: u64) -> Result<Vec<CaseRecord>, String> {
    let mut out = Vec::new();
    for index in job.start..job.end {
        let mut rng = case_rng(seed ^ 0xC0_4E3, &a.name, &b.name, a.eps, index);
        let kind = PoseKind::of_index(index);
        let pose = make_pose(a, b, kind, &mut rng);
        out.extend(convex::check_case(a, b, index, kind, pose)?);
    }
    Ok(out)
}
