//! A deterministic slice of the `verify queries` campaign (`docs/verification.md`): built-in
//! models, M_t frames and random freeform profiles under every pose kind, plus the fixed regression
//! cases, each query checked against the independent oracle. Run in release mode:
//! `cargo test --release -p verify --test queries_quick` (about 20-40 s on 2 cores).
//! Reproducers of failures go to `target/tmp/verify-queries-quick/`.

use verify::queries::{run, CampaignOptions, DEFAULT_EPS};

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
    };
    let s = run(&opts);
    if let Err(e) = s.write_reproducers() {
        eprintln!("cannot write reproducers: {e}");
    }
    let report = s.report(opts.print_failures);
    assert_eq!(s.violation_count(), 0, "\n{report}");
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
    };
    let s = run(&opts);
    let report = s.report(opts.print_failures);
    assert_eq!(s.violation_count(), 0, "\n{report}");
}
