//! Quick versions of `verify toi` and of FCL's continuous collision through the shim.

use nalgebra::Isometry3;
use revdist::models::model;
use revdist::tessellate::{tessellate, TessellateOptions};
use verify::baselines::fcl::{Bv, CcdSolver, FclMesh};
use verify::baselines::TriMesh;
use verify::toi::check::{Decided, Scene};
use verify::toi::{run, Options};

#[test]
fn quick_campaign_has_no_violations() {
    let opts = Options {
        count: 15,
        seed: 7,
        eps: vec![1e-3],
        shard: None,
        threads: 2,
    };
    let r = run(&opts).unwrap();
    assert_eq!(r.cases, 15);
    assert!(r.failures.is_empty(), "{}", r.summary());
}

/// The oracle's check can fail: two balls (radius 0.75) meeting head-on at t = 0.5 are
/// not apart before t_lower = 0.9, nor within D = 0 at t_upper = 0.1.
#[test]
fn oracle_check_catches_a_wrong_interval() {
    let index = verify::oracle::index(&model("sphere").unwrap());
    // Centres (x = 3 - 3t) meet at distance 1.5 at t = 0.5.
    let scene = Scene {
        a: &index,
        b: &index,
        pose_a: [Isometry3::identity(); 2],
        pose_b: [
            Isometry3::translation(3.0, 0.0, 0.0),
            Isometry3::translation(0.0, 0.0, 0.0),
        ],
    };
    let mut breaches = Vec::new();
    scene.check_apart(0.9, false, 0.0, &mut breaches);
    assert!(
        !breaches.is_empty(),
        "sampled overlap before t_lower = 0.9 not seen"
    );
    let mut breaches = Vec::new();
    scene.check_apart(0.49, false, 0.0, &mut breaches);
    assert!(breaches.is_empty(), "{breaches:?}");
    scene.check_contact(0.1, 0.0, &mut breaches);
    assert_eq!(breaches.len(), 1, "apart at t_upper = 0.1 not seen");
    let mut breaches = Vec::new();
    scene.check_contact(0.51, 0.0, &mut breaches);
    assert!(breaches.is_empty(), "{breaches:?}");
}

/// The check's shortcuts (the bounding spheres, the oracle's goal) decide "apart" exactly as
/// the quick oracle does without them, at every sampled time of random motions of every
/// family (through contact, so both answers occur), for contact distances 0, 0.01 and 0.1.
#[test]
fn shortcuts_decide_as_the_unaided_oracle() {
    use revdist::rng::SplitMix64;
    use verify::toi::motions::{random_motion, Extent, Family};
    let names = ["sphere", "pawn", "cup", "bottle", "lightmill", "table"];
    let indexes: Vec<_> = names
        .iter()
        .map(|n| verify::oracle::index(&model(n).unwrap()))
        .collect();
    let extent = |i: usize| {
        let (c, r) = verify::toi::check::bounding_sphere(&indexes[i]);
        Extent {
            centre: c,
            radius: r,
        }
    };
    let mut rng = SplitMix64(0x5407_0c75);
    let (mut breaches, mut spheres, mut grid, mut times) = (0, 0, 0, 0);
    for k in 0..24 {
        let (ia, ib) = (rng.int(0, names.len() - 1), rng.int(0, names.len() - 1));
        let family = Family::ALL[k % Family::ALL.len()];
        let case = random_motion(&mut rng, family, &extent(ia), &extent(ib));
        let scene = Scene {
            a: &indexes[ia],
            b: &indexes[ib],
            pose_a: case.a,
            pose_b: case.b,
        };
        for t in Scene::times_before(1.0, true).into_iter().step_by(3) {
            let (new, decided) = scene.breach_apart(t, case.contact_distance);
            let old = scene.breach_apart_unaided(t, case.contact_distance);
            assert_eq!(
                new.is_some(),
                old,
                "{} {} {family:?} D = {} t = {t}",
                names[ia],
                names[ib],
                case.contact_distance
            );
            breaches += usize::from(old);
            spheres += usize::from(decided == Decided::Spheres);
            grid += usize::from(decided == Decided::Grid);
            times += 1;
        }
    }
    // Both answers and both shortcuts occur (seed 0x5407_0c75: 160 breaches of 456 times,
    // 215 decided by the spheres, 80 by the grid).
    let counts = format!("{breaches} breaches, {spheres} spheres, {grid} grid, of {times}");
    eprintln!("{counts}");
    assert!(breaches > 20 && breaches + 20 < times, "{counts}");
    assert!(spheres > 20 && grid > 20, "{counts}");
}

#[test]
fn fcl_continuous_collision_runs_on_meshes() {
    let cm = tessellate(
        &model("sphere").unwrap(),
        1e-2,
        TessellateOptions::default(),
    )
    .unwrap();
    let tm = TriMesh::from_points(&cm.mesh.vertices, &cm.mesh.triangles);
    let m = FclMesh::new(&tm, Bv::Obbrss).unwrap();
    let id = Isometry3::identity();
    let b0 = Isometry3::translation(3.0, 0.0, 0.0);
    let b1 = Isometry3::translation(0.0, 0.0, 0.0);
    // Naive: 101 samples, the first colliding one at or after the contact at t = 0.5.
    let n = m
        .continuous_collide(&m, [&id, &id], [&b0, &b1], CcdSolver::Naive, 101, 1e-4)
        .unwrap();
    assert!(n.supported && n.collide);
    assert!((0.49..=0.52).contains(&n.time_of_contact), "{n:?}");
    // Conservative advancement answers (whether it finds the contact is measured by
    // toi_bench, not asserted here).
    let ca = m
        .continuous_collide(
            &m,
            [&id, &id],
            [&b0, &b1],
            CcdSolver::ConservativeAdvancement,
            10,
            1e-4,
        )
        .unwrap();
    assert!(ca.supported, "{ca:?}");
    assert!(ca.time_of_contact.is_finite());
}
