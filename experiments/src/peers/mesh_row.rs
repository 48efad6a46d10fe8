//! One row of the mesh table: revdist and every mesh peer (FCL, coal, parry3d) on the same
//! certified meshes and poses, timed and cross-checked.

use super::coal::CoalPeer;
use super::parry::{self, ParryShape};
use super::rows::{Row, Timed};
use super::{agrees, Res};
use crate::baseline_mesh::certified_mesh;
use crate::shapes::{diagonal, query_tree_bytes, timed_pair};
use crate::stats::{median, time_each, us};
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::{distance, Distance, QueryOptions};
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::{Bv, FclMesh};
use verify::baselines::TriMesh;

/// One row of the mesh table.
pub(super) fn mesh_row(
    pair: &str,
    (pa, pb): (&Arc<Profile>, &Arc<Profile>),
    eps: f64,
    poses: &[Isometry3<f64>],
    (parry_poses, parry_budget): (usize, Option<f64>),
    coal: &mut Result<CoalPeer, String>,
) -> Res<Row> {
    let same = pa.name() == pb.name();
    let size = diagonal(pa) + diagonal(pb);
    // revdist.
    let (sa, sb, rev_build_ms) = timed_pair(pa, pb, eps)?;
    let rev_bytes = query_tree_bytes(&sa.tree) + if same { 0 } else { query_tree_bytes(&sb.tree) };
    // The certified meshes every mesh peer gets (balanced layout).
    let (ma, ta) = certified_mesh(pa, eps, None)?;
    let (mb, tb) = if same {
        (ma.clone(), ta)
    } else {
        certified_mesh(pb, eps, None)?
    };
    let mesh_ms = (ta + if same { std::time::Duration::ZERO } else { tb }).as_secs_f64() * 1e3;
    let h_sum = ma.bound + mb.bound;
    let tris = ma.mesh.triangle_count() + mb.mesh.triangle_count();
    let opts = QueryOptions::default();
    let answers: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &opts))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |b| {
        std::hint::black_box(distance(&sa, &b, &opts));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev = Timed {
        us: median(&times),
        build_ms: rev_build_ms,
        bytes: rev_bytes,
    };
    let max_width = answers
        .iter()
        .map(|d| d.upper - d.lower)
        .fold(0.0, f64::max);
    let mut violations = 0;
    let mut check = |name: &str, i: usize, d: f64| {
        if !agrees(&answers[i], d, h_sum, &poses[i], size) {
            violations += 1;
            eprintln!(
                "VIOLATION {pair} eps {eps:e} pose {i}: {name} {d:e} outside revdist [{:e}, \
                 {:e}] widened by h_a + h_b = {h_sum:e}",
                answers[i].lower, answers[i].upper
            );
        }
    };
    // FCL, both BVs (mesh time counted in each build).
    let id = Isometry3::identity();
    let mut fcl = Vec::new();
    for bv in [Bv::Obbrss, Bv::Rss] {
        let fa = FclMesh::new(
            &TriMesh::from_points(&ma.mesh.vertices, &ma.mesh.triangles),
            bv,
        )?;
        let fb = if same {
            None
        } else {
            Some(FclMesh::new(
                &TriMesh::from_points(&mb.mesh.vertices, &mb.mesh.triangles),
                bv,
            )?)
        };
        let fbr = fb.as_ref().unwrap_or(&fa);
        for (i, p) in poses.iter().enumerate() {
            check(
                if bv == Bv::Obbrss {
                    "FCL OBBRSS"
                } else {
                    "FCL RSS"
                },
                i,
                fa.distance(fbr, &id, p)?.distance,
            );
        }
        let times = time_each(poses, |p| {
            std::hint::black_box(fa.distance(fbr, &id, p)?);
            Ok::<(), Box<dyn std::error::Error>>(())
        })?;
        let build = fa.build_time()
            + fb.as_ref()
                .map_or(std::time::Duration::ZERO, |f| f.build_time());
        fcl.push(Timed {
            us: median(&times),
            build_ms: mesh_ms + build.as_secs_f64() * 1e3,
            bytes: fa.bytes() + fb.as_ref().map_or(0, |f| f.bytes()),
        });
    }
    // coal, in its own process.
    let coal_timed = match coal {
        Ok(peer) => {
            let ba = peer.mesh("A", &ma)?;
            let bb = if same {
                Default::default()
            } else {
                peer.mesh("B", &mb)?
            };
            let answers_c = peer.query("A", if same { "A" } else { "B" }, poses)?;
            for (i, a) in answers_c.iter().enumerate() {
                check("coal OBBRSS", i, a.distance);
            }
            let times: Vec<f64> = answers_c.iter().map(|a| a.us).collect();
            Ok(Timed {
                us: median(&times),
                build_ms: mesh_ms + ba.build_ms + bb.build_ms,
                bytes: ba.bytes + bb.bytes,
            })
        }
        Err(e) => Err(e.clone()),
    };
    // parry3d, on the first poses only.
    let qa = ParryShape::mesh(&ma)?;
    let qb = if same {
        None
    } else {
        Some(ParryShape::mesh(&mb)?)
    };
    let qbr = qb.as_ref().unwrap_or(&qa);
    let parry_pose: Vec<_> = poses[..parry_poses.min(poses.len())]
        .iter()
        .map(parry::pose)
        .collect();
    let mut parry_d = Vec::with_capacity(parry_pose.len());
    let mut times = Vec::with_capacity(parry_pose.len());
    for p in &parry_pose {
        let t = Instant::now();
        parry_d.push(qa.distance(qbr, p)?);
        times.push(us(t.elapsed()));
        if parry_budget.is_some_and(|b| times.iter().sum::<f64>() > b * 1e6) {
            break;
        }
    }
    let pp = &poses[..times.len()];
    for (i, d) in parry_d.iter().enumerate() {
        check("parry3d", i, *d);
    }
    let parry_t = Timed {
        us: median(&times),
        build_ms: mesh_ms
            + (qa.build + qb.as_ref().map_or(std::time::Duration::ZERO, |q| q.build)).as_secs_f64()
                * 1e3,
        bytes: qa.bytes + qb.as_ref().map_or(0, |q| q.bytes),
    };
    Ok(Row {
        pair: pair.to_owned(),
        eps,
        poses: poses.len(),
        parry_poses: pp.len(),
        tris,
        h_sum,
        rev,
        fcl_obbrss: fcl[0],
        fcl_rss: fcl[1],
        coal: coal_timed,
        parry: parry_t,
        occt_us: None,
        max_width,
        violations,
    })
}
