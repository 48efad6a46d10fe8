//! A deterministic slice of the `verify queries` campaign (`docs/verification.md`): built-in
//! models, M_t frames and random freeform profiles under every pose kind, plus the fixed regression
//! cases, each query checked against the independent oracle. Run in release mode:
//! `cargo test --release -p verify --test queries_quick` (about 20-40 s on 2 cores).
//! Reproducers of failures go to `target/tmp/verify-queries-quick/`.

use verify::queries::{run, CampaignOptions, PoseKind, DEFAULT_EPS};

#[test]
fn quick_slice_has_no_violations() {
    let opts = CampaignOptions {
        count: 250,
        seed: 11,
        eps: DEFAULT_EPS.to_vec(),
        out: std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("verify-queries-quick"),
        threads: 0,
        random_profiles: 30,
        regressions: true,
        print_failures: 20,
        primitives: false,
        convex: false,
        shard: None,
    };
    let s = run(&opts);
    if let Err(e) = s.write_reproducers() {
        eprintln!("cannot write reproducers: {e}");
    }
    let report = s.report(opts.print_failures);
    assert_eq!(s.violation_count(), 0, "\n{report}");
    // The oracle reaches its verdict (`docs/verification.md`, "An oracle that finishes"),
    // and the corner contacts are a real share of the slice.
    assert!(
        s.budget_stops() * 100 <= s.results.len(),
        "{} budget stops in {} cases\n{report}",
        s.budget_stops(),
        s.results.len()
    );
    assert!(s.count_of(PoseKind::Corner) >= 40, "\n{report}");
}

/// Balls and solid tori only: every query takes the closed form of `revdist::query::offset`
/// (one core distance, no traversal), and the oracle, which knows nothing of it, checks each.
#[test]
fn primitive_slice_has_no_violations() {
    let opts = CampaignOptions {
        count: 200,
        seed: 12,
        eps: DEFAULT_EPS.to_vec(),
        out: std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("verify-queries-primitives"),
        threads: 0,
        random_profiles: 10,
        regressions: false,
        print_failures: 20,
        primitives: true,
        convex: false,
        shard: None,
    };
    let s = run(&opts);
    let report = s.report(opts.print_failures);
    assert_eq!(s.violation_count(), 0, "\n{report}");
}

/// Three shards of a small campaign, merged, cover the same cases as one run: every case
/// once, the same counts.
#[test]
fn shards_merge_to_the_whole_campaign() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("verify-queries-shards");
    let opts = |shard: Option<(usize, usize)>, name: &str| CampaignOptions {
        count: 30,
        seed: 13,
        eps: vec![1e-3],
        out: dir.join(name),
        threads: 0,
        random_profiles: 10,
        regressions: true,
        print_failures: 0,
        primitives: false,
        convex: false,
        shard,
    };
    let whole = run(&opts(None, "whole"));
    let mut dirs = Vec::new();
    let mut ids = Vec::new();
    for i in 0..3 {
        let o = opts(Some((i, 3)), &format!("shard{i}"));
        let s = run(&o);
        s.write_summary(13, 30, Some((i, 3))).unwrap();
        ids.extend(s.results.iter().map(|r| (r.case.kind, r.case.id)));
        dirs.push(o.out);
    }
    let mut all: Vec<_> = whole
        .results
        .iter()
        .map(|r| (r.case.kind, r.case.id))
        .collect();
    all.sort();
    ids.sort();
    assert_eq!(ids, all, "every case in exactly one shard");
    let (report, failed) = verify::queries::merge::merge(&dirs).unwrap();
    assert!(
        report.contains(&format!("{} cases, 0 failing", whole.results.len())),
        "{report}"
    );
    assert!(!failed);
    // A missing or repeated shard is an error that names it.
    let e = verify::queries::merge::merge(&dirs[..2]).unwrap_err();
    assert!(e.contains("[2]"), "{e}");
    let e = verify::queries::merge::merge(&[&dirs[0], &dirs[0]]).unwrap_err();
    assert!(e.contains("twice"), "{e}");
}

/// Convex solids only: every query between two of them takes the GJK path of
/// `revdist::query::convex`, and the oracle, which knows nothing of it, checks each.
#[test]
fn convex_slice_has_no_violations() {
    let opts = CampaignOptions {
        count: 300,
        seed: 14,
        eps: DEFAULT_EPS.to_vec(),
        out: std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("verify-queries-convex"),
        threads: 0,
        random_profiles: 10,
        regressions: false,
        print_failures: 20,
        primitives: false,
        convex: true,
        shard: None,
    };
    let s = run(&opts);
    let report = s.report(opts.print_failures);
    assert_eq!(s.violation_count(), 0, "\n{report}");
}
