//! Unit tests of the reproducer command line and the CSV quoting.

use super::query::{Kind, Placed, Spec};
use super::report::csv_field;
use super::MORPH_FRAME;

#[test]
fn reproducer_numbers_parse_back_to_the_timed_pose() {
    let q = Placed {
        spec: Spec {
            index: 3,
            kind: Kind::Flipped,
            eps: 1e-7,
            tol0: true,
            seed: 1,
        },
        a: "pawn_ff".into(),
        b: MORPH_FRAME.into(),
        gap: 1e-3,
        translation: [0.1 + 0.2, -1e-9, 1.0 / 3.0],
        rotation: [0.0, 1.0, -0.0, 0.0],
    };
    let line = q.reproducer();
    assert!(line.starts_with(
        "revdist distance pawn_ff morph@0.3 --eps 1e-7 --tolerance 0 --json --pose-b '{"
    ));
    let json = line.split('\'').nth(1).unwrap();
    let nums: Vec<f64> = json
        .split(|c: char| "[],:{}\"".contains(c))
        .filter_map(|w| w.parse().ok())
        .collect();
    let expect: Vec<f64> = q.translation.iter().chain(&q.rotation).copied().collect();
    assert_eq!(nums.len(), 7);
    for (x, y) in nums.iter().zip(&expect) {
        assert_eq!(x.to_bits(), y.to_bits(), "{json}");
    }
    // The pose is the one the command line builds: a half turn about x.
    let p = q.pose() * nalgebra::Point3::new(0.0, 0.0, 1.0);
    assert!((p - nalgebra::Point3::new(0.3, -1e-9, 1.0 / 3.0 - 1.0)).norm() < 1e-12);
    assert_eq!(csv_field("a,b\"c"), "\"a,b\"\"c\"");
    assert_eq!(csv_field("plain"), "plain");
}
