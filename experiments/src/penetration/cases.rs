//! The seeded cases: B placed at the touching length and pushed in, answered by revdist (both
//! timings) and, for the convex pairs, by coal's EPA.

use super::row::{Class, Row};
use super::{LEVELS, SHALLOW};
use crate::peers::coal::CoalPeer;
use crate::peers::convex::{primitive, CONVEX_MODELS};
use crate::shapes::{diagonal, profile, PAPER_MODELS};
use nalgebra::{Isometry3, UnitQuaternion};
use revdist::query::{distance, signed_distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::sync::Arc;
use verify::penetration::{ball_profile, pose_along, touching_length};
use verify::timing::thread_cpu_us;

/// A solid of the experiment: its name, solid at one eps and size.
struct Named {
    name: String,
    solid: Solid,
    size: f64,
}

fn model(name: &str, eps: f64) -> Result<Named, Box<dyn std::error::Error>> {
    let p = profile(name)?;
    let size = diagonal(&p);
    Ok(Named {
        name: name.to_owned(),
        solid: Solid::from_profile(Arc::new(p), eps)?,
        size,
    })
}

/// Places B against A (random rotation and direction), pushed in by `level * size`, and
/// answers the depth and the two timings.
fn case(a: &Named, b: &Named, class: Class, eps: f64, level: f64, rng: &mut SplitMix64) -> Row {
    let q = rng.quaternion();
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
    let u = rng.direction();
    let size = a.size.min(b.size);
    let push = level * size;
    let touch = touching_length(&a.solid, &b.solid, rot, &u);
    let pose = pose_along(&a.solid, &b.solid, rot, &u, touch - push);
    let bp = b.solid.with_pose(pose);
    let opts = QueryOptions::default();
    let t0 = thread_cpu_us();
    let s = signed_distance(&a.solid, &bp, &opts).expect("poses in range");
    let signed_us = thread_cpu_us() - t0;
    let t0 = thread_cpu_us();
    let d = distance(&a.solid, &bp, &opts);
    let distance_us = thread_cpu_us() - t0;
    std::hint::black_box(&d);
    let (lower, upper, queries, probes) = match &s.penetration {
        Some(p) => (p.lower, p.upper, p.stats.distance_queries, p.stats.probes),
        None => (f64::NAN, f64::NAN, 1, 0),
    };
    let cover_cells = s.penetration.as_ref().map_or(0, |p| p.stats.cover_cells);
    let certificate = s.penetration.as_ref().map(|p| p.certificate);
    let (direction, point) = s
        .penetration
        .as_ref()
        .map_or((nalgebra::Vector3::zeros(), None), |p| {
            (p.direction, p.point)
        });
    let class = match class {
        Class::Shallow | Class::Deep if level <= SHALLOW => Class::Shallow,
        Class::Shallow | Class::Deep => Class::Deep,
        c => c,
    };
    Row {
        pair: format!("{}-{}", a.name, b.name),
        class,
        eps,
        level,
        push,
        size,
        pose,
        lower,
        upper,
        queries,
        probes,
        cover_cells,
        certificate,
        signed_us,
        distance_us,
        direction,
        point,
        coal_depth: None,
        coal_us: None,
        coal_verdict: None,
    }
}

/// The seed of one group of cases.
fn group_rng(seed: u64, parts: &[u64]) -> SplitMix64 {
    let mut h = seed ^ 0x5EED_DE97;
    for p in parts {
        h = (h ^ p).wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(29);
    }
    SplitMix64(h)
}

/// The paper's pairs and the balls against each paper model.
pub(super) fn model_cases(
    eps_list: &[f64],
    poses: usize,
    seed: u64,
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    for (ie, &eps) in eps_list.iter().enumerate() {
        let models: Vec<Named> = PAPER_MODELS
            .iter()
            .map(|m| model(m, eps))
            .collect::<Result<_, _>>()?;
        for (i, a) in models.iter().enumerate() {
            for (j, b) in models.iter().enumerate().skip(i) {
                for (il, &level) in LEVELS.iter().enumerate() {
                    let mut rng = group_rng(seed, &[ie as u64, i as u64, j as u64, il as u64]);
                    for _ in 0..poses {
                        rows.push(case(a, b, Class::Deep, eps, level, &mut rng));
                    }
                }
            }
            for (il, &level) in LEVELS.iter().enumerate() {
                let mut rng = group_rng(seed, &[ie as u64, i as u64, 99, il as u64]);
                for _ in 0..poses {
                    let r = rng.range(0.05, 0.3) * a.size;
                    let ball = Named {
                        name: format!("ball{r:.3}"),
                        solid: Solid::from_profile(Arc::new(ball_profile(r)), eps)?,
                        size: 2.0 * r,
                    };
                    rows.push(case(a, &ball, Class::Ball, eps, level, &mut rng));
                }
            }
        }
        eprintln!(
            "penetration: eps {eps:e} done ({} cases so far)",
            rows.len()
        );
    }
    Ok(rows)
}

/// The convex pairs, answered by revdist and by coal's EPA on the same exact solids.
pub(super) fn coal_cases(
    coal: &mut CoalPeer,
    eps_list: &[f64],
    poses: usize,
    seed: u64,
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    let mut index = Vec::new();
    for name in CONVEX_MODELS {
        coal.primitive(name, &primitive(name).expect("convex model"))?;
        index.push(verify::oracle::index(&profile(name)?));
    }
    let mut rows = Vec::new();
    for (ie, &eps) in eps_list.iter().enumerate() {
        let models: Vec<Named> = CONVEX_MODELS
            .iter()
            .map(|m| model(m, eps))
            .collect::<Result<_, _>>()?;
        for (i, a) in models.iter().enumerate() {
            for (j, b) in models.iter().enumerate().skip(i) {
                let mut rng = group_rng(seed, &[ie as u64, i as u64, j as u64, 77]);
                let mut group: Vec<Row> = (0..poses)
                    .map(|_| {
                        let level = rng.log_range(1e-3, 0.3);
                        case(a, b, Class::Convex, eps, level, &mut rng)
                    })
                    .collect();
                let pose_list: Vec<Isometry3<f64>> = group.iter().map(|r| r.pose).collect();
                let answers = coal.signed_query(&a.name, &b.name, &pose_list)?;
                for (r, c) in group.iter_mut().zip(answers) {
                    r.coal_depth = Some((-c.distance).max(0.0));
                    r.coal_us = Some(c.us);
                    r.coal_verdict = r.judge_coal(&index[i], &index[j]);
                }
                rows.extend(group);
            }
        }
    }
    Ok(rows)
}
