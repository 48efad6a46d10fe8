//! Certified tessellation: watertight, outward, and within its certified Hausdorff
//! bound of the true surface, measured against an independent evaluation of the surface (the
//! NURBS profile evaluated densely, not the biarc tree).
//!
//! Measurement, both directions:
//! - mesh -> surface: points of every triangle (a barycentric grid with the corners and edge
//!   midpoints, where the balanced construction deviates most) are mapped to their meridian
//!   point `(|xy|, z)`; the distance of a 3-D point to a surface of revolution is the planar
//!   distance of its meridian point to the profile curve. That distance is taken to a dense
//!   polyline of the curve (`SAMPLES_PER_SPAN` evaluations per NURBS span), which is within
//!   `sigma` of the curve two-sided; `sigma` is measured per profile as the largest distance
//!   between a chord's midpoint and the curve point at the mid parameter (the sagitta to second
//!   order), so the true distance is at least the measured one minus `sigma`.
//! - surface -> mesh: exact NURBS points revolved to `ANGLES` angles (not aligned with the
//!   mesh's rings, so some fall near the middle of a ring edge, where the mesh is farthest
//!   inside), each at its exact point-to-triangle distance from the mesh.
//!
//! Both are sampled maxima, so they are lower estimates of the true Hausdorff distance: a
//! measured value above the certified bound (plus `sigma`) disproves the bound.
//!
//! `cargo test --release --test tessellate -- --nocapture` prints the measured/certified table
//! and the triangle counts.

use std::collections::HashMap;

use nalgebra::{Point2, Point3, Vector3};
use revdist::models;
use revdist::profile::Profile;
use revdist::tessellate::{
    tessellate, CertifiedMesh, TessellateError, TessellateOptions, TriMesh, VertexPlacement,
};

/// Dense evaluations per NURBS span for the reference polyline (its measured `sigma` is
/// asserted to stay below 1e-3 eps).
const SAMPLES_PER_SPAN: usize = 800;
/// Angles at which surface samples are taken (prime, so not a multiple of any ring count
/// that matters here).
const ANGLES: usize = 211;
/// About this many reference samples (evenly strided) are revolved into surface samples.
const SURFACE_SAMPLES: usize = 4000;
/// Barycentric grid of mesh samples per triangle (`k = 4`: 15 points incl. corners and edge
/// midpoints).
const TRIANGLE_GRID: usize = 4;

/// The profile curve sampled densely from its NURBS pieces, with the sampling tolerance.
struct Reference {
    points: Vec<Point2<f64>>,
    /// Largest measured chord-to-curve deviation of the dense polyline.
    sigma: f64,
    grid: Grid2,
}

impl Reference {
    /// `cell`: grid cell size for the distance queries (about the distances expected).
    fn new(profile: &Profile, cell: f64) -> Reference {
        let mut points: Vec<Point2<f64>> = Vec::new();
        let mut sigma: f64 = 0.0;
        for piece in profile.pieces() {
            for (t0, t1) in piece.distinct_spans() {
                let n = SAMPLES_PER_SPAN;
                let mut prev = piece.eval(t0);
                if points.last() != Some(&prev) {
                    points.push(prev);
                }
                for k in 1..=n {
                    let t = t0 + (t1 - t0) * k as f64 / n as f64;
                    let p = piece.eval(t);
                    let mid = piece.eval(t0 + (t1 - t0) * (k as f64 - 0.5) / n as f64);
                    sigma = sigma.max((mid - nalgebra::center(&prev, &p)).norm());
                    points.push(p);
                    prev = p;
                }
            }
        }
        let grid = Grid2::new(&points, cell);
        Reference {
            points,
            sigma,
            grid,
        }
    }

    /// Distance from a meridian point to the dense polyline.
    fn distance(&self, p: Point2<f64>) -> f64 {
        self.grid.distance(&self.points, p)
    }
}

fn seg_dist2(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    let u = if l2 > 0.0 {
        ((p - a).dot(&d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * u)).norm()
}

/// Uniform grid over the segments of a polyline.
struct Grid2 {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl Grid2 {
    fn new(points: &[Point2<f64>], cell: f64) -> Grid2 {
        let len: f64 = points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        let cell = cell.max(4.0 * len / points.len() as f64);
        let key = |v: f64| (v / cell).floor() as i64;
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for i in 0..points.len() - 1 {
            let (a, b) = (points[i], points[i + 1]);
            for x in key(a.x.min(b.x))..=key(a.x.max(b.x)) {
                for y in key(a.y.min(b.y))..=key(a.y.max(b.y)) {
                    cells.entry((x, y)).or_default().push(i);
                }
            }
        }
        Grid2 { cell, cells }
    }

    /// Exact distance to the polyline: rings of cells around `p`, outwards until the best
    /// distance found is below the inner radius of the next ring.
    fn distance(&self, points: &[Point2<f64>], p: Point2<f64>) -> f64 {
        let (cx, cy) = (
            (p.x / self.cell).floor() as i64,
            (p.y / self.cell).floor() as i64,
        );
        let mut best = f64::INFINITY;
        for ring in 0i64..100_000 {
            for x in cx - ring..=cx + ring {
                for y in cy - ring..=cy + ring {
                    if (x - cx).abs() != ring && (y - cy).abs() != ring {
                        continue;
                    }
                    for &i in self.cells.get(&(x, y)).into_iter().flatten() {
                        best = best.min(seg_dist2(p, points[i], points[i + 1]));
                    }
                }
            }
            if best <= ring as f64 * self.cell {
                break;
            }
        }
        best
    }
}

/// Closest point of triangle `abc` to `p` (Voronoi regions of the vertices, edges and face).
fn triangle_distance(p: Point3<f64>, a: Point3<f64>, b: Point3<f64>, c: Point3<f64>) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.norm();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.norm();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + ab * v)).norm();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.norm();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + ac * w)).norm();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).norm();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (a + ab * v + ac * w)).norm()
}

/// Uniform grid over a mesh's triangles (by bounding box).
struct Grid3<'a> {
    mesh: &'a TriMesh,
    cell: f64,
    cells: HashMap<(i64, i64, i64), Vec<u32>>,
}

impl<'a> Grid3<'a> {
    fn new(mesh: &'a TriMesh) -> Grid3<'a> {
        let mut edges: Vec<f64> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.triangle(t);
                (b - a).norm().max((c - b).norm()).max((a - c).norm())
            })
            .collect();
        edges.sort_by(f64::total_cmp);
        let cell = edges[edges.len() / 2].max(1e-9);
        let key = |v: f64| (v / cell).floor() as i64;
        let mut cells: HashMap<(i64, i64, i64), Vec<u32>> = HashMap::new();
        for t in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(t);
            let lo = a.inf(&b).inf(&c);
            let hi = a.sup(&b).sup(&c);
            for x in key(lo.x)..=key(hi.x) {
                for y in key(lo.y)..=key(hi.y) {
                    for z in key(lo.z)..=key(hi.z) {
                        cells.entry((x, y, z)).or_default().push(t as u32);
                    }
                }
            }
        }
        Grid3 { mesh, cell, cells }
    }

    /// Distance from `p` to the mesh if it is at most `r`, else some value above `r`.
    fn distance_within(&self, p: Point3<f64>, r: f64) -> f64 {
        let key = |v: f64| (v / self.cell).floor() as i64;
        let mut best = f64::INFINITY;
        for x in key(p.x - r)..=key(p.x + r) {
            for y in key(p.y - r)..=key(p.y + r) {
                for z in key(p.z - r)..=key(p.z + r) {
                    for &t in self.cells.get(&(x, y, z)).into_iter().flatten() {
                        let [a, b, c] = self.mesh.triangle(t as usize);
                        best = best.min(triangle_distance(p, a, b, c));
                    }
                }
            }
        }
        best
    }
}

/// Measured Hausdorff distances of a certified mesh: (mesh -> surface, surface -> mesh).
fn measure(reference: &Reference, cm: &CertifiedMesh) -> (f64, f64) {
    let mesh = &cm.mesh;
    let k = TRIANGLE_GRID;
    let mut to_surface: f64 = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        for i in 0..=k {
            for j in 0..=(k - i) {
                let (u, v) = (i as f64 / k as f64, j as f64 / k as f64);
                let x = a + (b - a) * u + (c - a) * v;
                let m = Point2::new(x.x.hypot(x.y), x.z);
                to_surface = to_surface.max(reference.distance(m));
            }
        }
    }
    let grid = Grid3::new(mesh);
    let mut to_mesh: f64 = 0.0;
    let stride = (reference.points.len() / SURFACE_SAMPLES).max(1);
    // Anything farther than this is reported as far (and fails the check).
    let radius = 1.5 * cm.bound;
    for p in reference.points.iter().step_by(stride) {
        for j in 0..ANGLES {
            // An irrational offset keeps the angles away from the mesh's ring angles.
            let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.382) / ANGLES as f64;
            let y = Point3::from(Vector3::new(p.x * phi.cos(), p.x * phi.sin(), p.y));
            to_mesh = to_mesh.max(grid.distance_within(y, radius).min(1e300));
        }
    }
    (to_surface, to_mesh)
}

/// Volume of the solid by Pappus: `2 pi` times the rho-moment of the profile region, from the
/// dense reference polyline (closed by the axis for open profiles).
fn reference_volume(reference: &Reference) -> f64 {
    let p = &reference.points;
    let n = p.len();
    let moment: f64 = (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            (a.x + b.x) * (a.x * b.y - b.x * a.y)
        })
        .sum::<f64>()
        / 6.0;
    (2.0 * std::f64::consts::PI * moment).abs()
}

fn surface_area(mesh: &TriMesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t);
            0.5 * (b - a).cross(&(c - a)).norm()
        })
        .sum()
}

/// Structural checks every certified mesh must pass.
fn check_structure(name: &str, eps: f64, cm: &CertifiedMesh) {
    let top = cm.mesh.topology();
    assert!(top.is_watertight(), "{name} eps {eps}: {top:?}");
    assert!(
        cm.mesh.min_triangle_area() > 0.0,
        "{name}: zero-area triangle"
    );
    assert!(cm.bound <= eps, "{name}: bound {} > eps {eps}", cm.bound);
    let split = cm.leaf_error + cm.meridian_error + cm.revolution_error + cm.rounding_slack;
    assert!(
        cm.bound <= split * (1.0 + 1e-12),
        "{name}: bound above its split"
    );
}

fn check_model(name: &str, eps: f64, options: TessellateOptions) -> (f64, f64, CertifiedMesh) {
    let profile = models::model(name).unwrap();
    let cm = tessellate(&profile, eps, options).unwrap();
    check_structure(name, eps, &cm);
    let reference = Reference::new(&profile, 0.5 * eps);
    assert!(
        reference.sigma < 1e-3 * eps,
        "{name}: sampling sigma {}",
        reference.sigma
    );
    let (to_surface, to_mesh) = measure(&reference, &cm);
    let sigma = reference.sigma;
    assert!(
        to_surface - sigma <= cm.bound,
        "{name} eps {eps}: mesh->surface {to_surface} > bound {}",
        cm.bound
    );
    assert!(
        to_mesh <= cm.bound,
        "{name} eps {eps}: surface->mesh {to_mesh} > bound {}",
        cm.bound
    );
    // Volume: the symmetric difference lies within `bound` of the surface.
    let v_ref = reference_volume(&reference);
    let dv = (cm.mesh.signed_volume() - v_ref).abs();
    let allowance = 2.2 * cm.bound * surface_area(&cm.mesh);
    assert!(cm.mesh.signed_volume() > 0.0, "{name}: inward normals");
    assert!(dv <= allowance, "{name}: volume off by {dv} > {allowance}");
    eprintln!(
        "{name:<10} {eps:>7.0e} {:?}: {:>7} tris n_theta {:>4}  bound {:.3e}  measured m->s {:.3e} s->m {:.3e}  ratio {:.2}  (sigma {:.1e}; split leaf {:.2e} chord {:.2e} rev {:.2e})",
        cm.placement,
        cm.mesh.triangle_count(),
        cm.n_theta,
        cm.bound,
        to_surface,
        to_mesh,
        to_surface.max(to_mesh) / eps,
        sigma,
        cm.leaf_error,
        cm.meridian_error,
        cm.revolution_error,
    );
    (to_surface, to_mesh, cm)
}

#[test]
fn meshes_are_within_their_certified_bound() {
    for name in ["ring", "pawn", "cup", "bottle", "morph@0.3"] {
        for eps in [1e-2, 1e-3] {
            let (s, m, _) = check_model(name, eps, TessellateOptions::default());
            // The bound is tight: the measured error is a good fraction of it.
            assert!(
                s.max(m) >= 0.5 * eps,
                "{name} eps {eps}: measured only {}",
                s.max(m)
            );
        }
    }
}

#[test]
fn torus_error_is_close_to_eps() {
    let (s, m, cm) = check_model("ring", 1e-3, TessellateOptions::default());
    assert!(s.max(m) >= 0.8 * 1e-3, "measured {} {}", s, m);
    let on = check_model(
        "ring",
        1e-3,
        TessellateOptions {
            placement: VertexPlacement::OnSurface,
            ..Default::default()
        },
    )
    .2;
    // Balancing the vertices roughly halves the triangle count for the same bound.
    let ratio = cm.mesh.triangle_count() as f64 / on.mesh.triangle_count() as f64;
    assert!(ratio < 0.65, "balanced/on-surface triangles {ratio}");
}

#[test]
fn poles_creases_and_pinches_are_watertight() {
    for name in [
        "sphere",
        "capsule",
        "cylinder",
        "cone",
        "table",
        "lightmill",
    ] {
        check_model(name, 1e-2, TessellateOptions::default());
    }
    // Capped meridian edges on the flat disks (no long slivers), and the on-surface placement.
    let capped = TessellateOptions {
        max_meridian_edge: Some(0.05),
        ..Default::default()
    };
    let (_, _, cm) = check_model("cylinder", 1e-3, capped);
    for t in 0..cm.mesh.triangles.len() {
        let [a, b, c] = cm.mesh.triangle(t);
        let (ra, rb, rc) = (
            a.xy().coords.norm(),
            b.xy().coords.norm(),
            c.xy().coords.norm(),
        );
        let dz = (a.z - b.z)
            .abs()
            .max((b.z - c.z).abs())
            .max((a.z - c.z).abs());
        let drho = ra.max(rb).max(rc) - ra.min(rb).min(rc);
        assert!(dz.max(drho) <= 0.05 * 1.1, "meridian edge above the cap");
    }
    let on = TessellateOptions {
        placement: VertexPlacement::OnSurface,
        ..Default::default()
    };
    check_model("cone", 1e-3, on);
    check_model("pawn", 1e-3, on);
}

#[test]
fn a_pole_is_one_vertex() {
    let cm = tessellate(&models::model("sphere").unwrap(), 1e-3, Default::default()).unwrap();
    let on_axis = cm
        .mesh
        .vertices
        .iter()
        .filter(|v| v.x == 0.0 && v.y == 0.0)
        .count();
    assert_eq!(on_axis, 2);
    assert_eq!(
        cm.mesh.vertices.len(),
        2 + cm.n_theta * (cm.meridian_vertices - 2)
    );
}

#[test]
fn straight_pieces_are_single_segments() {
    // Cylinder: bottom disk, side, top disk: a fan, one band, a fan.
    let cm = tessellate(
        &models::model("cylinder").unwrap(),
        1e-3,
        Default::default(),
    )
    .unwrap();
    assert_eq!(cm.meridian_vertices, 4);
    assert_eq!(cm.mesh.triangle_count(), 4 * cm.n_theta);
}

#[test]
fn fixed_options_are_honoured_and_bad_ones_rejected() {
    let p = models::model("pawn").unwrap();
    let o = TessellateOptions {
        n_theta: Some(200),
        tree_fraction: Some(0.2),
        ..Default::default()
    };
    let cm = tessellate(&p, 1e-3, o).unwrap();
    assert_eq!(cm.n_theta, 200);
    assert!((cm.tree_eps - 0.2 * (1e-3 - cm.rounding_slack)).abs() < 1e-15);
    for eps in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            tessellate(&p, eps, Default::default()),
            Err(TessellateError::InvalidEps(_))
        ));
    }
    for bad in [
        TessellateOptions {
            n_theta: Some(2),
            ..Default::default()
        },
        TessellateOptions {
            tree_fraction: Some(1.0),
            ..Default::default()
        },
        TessellateOptions {
            max_meridian_edge: Some(1e-3),
            ..Default::default()
        },
    ] {
        assert!(matches!(
            tessellate(&p, 1e-3, bad),
            Err(TessellateError::InvalidOption(_))
        ));
    }
    // A ring too coarse for eps on its own.
    let o = TessellateOptions {
        n_theta: Some(8),
        ..Default::default()
    };
    assert!(matches!(
        tessellate(&p, 1e-3, o),
        Err(TessellateError::BudgetTooSmall { .. })
    ));
}

/// Triangle counts per model and eps (printed with `--nocapture`), structure checked. Eps
/// 1e-5 (up to 1.7 M triangles) is left to the experiments to keep the suite fast.
#[test]
fn triangle_counts() {
    eprintln!(
        "model       eps     triangles  n_theta  meridian  bound/eps  (on-surface triangles)"
    );
    for name in [
        "ring",
        "pawn",
        "cup",
        "bottle",
        "table",
        "lightmill",
        "morph@0.3",
    ] {
        let profile = models::model(name).unwrap();
        for eps in [1e-3, 1e-4] {
            let cm = tessellate(&profile, eps, Default::default()).unwrap();
            check_structure(name, eps, &cm);
            let on = tessellate(
                &profile,
                eps,
                TessellateOptions {
                    placement: VertexPlacement::OnSurface,
                    ..Default::default()
                },
            )
            .unwrap();
            assert!(on.bound <= eps);
            eprintln!(
                "{name:<10} {eps:>6.0e} {:>10} {:>8} {:>9} {:>10.3} ({})",
                cm.mesh.triangle_count(),
                cm.n_theta,
                cm.meridian_vertices,
                cm.bound / eps,
                on.mesh.triangle_count()
            );
        }
    }
}
