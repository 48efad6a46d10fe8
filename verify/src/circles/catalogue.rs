//! The catalogue of degenerate circle pairs (research notes section 2.1), A the unit circle.

use super::rcircle::rat;
use rug::Rational;

/// One catalogued configuration: (label, centre, integer rotation quaternion mapping z to
/// the normal, radius, analytic distance when the polynomial vanishes).
pub type CatalogueEntry = (&'static str, [Rational; 3], [i64; 4], Rational, Option<f64>);

/// The degenerate catalogue (research notes section 2.1), A the unit circle.
pub fn catalogue() -> Vec<CatalogueEntry> {
    let z = Rational::new;
    // Integer quaternions with rational rotations: (2,1,0,0) rotates z by atan(4/3) about x:
    // normal (0, -4/5, 3/5); (3,0,1,0) rotates z about y: normal (3/5, 0, 4/5).
    vec![
        (
            "D1 centre on axis",
            [z(), z(), rat(1, 2)],
            [3, 0, 1, 0],
            rat(1, 2),
            None,
        ),
        (
            "D1b centre on axis",
            [z(), z(), rat(1, 2)],
            [3, -1, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "D6 centre on axis",
            [z(), z(), rat(1, 3)],
            [2, 1, 0, 0],
            rat(9, 10),
            None,
        ),
        (
            "D2 meridian",
            [z(), Rational::from(1), z()],
            [1, 0, 1, 0],
            rat(1, 2),
            Some(0.5),
        ),
        (
            "D3 Villarceau",
            [z(), rat(3, 5), z()],
            [3, 0, -1, 0],
            Rational::from(1),
            Some(0.6),
        ),
        (
            "D4 through centre",
            [rat(1, 2), z(), z()],
            [1, -1, 0, 0],
            rat(1, 2),
            None,
        ),
        ("D5", [rat(1, 2), z(), z()], [1, -1, 0, 0], rat(3, 4), None),
        (
            "coaxial",
            [z(), z(), Rational::from(2)],
            [1, 0, 0, 0],
            rat(1, 2),
            Some(0.5f64.hypot(2.0)),
        ),
        (
            "concentric coplanar",
            [z(), z(), z()],
            [0, 1, 0, 0],
            rat(1, 4),
            Some(0.75),
        ),
        (
            "coplanar separated",
            [Rational::from(3), z(), z()],
            [1, 0, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "coplanar tangent",
            [rat(3, 2), z(), z()],
            [1, 0, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "coplanar intersecting",
            [Rational::from(1), z(), z()],
            [1, 0, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "coplanar nested",
            [rat(1, 4), z(), z()],
            [1, 0, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "parallel planes",
            [Rational::from(3), z(), Rational::from(1)],
            [1, 0, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "linked",
            [Rational::from(1), z(), rat(1, 10)],
            [1, -1, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "intersecting 3-D",
            [rat(7, 10), z(), rat(2, 5)],
            [1, -1, 0, 0],
            rat(1, 2),
            None,
        ),
        (
            "larger centre on smaller axis",
            [z(), z(), rat(1, 2)],
            [3, 0, 1, 0],
            Rational::from(3),
            None,
        ),
        // Exactly 8 binormals (Neff's bound), the pinned pairs of revdist's circle tests
        // (`eight_binormals_pinned`, found by `verify eight --count 400 --seed 11 --min-gap
        // 0.1`) scaled by 1 / ra so that A is the unit circle.
        (
            "8 binormals A",
            [rat(37, 91), rat(-37, 91), rat(-38, 91)],
            [0, -7, 1, -6],
            rat(85, 91),
            None,
        ),
        (
            "8 binormals B",
            [rat(-34, 87), rat(-17, 87), rat(7, 87)],
            [-9, 9, -8, -8],
            rat(112, 87),
            None,
        ),
        (
            "tangent along axis at centre",
            [Rational::from(1), z(), z()],
            [1, -1, 0, 0],
            Rational::from(1),
            Some(1.0),
        ),
    ]
}
