//! Unit tests of `verify circles`: a small campaign passes, and the catalogue's 8-binormal
//! entries and rational rotations are right.

use super::cases::rotation_from_quaternion_rat;
use super::{catalogue, run, Case, RCircle};
use crate::exact_circle::{rotation_from_quaternion, rotation_from_rational_quaternion};
use rug::Rational;

/// Bound on the companion-matrix reference's relative error in [`small_slice_passes`].
const COMPANION_REL_BOUND: f64 = 1e-3;

#[test]
fn small_slice_passes() {
    let s = run(1500, 1, 1);
    eprintln!("{s}");
    assert_eq!(s.total().1, 0, "{s}");
    // Binormal counts: in the random family every mismatch with the exact Sturm count
    // must be a pair of exact roots closer than CLUSTER_GAP (not resolvable in double
    // precision, see its doc comment). Perturbed catalogue entries are exempt: within
    // 1e-14..1e-4 of a continuum the polynomial is within noise of zero, and the count
    // of its roots is not a double-precision quantity.
    assert_eq!(s.count_mismatch_random_resolvable, 0, "{s}");
    // The faer companion-matrix reference finds every minimum: its error is bounded by
    // the power basis' conditioning (coefficients spanning up to 1e24 at radius ratios
    // of 1e6; measured worst 9.1e-5 on 31,600 cases), never a missed root (errors of
    // order 1, as before candidates included complex-split eigenvalues).
    assert!(s.companion_worst <= COMPANION_REL_BOUND, "{s}");
}

/// The 8-binormal entries really have 8 binormals (exact Sturm count), and the rational
/// quaternion rotation agrees with the integer one.
#[test]
fn eight_binormal_entries_have_eight() {
    let mut found = 0;
    for (label, c, q, r, _) in catalogue() {
        if !label.starts_with("8 binormals") {
            continue;
        }
        let case = Case {
            family: "catalogue",
            label: label.into(),
            ra: Rational::from(1),
            b: RCircle::rotated(c, &rotation_from_quaternion(q), r),
            motion: None,
            analytic: None,
        };
        let res = case.exact_pair().analyse().expect("finite");
        assert_eq!(res.root_count, 8, "{label}");
        found += 1;
    }
    assert_eq!(found, 2);
    let rq = rotation_from_rational_quaternion(&[3, -1, 2, 5].map(Rational::from));
    assert_eq!(rq, rotation_from_quaternion([3, -1, 2, 5]));
    // (m, 1, 0, 0) turns about x by 2 atan(1 / m).
    let tilt = rotation_from_quaternion_rat(Rational::from(1000));
    let angle = tilt[1][2].to_f64().atan2(tilt[1][1].to_f64());
    assert!((angle - 2.0 * (1e-3f64).atan()).abs() < 1e-15);
}
