//! Unit tests of the planar queries: distance, closest point and inside test on squares,
//! open chains, retraces and zero-speed knots.

use super::PlanarIndex;
use crate::oracle::profile_eval::{dist, norm, PieceEval, ProfileGeom, P2};
use revdist::profile::ProfileKind;

fn line(a: P2, b: P2) -> PieceEval {
    PieceEval::new(1, &[0.0, 0.0, 1.0, 1.0], &[a, b], None)
}

#[test]
fn square_ring_inside_and_distance() {
    let (a, b, c, d) = ([1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]);
    let g = ProfileGeom::from_pieces(
        "sq".into(),
        vec![line(a, b), line(b, c), line(c, d), line(d, a)],
        ProfileKind::Closed,
    );
    let idx = PlanarIndex::new(g);
    let s = idx.signed([1.5, 0.5]);
    assert!((s.value + 0.5).abs() < 1e-14);
    let s = idx.signed([1.2, 0.5]);
    assert!((s.value + 0.2).abs() < 1e-14);
    let s = idx.signed([3.0, 2.0]);
    assert!((s.value - 2f64.sqrt()).abs() < 1e-14);
    let s = idx.signed([0.0, 0.5]);
    assert!((s.value - 1.0).abs() < 1e-14);
    assert!(!idx.inside_poly([0.5, 0.5]));
    assert!(idx.inside_poly([1.999, 0.999]));
}

/// A cubic that leaves a corner backwards along its own line for 4e-6 and returns (a
/// retrace, found by the stationary-point property test): the polyline's probes at 1/8
/// of a chord missed the fin's tip, and the oracle put a point of the tip 3.9e-6 from
/// the curve. The control-polygon bound of the sagitta refines the polyline around it.
#[test]
fn retrace_fin_at_a_corner_is_on_the_curve() {
    let (c, d) = (
        [0.6149755885599717, 0.90542182387424],
        [1.5437466728434721, 0.90542182387424],
    );
    let fin = PieceEval::new(
        3,
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        &[c, [0.6137585056521959, c[1]], [0.8929366780727052, c[1]], d],
        None,
    );
    let (a, e) = (
        [0.5041220461639593, 1.4047918639542627],
        [1.6780510783507863, 1.4047918639542627],
    );
    let g = ProfileGeom::from_pieces(
        "retrace".into(),
        vec![line(a, c), fin, line(d, e), line(e, a)],
        ProfileKind::Closed,
    );
    let idx = PlanarIndex::new(g);
    // The tip: x(t) = c + 3 t (x1 - c) + ... has its minimum at t = 0.0021695...
    let tip = [0.6149716273419957, c[1]];
    let hit = idx.closest(tip);
    assert!(hit.dist < 1e-12, "tip {:e} from the curve", hit.dist);
    let beyond = idx.closest([tip[0] - 1e-6, c[1]]);
    assert!((beyond.dist - 1e-6).abs() < 1e-12, "{:e}", beyond.dist);
}

/// Case f11 of the stationary-point property test (`verify/regressions/near-stationary/zero-speed-knot.toml`): piece 2 is a cubic
/// B-spline whose speed vanishes at its knot 0.99834504835 (a stationary point on a knot)
/// and slows down towards it over the span before. `q` is that piece's point at
/// t = 0.8914, so its distance to the curve is zero up to the round-off of one curve
/// evaluation (a few ulps of coordinates of size ~1, i.e. ~1e-16). The tolerance is
/// [`SLACK_REL`](crate::oracle::checks::SLACK_REL) = 1e-12 times `1 + |q|`, the round-off
/// slack the checks grant witness points: four orders above that round-off and nine
/// below the wrong answer the Newton iteration on `(C - q) . C'` gave (6.45e-3 at
/// t = 0.93584, where `h'` nearly vanishes as the curve decelerates).
#[test]
fn closest_next_to_zero_speed_knot_is_on_the_curve() {
    let profile = revdist::profile_file::from_toml_str_allowing_self_contact(include_str!(
        "../../../regressions/near-stationary/zero-speed-knot.toml"
    ))
    .expect("the f11 profile builds");
    let idx = crate::oracle::index(&profile);
    let q = [1.1755570567281444, 0.11530362878890313];
    let on_curve = idx.geom.point(2, 0.8914);
    assert!(dist(on_curve, q) < 1e-15, "q is piece 2 at t = 0.8914");
    let hit = idx.closest(q);
    let tol = crate::oracle::checks::SLACK_REL * (1.0 + norm(q));
    assert!(
        hit.dist < tol,
        "closest: dist {:e} (piece {}, t {}, p {:?}) above {tol:e}",
        hit.dist,
        hit.piece,
        hit.t,
        hit.p
    );
}

/// A corner at a knot inside a piece (a degree-1 polyline turning at (1, 0), from a slanted
/// side to the top): a point just beyond the corner and 1e-15 below its height is outside,
/// 1e-6 from the corner, which is its closest point. (A curved piece elsewhere gives the
/// polyline a sagitta above that distance, so the side comes from the closest point.) The
/// tangent of the span after the corner (pointing along the top edge) put it inside, since
/// the corner counted as a joint only at a piece's ends (campaign 1803, case 17213: a
/// random profile against the bottle, reported overlapping at 1.27e-6 apart).
#[test]
fn corner_inside_a_piece_gives_no_side_from_its_tangent() {
    let profile = revdist::profile_file::from_toml_str_allowing_self_contact(
        r#"
name = "quad-with-inner-corner"
[[piece]]
degree = 1
knots = [0.0, 0.0, 1.0, 1.0]
points = [[0.0, -1.0], [0.9, -1.0]]
[[piece]]
degree = 1
knots = [0.0, 0.0, 0.5, 1.0, 1.0]
points = [[0.9, -1.0], [1.0, 0.0], [0.5, 0.0]]
[[piece]]
degree = 2
knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
points = [[0.5, 0.0], [0.25, 0.4], [0.0, 0.0]]
"#,
    )
    .expect("the profile builds");
    let idx = crate::oracle::index(&profile);
    let beyond = idx.signed([1.0 + 1e-6, -1e-15]);
    assert!(
        (beyond.value - 1e-6).abs() < 1e-12,
        "signed {:e}, expected +1e-6 (outside)",
        beyond.value
    );
    let within = idx.signed([1.0 - 1e-6, -1e-6]);
    assert!(
        within.value < 0.0,
        "signed {:e}, expected inside",
        within.value
    );
}

#[test]
fn open_chain_closed_by_axis() {
    // Half of a square [0, 1] x [0, 1] around the axis: bottom, side, top.
    let g = ProfileGeom::from_pieces(
        "cyl".into(),
        vec![
            line([0.0, 0.0], [1.0, 0.0]),
            line([1.0, 0.0], [1.0, 1.0]),
            line([1.0, 1.0], [0.0, 1.0]),
        ],
        ProfileKind::OpenOnAxis,
    );
    let idx = PlanarIndex::new(g);
    // On the axis, inside: distance to the curve, not to the axis.
    let s = idx.signed([0.0, 0.5]);
    assert!((s.value + 0.5).abs() < 1e-14, "{}", s.value);
    let s = idx.signed([0.1, 0.5]);
    assert!((s.value + 0.5).abs() < 1e-14);
    let s = idx.signed([0.0, 1.5]);
    assert!((s.value - 0.5).abs() < 1e-14);
    let s = idx.signed([0.9, 0.95]);
    assert!((s.value + 0.05).abs() < 1e-14);
    assert!(!idx.inside_poly([0.0, -0.1]));
}
