//! Quick slice of `verify crosscheck`: revdist against FCL meshes on every mesh
//! pair, and against CGAL and libccd on the convex pairs, with a few poses of each kind;
//! asserts zero failures (see verify/src/crosscheck/mod.rs for the criterion).

use verify::crosscheck::{run, Options};

/// Poses per mesh pair (covers every pose kind, see `PoseKind::of_index`).
const POSES: usize = 4;
/// Poses per convex pair.
const CONVEX_POSES: usize = 4;

#[test]
fn crosscheck_quick_slice_has_no_failures() {
    let opts = Options {
        poses: POSES,
        convex_poses: CONVEX_POSES,
        eps: verify::crosscheck::options::DEFAULT_EPS.to_vec(),
        // The OCCT sweep has its own test (occt.rs).
        occt_poses: 0,
        ..Options::default()
    };
    let report = run(&opts).expect("cross-check runs");
    // One FCL record per mesh case; per convex case a CGAL record and a GJK or EPA record.
    let n_eps = opts.eps.len();
    let expected = n_eps * (opts.pairs.len() * POSES + 2 * opts.convex_pairs.len() * CONVEX_POSES);
    assert_eq!(
        report.total(None).cases,
        expected,
        "every case was compared"
    );
    assert_eq!(
        report.failures(),
        0,
        "cross-check failures:\n{}",
        report.markdown()
    );
}
