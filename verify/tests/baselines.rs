//! The C++ baselines (FCL, libccd, CGAL through cxx) against analytic references.
//!
//! Torus meshes are built here with their vertices on the surface at parameters
//! `u = 2 pi i / nu`, `v = 2 pi j / nv` (nu, nv multiples of 4), so the circles where two
//! coaxial or side-by-side tori come closest are made of mesh vertices and the mesh distance
//! equals the exact torus distance up to rounding.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use rug::Rational;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use verify::baselines::ccd::{self, Algorithm, CcdParams};
use verify::baselines::cgal::{self, MeshLimits};
use verify::baselines::fcl::{Bv, FclMesh};
use verify::baselines::{BaselineError, TriMesh};

/// Torus major radius (centre of the tube to the axis).
const R: f64 = 1.0;
/// Torus minor radius (tube radius).
const RT: f64 = 0.3;
/// Rounding allowance for distances of order 1 computed in double precision.
const ROUND: f64 = 4.0 * f64::EPSILON;
/// FCL against the exact mesh distance on generically posed meshes with world coordinates up
/// to about 7: FCL moves vertices between frames in double precision, so its error is a few
/// ulps of the coordinates (ulp 8.9e-16 at 4..8), not of the distance; 1.33e-15 was the
/// largest difference seen (distance 1.08).
const FCL_VS_EXACT: f64 = 4e-15;

/// Torus (R, r) about the z axis, `nu` x `nv` quads split into two triangles each.
fn torus(nu: usize, nv: usize) -> TriMesh {
    let mut vertices = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let rho = R + RT * v.cos();
            vertices.push(Point3::new(rho * u.cos(), rho * u.sin(), RT * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriMesh::from_points(&vertices, &triangles)
}

fn shift(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::translation(x, y, z)
}

/// A fixed, generic rigid motion (to check that results follow the world frame).
fn generic_pose() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.37, -1.25, 2.5),
        UnitQuaternion::from_scaled_axis(Vector3::new(0.3, -0.7, 1.1)),
    )
}

#[test]
fn fcl_coaxial_stacked_tori() {
    let mesh = torus(64, 32);
    let dz = 0.9;
    for bv in [Bv::Obbrss, Bv::Rss] {
        let m = FclMesh::new(&mesh, bv).unwrap();
        assert_eq!(m.num_triangles(), 2 * 64 * 32);
        assert_eq!(m.num_bvs(), 2 * m.num_triangles() - 1);
        assert!(m.bytes() > m.num_bvs() * 100, "{m:?}");
        let d = m
            .distance(&m, &Isometry3::identity(), &shift(0.0, 0.0, dz))
            .unwrap();
        assert!((d.distance - (dz - 2.0 * RT)).abs() <= ROUND, "{d:?}");
        // Nearest points: on A's top circle (z = r) and B's bottom circle (z = dz - r), at a
        // ring vertex or on a ring edge (rho between R cos(pi / nu) and R).
        assert!((d.point_a.z - RT).abs() <= ROUND, "{d:?}");
        assert!((d.point_b.z - (dz - RT)).abs() <= ROUND, "{d:?}");
        for p in [d.point_a, d.point_b] {
            let rho = p.x.hypot(p.y);
            assert!(
                rho <= R + ROUND && rho >= R * (PI / 64.0).cos() - ROUND,
                "{p}"
            );
        }
        assert!(((d.point_b - d.point_a).norm() - d.distance).abs() <= ROUND);
    }
}

#[test]
fn fcl_side_by_side_tori_and_world_frame() {
    let mesh = torus(64, 32);
    let c = 2.9;
    let m = FclMesh::new(&mesh, Bv::Obbrss).unwrap();
    let d = m
        .distance(&m, &Isometry3::identity(), &shift(c, 0.0, 0.0))
        .unwrap();
    assert!(
        (d.distance - (c - 2.0 * R - 2.0 * RT)).abs() <= ROUND,
        "{d:?}"
    );
    assert!(
        (d.point_a - Point3::new(R + RT, 0.0, 0.0)).norm() <= ROUND,
        "{d:?}"
    );
    assert!(
        (d.point_b - Point3::new(c - R - RT, 0.0, 0.0)).norm() <= ROUND,
        "{d:?}"
    );

    // The same pair moved rigidly: same distance, nearest points moved with it (world frame).
    let g = generic_pose();
    let moved = m.distance(&m, &g, &(g * shift(c, 0.0, 0.0))).unwrap();
    assert!((moved.distance - d.distance).abs() <= 1e-14, "{moved:?}");
    assert!((moved.point_a - g * d.point_a).norm() <= 1e-14, "{moved:?}");
    assert!((moved.point_b - g * d.point_b).norm() <= 1e-14, "{moved:?}");
}

#[test]
fn fcl_rss_equals_obbrss_on_generic_poses() {
    let mesh = torus(32, 16);
    let (obbrss, rss) = (
        FclMesh::new(&mesh, Bv::Obbrss).unwrap(),
        FclMesh::new(&mesh, Bv::Rss).unwrap(),
    );
    assert_eq!(obbrss.num_bvs(), rss.num_bvs());
    assert!(
        obbrss.bytes() > rss.bytes(),
        "OBBRSS nodes are larger than RSS nodes"
    );
    for k in 0..20 {
        let t = k as f64;
        let pose_b = Isometry3::from_parts(
            Translation3::new(1.5 + 0.1 * t, 0.8 - 0.05 * t, 0.3 * (t * 0.7).sin()),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.2 * t, 1.0 - 0.1 * t, 0.5)),
        );
        let a = obbrss.distance(&obbrss, &generic_pose(), &pose_b).unwrap();
        let b = rss.distance(&rss, &generic_pose(), &pose_b).unwrap();
        assert!((a.distance - b.distance).abs() <= 1e-15, "{a:?} {b:?}");
    }
}

#[test]
fn fcl_rejects_bad_input() {
    let good = torus(8, 4);
    let mut out_of_range = good.clone();
    out_of_range.triangles[5] = good.num_vertices() as u32;
    let mut short = good.clone();
    short.vertices.pop();
    let mut ragged = good.clone();
    ragged.triangles.push(0);
    let mut nan = good.clone();
    nan.vertices[4] = f64::NAN;
    for (label, mesh) in [
        ("index out of range", &out_of_range),
        ("vertex length", &short),
        ("triangle length", &ragged),
        ("non-finite", &nan),
        ("empty", &TriMesh::default()),
    ] {
        match FclMesh::new(mesh, Bv::Obbrss) {
            Err(BaselineError::Cpp { library, message }) => {
                assert_eq!(library, "FCL");
                assert!(!message.is_empty(), "{label}");
            }
            other => panic!("{label}: expected a C++ error, got {other:?}"),
        }
    }
    let a = FclMesh::new(&good, Bv::Obbrss).unwrap();
    let b = FclMesh::new(&good, Bv::Rss).unwrap();
    let i = Isometry3::identity();
    assert!(matches!(
        a.distance(&b, &i, &i),
        Err(BaselineError::Input(_))
    ));
}

#[test]
fn cgal_exact_triangle_distances() {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let base = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
    // Parallel triangles 0.7 apart: exact squared distance (0.7 as a double)^2, distance 0.7.
    let lifted = base.map(|q| q + Vector3::new(0.0, 0.0, 0.7));
    let r = cgal::triangle_distance_exact(&base, &lifted).unwrap();
    let seven = Rational::from_f64(0.7).unwrap();
    assert_eq!(r.exact, Rational::from(&seven * &seven));
    assert_eq!(r.squared, 0.7 * 0.7); // IEEE multiplication is correctly rounded too
    assert_eq!(r.distance, 0.7);
    // Vertex above the interior of the face: 0.5^2.
    let apex = [p(0.25, 0.25, 0.5), p(0.25, 0.25, 2.0), p(1.0, 1.0, 3.0)];
    assert_eq!(
        cgal::triangle_distance_exact(&base, &apex).unwrap().exact,
        Rational::from((1, 4))
    );
    // A vertical triangle (plane x = 0.25) whose lowest edge runs 1.5 above the face.
    let skew = [p(0.25, -1.0, 1.5), p(0.25, 1.0, 1.5), p(0.25, 0.0, 4.0)];
    assert_eq!(
        cgal::triangle_distance_exact(&base, &skew).unwrap().exact,
        Rational::from((9, 4))
    );
    // Intersecting triangles: 0.
    let through = [p(0.2, 0.2, -1.0), p(0.2, 0.2, 1.0), p(0.6, 0.2, 1.0)];
    let r = cgal::triangle_distance_exact(&base, &through).unwrap();
    assert_eq!(r.exact, Rational::new());
    assert_eq!(r.distance, 0.0);
}

#[test]
fn cgal_mesh_distance_exact_stacked_tori() {
    // Coaxial tori stacked by dz: the exact distance of the meshes is the exact rational
    // (dz - 0.3 as placed) - 0.3 = dz - 2 r with the doubles' exact values (the vertices at
    // v = +-pi/2 have z = +-0.3 exactly; sin(pi/2) rounds to 1).
    let mesh = torus(16, 8);
    let dz = 0.9;
    let r = cgal::mesh_distance_exact(
        &mesh,
        &Isometry3::identity(),
        &mesh,
        &shift(0.0, 0.0, dz),
        &MeshLimits::default(),
    )
    .unwrap();
    let gap = Rational::from_f64(dz).unwrap() - Rational::from_f64(RT).unwrap() * 2u32;
    assert_eq!(r.value.exact, Rational::from(&gap * &gap), "{r:?}");
    assert!(r.candidates >= 1);
    let fcl = FclMesh::new(&mesh, Bv::Obbrss).unwrap();
    let f = fcl
        .distance(&fcl, &Isometry3::identity(), &shift(0.0, 0.0, dz))
        .unwrap();
    assert!(
        (f.distance - r.value.distance).abs() <= ROUND,
        "{f:?} {r:?}"
    );
}

#[test]
fn cgal_mesh_distance_matches_fcl_on_generic_poses() {
    let mesh = torus(16, 8);
    let fcl = FclMesh::new(&mesh, Bv::Obbrss).unwrap();
    let pose_a = generic_pose();
    for k in 0..4 {
        let t = k as f64;
        // Centres 2.7 + 0.1 k apart (> 2 (R + r)): separated, whatever the rotation.
        let offset = Vector3::new(2.7 + 0.1 * t, 0.0, 0.0);
        let pose_b = pose_a
            * Isometry3::from_parts(
                Translation3::from(
                    UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.0, t)) * offset,
                ),
                UnitQuaternion::from_scaled_axis(Vector3::new(0.9, 0.3 * t, -0.4)),
            );
        let exact =
            cgal::mesh_distance_exact(&mesh, &pose_a, &mesh, &pose_b, &MeshLimits::default())
                .unwrap();
        let f = fcl.distance(&fcl, &pose_a, &pose_b).unwrap();
        assert!(
            exact.value.distance > 0.05,
            "pose {k} should be separated: {exact:?}"
        );
        // FCL is exact for the meshes up to the rounding of its frame changes (FCL_VS_EXACT).
        assert!(
            (f.distance - exact.value.distance).abs() <= FCL_VS_EXACT,
            "pose {k}: FCL {} exact {} ({} candidates)",
            f.distance,
            exact.value.distance,
            exact.candidates
        );
    }
}

#[test]
fn cgal_rejects_bad_input_and_limits() {
    let good = torus(8, 4);
    let i = Isometry3::identity();
    let mut bad = good.clone();
    bad.triangles[0] = 1_000;
    let r = cgal::mesh_distance_exact(&bad, &i, &good, &i, &MeshLimits::default());
    assert!(
        matches!(
            r,
            Err(BaselineError::Cpp {
                library: "CGAL",
                ..
            })
        ),
        "{r:?}"
    );
    let tight = MeshLimits {
        max_pairs: 10,
        ..MeshLimits::default()
    };
    assert!(cgal::mesh_distance_exact(&good, &i, &good, &shift(3.0, 0.0, 0.0), &tight).is_err());
    assert!(cgal::polytope_distance_exact(&[], &[Point3::origin()]).is_err());
    let nan = [Point3::new(f64::NAN, 0.0, 0.0)];
    assert!(cgal::polytope_distance_exact(&nan, &[Point3::origin()]).is_err());
}

/// Corners of the axis-aligned box [lo, hi].
fn cube(lo: [f64; 3], hi: [f64; 3]) -> Vec<Point3<f64>> {
    (0..8)
        .map(|k| {
            let pick = |bit: usize, a: usize| if k >> bit & 1 == 0 { lo[a] } else { hi[a] };
            Point3::new(pick(0, 0), pick(1, 1), pick(2, 2))
        })
        .collect()
}

#[test]
fn cgal_polytope_distance_on_cubes() {
    let unit = cube([0.0; 3], [1.0; 3]);
    // [0,1]^3 vs [2,3]^3: the corners (1,1,1) and (2,2,2), squared distance 3.
    let r = cgal::polytope_distance_exact(&unit, &cube([2.0; 3], [3.0; 3])).unwrap();
    assert_eq!(r.value.exact, Rational::from(3));
    assert_eq!(r.value.distance, 3f64.sqrt());
    assert!(
        (r.point_p - Point3::new(1.0, 1.0, 1.0)).norm() < 1e-12,
        "{r:?}"
    );
    assert!(
        (r.point_q - Point3::new(2.0, 2.0, 2.0)).norm() < 1e-12,
        "{r:?}"
    );
    // Gaps 0.5, 0 (overlapping range), 2 along x, y, z: 0.25 + 4.
    let far = cube([1.5, 0.5, 3.0], [2.5, 1.5, 4.0]);
    let r = cgal::polytope_distance_exact(&unit, &far).unwrap();
    assert_eq!(r.value.exact, Rational::from((17, 4)));
    // Overlapping hulls: 0.
    let r = cgal::polytope_distance_exact(&unit, &cube([0.5; 3], [1.5; 3])).unwrap();
    assert_eq!(r.value.exact, Rational::new());
}

#[test]
fn libccd_penetration_and_separation_of_cubes() {
    let params = CcdParams::default();
    let a = cube([-1.0; 3], [1.0; 3]);
    // B = A moved by 1.5 along x: overlap 0.5.
    let b = cube([0.5, -1.0, -1.0], [2.5, 1.0, 1.0]);
    for alg in [Algorithm::Gjk, Algorithm::Mpr] {
        assert!(ccd::intersect(&a, &b, alg, &params).unwrap());
        let p = ccd::penetration(&a, &b, alg, &params)
            .unwrap()
            .expect("overlap");
        assert!((p.depth - 0.5).abs() <= 1e-9, "{alg:?} {p:?}");
        assert!((p.direction.x.abs() - 1.0).abs() <= 1e-9, "{alg:?} {p:?}");
    }
    let sep = ccd::gjk_separate(&a, &b, &params)
        .unwrap()
        .expect("overlap");
    assert!(
        (sep.norm() - 0.5).abs() <= 1e-9 && sep.x.abs() > 0.5 - 1e-9,
        "{sep}"
    );
    let signed = ccd::gjk_signed_distance(&a, &b).unwrap();
    assert!((signed.distance + 0.5).abs() <= 1e-6, "{signed:?}");
    assert!(ccd::gjk_distance(&a, &b).unwrap().is_none());

    // Separated by a gap of 1.5 along x.
    let c = cube([2.5, -1.0, -1.0], [4.5, 1.0, 1.0]);
    for alg in [Algorithm::Gjk, Algorithm::Mpr] {
        assert!(!ccd::intersect(&a, &c, alg, &params).unwrap());
        assert!(ccd::penetration(&a, &c, alg, &params).unwrap().is_none());
    }
    assert!(ccd::gjk_separate(&a, &c, &params).unwrap().is_none());
}

#[test]
fn gjk_distance_on_separated_cubes() {
    let a = cube([-1.0; 3], [1.0; 3]);
    // Gaps 1.5 (x) and 1 (y): distance sqrt(3.25).
    let b = cube([2.5, 2.0, -0.5], [4.5, 4.0, 0.5]);
    let d = ccd::gjk_distance(&a, &b).unwrap().expect("separated");
    assert!((d.distance - 3.25f64.sqrt()).abs() <= 1e-9, "{d:?}");
    assert!(
        ((d.point_b - d.point_a).norm() - d.distance).abs() <= 1e-9,
        "{d:?}"
    );
    assert!(
        (d.point_a.x - 1.0).abs() <= 1e-9 && (d.point_a.y - 1.0).abs() <= 1e-9,
        "{d:?}"
    );
    let exact = cgal::polytope_distance_exact(&a, &b).unwrap();
    assert_eq!(exact.value.exact, Rational::from((13, 4)));
}

/// Deterministic quasi-random points on the unit sphere (golden-angle spiral).
fn sphere_points(n: usize, centre: Point3<f64>) -> Vec<Point3<f64>> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / n as f64;
            let rho = (1.0 - z * z).sqrt();
            let phi = golden * k as f64;
            centre + Vector3::new(rho * phi.cos(), rho * phi.sin(), z)
        })
        .collect()
}

#[test]
fn gjk_distance_agrees_with_cgal_on_sphere_hulls() {
    let a = sphere_points(300, Point3::origin());
    for (k, c) in [
        Point3::new(2.6, 0.4, -0.3),
        Point3::new(0.2, -2.3, 0.9),
        Point3::new(1.2, 1.2, 1.2),
    ]
    .into_iter()
    .enumerate()
    {
        let b = sphere_points(300, c);
        let exact = cgal::polytope_distance_exact(&a, &b).unwrap();
        let gjk = ccd::gjk_distance(&a, &b).unwrap().expect("separated");
        // GJK stops on small improvement, not on a certified gap: 1e-8 is generous.
        assert!(
            (gjk.distance - exact.value.distance).abs() <= 1e-8,
            "case {k}: GJK {} exact {}",
            gjk.distance,
            exact.value.distance
        );
        // Roughly the sphere distance (the hull is inside the sphere).
        let sphere = (c - Point3::origin()).norm() - 2.0;
        assert!(exact.value.distance >= sphere && exact.value.distance < sphere + 0.05);
    }
}

#[test]
fn libccd_rejects_bad_input() {
    let a = cube([0.0; 3], [1.0; 3]);
    let p = CcdParams::default();
    assert!(matches!(
        ccd::intersect(&[], &a, Algorithm::Gjk, &p),
        Err(BaselineError::Cpp { .. })
    ));
    let nan = [Point3::new(0.0, f64::INFINITY, 0.0)];
    assert!(ccd::penetration(&a, &nan, Algorithm::Mpr, &p).is_err());
    let zero_iter = CcdParams {
        max_iterations: 0,
        ..p
    };
    assert!(ccd::gjk_separate(&a, &a, &zero_iter).is_err());
    assert!(ccd::gjk_distance_with(&a, &a, 10, -1.0).is_err());
    // v = +-pi/2 rounds as expected in the torus builder used above.
    assert_eq!(FRAC_PI_2.sin(), 1.0);
}
