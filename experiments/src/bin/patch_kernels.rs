//! What the leaf kernel's accuracy costs (paper sections 3.2-3.3): the exact distance of
//! leaf-sized patch pairs (toroidal patches of sweep <= 0.1 rad, as at eps ~1e-4, and
//! straight pieces) slid to a known gap `g` of contact, computed by
//! * the sampled scan (64 samples per circle, root refinement; the first implementation),
//! * circle binormals (degree-8 polynomials, even roots kept) on whole circles,
//! * circle binormals with the Gauss-map restriction of section 3.3.
//!
//! Sliding moves a measured pair of patch points to exactly `g` apart, so the true distance
//! is at most `g`: a kernel answering more than `g` missed the minimum. Writes
//! `patch_kernels.csv` and `patch_kernels.md`: time per pair and misses per gap.
//!
//! Usage: `patch_kernels [--out DIR] [--patch-pairs N] [--seed S]` (default `figures`, 2000
//! patch pairs per gap).

use clap::Parser;
use experiments::args::positive_count;
use experiments::cli::{Out, Seed};
use experiments::driver::{self, DriverResult};
use experiments::table::Table;
use experiments::{Draw, SplitMix};
use nalgebra::{Isometry3, Point2, Translation3};
use revdist::bvh::{Patch, ProfileArc};
use revdist::query::patch_distance::{patch_distance_with, Kernel, PatchOptions};
use std::time::Instant;

/// Gaps to contact.
const GAPS: [f64; 4] = [1e-2, 1e-4, 1e-6, 1e-8];
/// Default seed: the same pairs on every run.
const SEED: u64 = 0x6a05_5e3d;
/// Patch pairs per gap by default.
const DEFAULT_PATCH_PAIRS: usize = 2000;
/// Round-off allowed above the gap: sliding composes a translation with the pose
/// (~1e-16 of the pose size, which is O(1)).
const GAP_SLACK: f64 = 1e-14;

/// A leaf-sized piece in rho > 0: mostly short arcs, some segments (cones, cylinders,
/// annuli).
fn leaf_piece(rng: &mut SplitMix) -> Patch {
    loop {
        let piece = if rng.next_f64() < 0.2 {
            let a = Point2::new(0.05 + rng.next_f64(), rng.next_f64() - 0.5);
            let d = rng.unit_vector().xy().normalize() * 0.05;
            ProfileArc::Segment {
                start: a,
                end: a + d,
            }
        } else {
            ProfileArc::Arc {
                center: Point2::new(0.2 + rng.next_f64(), rng.next_f64() - 0.5),
                radius: 0.05 + 0.5 * rng.next_f64(),
                phi_start: rng.next_f64() * std::f64::consts::TAU,
                sweep: (2.0 * rng.next_f64() - 1.0) * 0.1,
            }
        };
        if piece.start().x > 0.0 && piece.end().x > 0.0 {
            return Patch::new(piece);
        }
    }
}

struct Case {
    a: Patch,
    b: Patch,
    pose: Isometry3<f64>,
    gap: f64,
}

fn cases(n: usize, seed: u64) -> Vec<Case> {
    let mut rng = SplitMix(seed);
    let reference = PatchOptions::default();
    let mut out = Vec::new();
    for &gap in &GAPS {
        let mut made = 0;
        while made < n {
            let (a, b) = (leaf_piece(&mut rng), leaf_piece(&mut rng));
            let t = rng.unit_vector() * (0.2 + 0.5 * rng.next_f64());
            let pose = Isometry3::from_parts(Translation3::from(t), rng.rotation());
            let r = patch_distance_with(&a, &b, &pose, reference);
            if r.distance <= 10.0 * gap {
                continue;
            }
            let shift = (r.point_a - r.point_b) * ((r.distance - gap) / r.distance);
            out.push(Case {
                a,
                b,
                pose: Translation3::from(shift) * pose,
                gap,
            });
            made += 1;
        }
    }
    out
}

struct Row {
    kernel: &'static str,
    gap: f64,
    pairs: usize,
    micros_per_pair: f64,
    misses: usize,
    worst_excess: f64,
}

/// The columns of `patch_kernels.csv` and of the table in `patch_kernels.md`.
fn kernel_table() -> Table<'static, Row> {
    Table::new()
        .csv("kernel", |r: &Row| r.kernel.to_owned())
        .with_markdown_header("kernel")
        .csv("gap", |r| format!("{:e}", r.gap))
        .with_markdown_header("gap")
        .csv("pairs", |r| r.pairs.to_string())
        .with_markdown_header("pairs")
        .csv("us_per_pair", |r| format!("{:.2}", r.micros_per_pair))
        .with_markdown("time per pair (us)", |r| {
            format!("{:.1}", r.micros_per_pair)
        })
        .csv("misses", |r| r.misses.to_string())
        .with_markdown_header("misses")
        .csv("worst_excess", |r| format!("{:e}", r.worst_excess))
        .with_markdown("worst excess", |r| format!("{:.1e}", r.worst_excess))
}

/// What the leaf kernel's accuracy costs: leaf-sized patch pairs (short arcs and segments)
/// slid to a known gap of 1e-2 .. 1e-8 from contact, solved by the sampled scan, by circle
/// binormals, and by binormals with the Gauss-map restriction; per kernel and gap, the time
/// per pair and the misses (answers above the gap, i.e. a missed minimum). Writes
/// patch_kernels.csv and .md.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    /// Patch pairs per gap [default: 2000]
    #[arg(long, value_name = "N", value_parser = positive_count)]
    patch_pairs: Option<usize>,
    #[command(flatten)]
    seed: Seed,
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let out = args.out.dir;
    let (n, seed) = (
        args.patch_pairs.unwrap_or(DEFAULT_PATCH_PAIRS),
        args.seed.or(SEED),
    );
    let all = cases(n, seed);
    let kernels = [
        ("sampled scan", Kernel::Sweep, false),
        ("circle binormals", Kernel::Binormals, false),
        ("binormals + Gauss map", Kernel::Binormals, true),
    ];
    let mut rows = Vec::new();
    for (name, kernel, gauss_restriction) in kernels {
        let opts = PatchOptions {
            kernel,
            gauss_restriction,
            ..PatchOptions::default()
        };
        for &gap in &GAPS {
            let subset: Vec<&Case> = all.iter().filter(|c| c.gap == gap).collect();
            let start = Instant::now();
            let results: Vec<f64> = subset
                .iter()
                .map(|c| patch_distance_with(&c.a, &c.b, &c.pose, opts).distance)
                .collect();
            let micros = start.elapsed().as_secs_f64() * 1e6 / subset.len() as f64;
            let excess: Vec<f64> = results.iter().map(|d| d - gap).collect();
            rows.push(Row {
                kernel: name,
                gap,
                pairs: subset.len(),
                micros_per_pair: micros,
                misses: excess.iter().filter(|&&e| e > GAP_SLACK).count(),
                worst_excess: excess.iter().fold(0.0f64, |m, &e| m.max(e)),
            });
        }
    }
    let table = kernel_table();
    let md = String::from(
        "# Leaf kernels: exact patch distance, time and misses near contact\n\n\
         Leaf-sized patch pairs (arcs of sweep <= 0.1 rad and short segments) slid so that a \
         known pair of points is `gap` apart: the true distance is at most `gap`, and an answer \
         above it is a missed minimum. Written by `target/release/patch_kernels`.\n\n",
    ) + &table.markdown_text(&rows);
    let prov = experiments::provenance::Provenance::collect(
        "patch_kernels (leaf kernels near contact)",
        &[
            ("patch_pairs_per_gap", n.to_string()),
            ("seed", format!("{seed:#x}")),
        ],
    );
    std::fs::write(
        out.join("patch_kernels.csv"),
        prov.csv_preamble() + &table.csv_text(&rows),
    )?;
    std::fs::write(out.join("patch_kernels.md"), md + &prov.markdown_footer())?;
    print!("{}", std::fs::read_to_string(out.join("patch_kernels.md"))?);
    Ok(())
}
