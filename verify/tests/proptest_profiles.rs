//! Property test (proptest) of the certificate on random freeform profiles: for any profile
//! the generator can draw (closed or open on the axis, 4-40 control points, straight spans,
//! corners, several pieces, pieces touching the axis), any pose of a second solid and any eps
//! in 1e-3..1e-6, the query's answer passes every check of the independent oracle.
//! Run in release mode: `cargo test --release -p verify --test proptest_profiles`.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use proptest::prelude::*;
use revdist::rng::SplitMix64;
use verify::queries::{single, PoseSpec};
use verify::random_profiles::random_profile;

proptest! {
    // 40 cases unless PROPTEST_CASES asks for more (the seed comes from PROPTEST_RNG_SEED).
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(40),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_profiles_are_certified(
        seed_a in any::<u64>(),
        seed_b in any::<u64>(),
        eps_exp in 3i32..=6,
        dir in prop::array::uniform3(-1.0f64..1.0),
        reach in 0.3f64..2.5,
        rot in prop::array::uniform4(-1.0f64..1.0),
    ) {
        let (a, _) = random_profile(&mut SplitMix64(seed_a), "prop-a", 1.0);
        let (b, _) = random_profile(&mut SplitMix64(seed_b), "prop-b", 1.0);
        let eps = 10f64.powi(-eps_exp);
        let n = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-3);
        let t = Translation3::new(dir[0] / n * reach, dir[1] / n * reach, dir[2] / n * reach);
        let q = Quaternion::new(rot[0], rot[1], rot[2], rot[3]);
        let r = if q.norm() > 1e-3 { UnitQuaternion::from_quaternion(q) } else { UnitQuaternion::identity() };
        let pose = PoseSpec::from_isometry(&Isometry3::from_parts(t, r));
        let (d, _, v, _, _) = single(&a, &b, &pose, eps, None, false).expect("every valid profile builds");
        prop_assert!(
            v.is_empty(),
            "{:?}\nanswer {:?}\nA:\n{}\nB:\n{}",
            v.iter().map(|x| &x.detail).collect::<Vec<_>>(),
            d,
            verify::random_profiles::to_toml(&a),
            verify::random_profiles::to_toml(&b)
        );
    }
}
