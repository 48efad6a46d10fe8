//! Property test (proptest) of the certificate on random freeform profiles: for any profile
//! the generator can draw (closed or open on the axis, 4-40 control points, straight spans,
//! corners, several pieces, pieces touching the axis), any pose of a second solid and any eps
//! in 1e-3..1e-6, the query's answer passes every check of the independent oracle.
//! Run in release mode: `cargo test --release -p verify --test proptest_profiles`.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use proptest::prelude::*;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;
use verify::oracle::{self, check, surface_distance, CheckInput, OracleOptions};
use verify::random_profiles::{random_profile, SplitMix64};

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, failure_persistence: None, ..ProptestConfig::default() })]

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
        let pose = Isometry3::from_parts(t, r);
        let sa = Solid::from_profile(Arc::new(a.clone()), eps).expect("every valid profile builds");
        let sb = Solid::from_profile(Arc::new(b.clone()), eps).expect("every valid profile builds").with_pose(pose);
        let d = distance(&sa, &sb, &QueryOptions::default());
        let (ia, ib) = (oracle::index(&a), oracle::index(&b));
        let o = surface_distance(&ia, &ib, &pose, &OracleOptions::full());
        let v = check(&CheckInput {
            d: &d,
            pose_a: &Isometry3::identity(),
            pose_b: &pose,
            eps_a: sa.tree.eps,
            eps_b: sb.tree.eps,
            tolerance: 0.0,
            oracle: &o,
            a: &ia,
            b: &ib,
        });
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
