//! The jobs of a run (family, delta, seed per level), numbered for `--shard`, and their
//! samples computed in parallel.

use super::circle::circle_sample;
use super::solid::solid_sample;
use super::solids::Shapes;
use super::{Config, Error, Sample, CIRCLE_FAMILIES, SOLID_FAMILIES};
use indicatif::ProgressBar;
use rayon::prelude::*;

/// A job: family, perturbation (`None`: delta = 0) and seed.
type Job = (usize, Option<i32>, usize);

/// The jobs of a level with `families` families, numbered in this order (a job's number is
/// its work unit within the level for `--shard`).
fn jobs(families: usize, cfg: &Config) -> Vec<Job> {
    (0..families)
        .flat_map(|fi| {
            cfg.deltas
                .iter()
                .flat_map(move |&d| (0..cfg.seeds).map(move |s| (fi, d, s)))
        })
        .collect()
}

/// Runs `sample(family, delta, seed)` for the jobs ([`jobs`]) whose number `keep` accepts,
/// in parallel, advancing `bar`; each sample with its job's number.
fn run_all<F>(
    families: usize,
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
    sample: F,
) -> Result<Vec<(usize, Sample)>, Error>
where
    F: Fn(usize, Option<i32>, usize) -> Result<Sample, Error> + Sync,
{
    let jobs: Vec<(usize, Job)> = jobs(families, cfg)
        .into_iter()
        .enumerate()
        .filter(|(k, _)| keep(*k))
        .collect();
    if let Some(b) = bar {
        b.set_length(jobs.len() as u64);
    }
    jobs.par_iter()
        .map(|&(k, (fi, d, s))| {
            let r = sample(fi, d, s);
            if let Some(b) = bar {
                b.inc(1);
            }
            r.map(|r| (k, r))
        })
        .collect()
}

/// Every circle-level sample of `cfg`, in parallel.
pub fn circle_samples(cfg: &Config, bar: Option<&ProgressBar>) -> Result<Vec<Sample>, Error> {
    circle_samples_where(cfg, bar, &|_| true).map(without_numbers)
}

/// Every solid-level sample of `cfg`, in parallel.
pub fn solid_samples(cfg: &Config, bar: Option<&ProgressBar>) -> Result<Vec<Sample>, Error> {
    solid_samples_where(cfg, bar, &|_| true).map(without_numbers)
}

fn without_numbers(v: Vec<(usize, Sample)>) -> Vec<Sample> {
    v.into_iter().map(|(_, s)| s).collect()
}

/// Jobs of the circle level ([`circle_samples_where`] numbers them `0..` this).
pub fn circle_jobs(cfg: &Config) -> usize {
    jobs(CIRCLE_FAMILIES.len(), cfg).len()
}

/// Jobs of the solid level.
pub fn solid_jobs(cfg: &Config) -> usize {
    jobs(SOLID_FAMILIES.len(), cfg).len()
}

/// The circle-level samples whose job number `keep` accepts, with their numbers.
pub fn circle_samples_where(
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Vec<(usize, Sample)>, Error> {
    run_all(CIRCLE_FAMILIES.len(), cfg, bar, keep, circle_sample)
}

/// The solid-level samples whose job number `keep` accepts, with their numbers (the shapes
/// are built only when a job is kept).
pub fn solid_samples_where(
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Vec<(usize, Sample)>, Error> {
    if !(0..solid_jobs(cfg)).any(keep) {
        return Ok(Vec::new());
    }
    let shapes = Shapes::new(cfg.eps)?;
    run_all(SOLID_FAMILIES.len(), cfg, bar, keep, |fi, d, s| {
        solid_sample(&shapes, fi, d, s)
    })
}
