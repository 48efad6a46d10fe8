//! One configuration of two chains: the MPFR reference of every piece pair and of the
//! chains, and every piece, node and leaf bound checked against it.

use super::chain::{closest_on_chain, point, Pair};
use super::exact::pair_distance;
use super::nearest::nearest_pairs;
use super::pieces::PieceConfig;
use super::report::{Power, Tally};
use super::Bound;
use nalgebra::{Isometry3, Vector3};
use revdist::bvh::hull::NodeHull;
use revdist::bvh::tree::Leaf;
use revdist::bvh::{Patch, ProfileArc, QueryTree};
use revdist::profile::ProfileKind;
use revdist::query::bound::hull_bound::{hull_bound, hull_bound_until};
use revdist::query::bound::node_pair::{
    node_pair_bound, shell_bound, slab_bound, sphere_bound, torus_bound, BoundKind,
};
use revdist::query::search::leaf::patch_lower::{patch_lower, CoreMemo};
use revdist::query::search::leaf::sectors::sector_lower_bound;
use revdist::query::search::leaf::subdivision::{patch_lower_bound, CERTIFY_MAX_PAIRS};
use revdist::query::search::leaf::LeafPair;
use revdist::query::{patch_distance, query_slack};
use revdist::rng::SplitMix64;

/// Realised pairs of a piece pair evaluated in MPFR (the best of the search).
const EXACT_PAIRS: usize = 3;

/// The reference of one piece pair: the smallest MPFR distance of the realised pairs found,
/// and that pair (chain indices).
struct PairReference {
    distance: f64,
    pair: Pair,
}

fn reference(cfg: &PieceConfig, (i, j): (usize, usize), extra_seeds: &[Pair]) -> PairReference {
    let (a, b) = (&cfg.a[i..=i], &cfg.b[j..=j]);
    let local = |p: &Pair| {
        let mut p = *p;
        p.p.piece = 0;
        p.q.piece = 0;
        Pair::new(a, b, &cfg.pos_ab, p.p, p.q)
    };
    let mut seeds: Vec<Pair> = extra_seeds.iter().map(local).collect();
    if let Some(c) = cfg.contact.filter(|c| c.p.piece == i && c.q.piece == j) {
        seeds.push(local(&c));
    }
    let found = nearest_pairs(a, b, &cfg.pos_ab, &seeds, EXACT_PAIRS);
    let mut best = PairReference {
        distance: f64::INFINITY,
        pair: found[0],
    };
    for p in &found {
        let d = pair_distance(a, b, &cfg.pos_ab, &p.p, &p.q);
        if d < best.distance {
            best = PairReference {
                distance: d,
                pair: *p,
            };
        }
    }
    best.pair.p.piece = i;
    best.pair.q.piece = j;
    best
}

/// Everything a configuration's checks write to.
pub struct Sink<'t> {
    pub tallies: &'t mut [(Bound, Tally)],
    pub power: &'t mut Power,
}

impl Sink<'_> {
    fn tally(&mut self, b: Bound) -> Option<&mut Tally> {
        self.tallies
            .iter_mut()
            .find(|(x, _)| *x == b)
            .map(|(_, t)| t)
    }

    fn record(
        &mut self,
        b: Bound,
        bound: f64,
        reference: f64,
        allowance: f64,
        scale: f64,
        describe: &dyn Fn() -> String,
    ) {
        if let Some(t) = self.tally(b) {
            t.record(bound, reference, allowance, scale, describe);
        }
    }

    fn wants(&self, b: Bound) -> bool {
        self.tallies.iter().any(|(x, _)| *x == b)
    }
}

/// A reproducer of a configuration: every f64 in Rust's round-trip form.
pub fn describe(cfg: &PieceConfig, what: &str) -> String {
    format!(
        "{what}; family {}; a = {:?}; b = {:?}; {}",
        cfg.family.name(),
        cfg.a,
        cfg.b,
        pose_text(&cfg.pos_ab)
    )
}

/// B's pose in a reproducer: quaternion and translation in Rust's round-trip form.
pub fn pose_text(pos: &Isometry3<f64>) -> String {
    let q = pos.rotation.quaternion();
    let t = pos.translation.vector;
    format!(
        "pose quaternion (w, i, j, k) = ({:?}, {:?}, {:?}, {:?}), translation = ({:?}, {:?}, {:?})",
        q.w, q.i, q.j, q.k, t.x, t.y, t.z
    )
}

fn tree(chain: &[ProfileArc]) -> QueryTree {
    QueryTree::from_leaves(vec![Leaf::new(chain.to_vec(), 0.0)], ProfileKind::Closed)
}

/// A level for the `_until` and pruned variants: around the reference (both sides), or none.
fn level(rng: &mut SplitMix64, reference: f64, scale: f64) -> f64 {
    match rng.below(3) {
        0 => f64::INFINITY,
        1 => reference.max(0.0) * rng.range(0.3, 3.0) + 1e-9 * scale,
        _ => reference.max(0.0) + rng.log_range(1e-14, 1e-6) * scale,
    }
}

/// All checks of one configuration. The pieces are first put through [`Patch::new`] (its
/// snap of arc centres within `1e-10 r` of the axis), as the query tree does: the kernels'
/// contract is about snapped patches, and the reference is taken on the same surfaces.
pub fn check(cfg: &PieceConfig, rng: &mut SplitMix64, sink: &mut Sink<'_>) {
    let snap = |c: &[ProfileArc]| c.iter().map(|p| Patch::new(*p).arc).collect::<Vec<_>>();
    let cfg = &PieceConfig {
        a: snap(&cfg.a),
        b: snap(&cfg.b),
        ..cfg.clone()
    };
    let pos: &Isometry3<f64> = &cfg.pos_ab;
    let (ta, tb) = (tree(&cfg.a), tree(&cfg.b));
    let slack = query_slack(&ta, &tb, pos);
    let scale = 1.0
        + pos.translation.vector.norm()
        + ta.nodes[ta.root as usize].bound.center.coords.norm()
        + ta.nodes[ta.root as usize].bound.radius
        + tb.nodes[tb.root as usize].bound.center.coords.norm()
        + tb.nodes[tb.root as usize].bound.radius;
    let mut chain_ref = f64::INFINITY;
    let mut seen = vec![false; sink.tallies.len()];
    let mut mark = |sink: &Sink<'_>, b: Bound| {
        if let Some(k) = sink.tallies.iter().position(|(x, _)| *x == b) {
            seen[k] = true;
        }
    };
    for i in 0..cfg.a.len() {
        for j in 0..cfg.b.len() {
            let (a, b) = (cfg.a[i], cfg.b[j]);
            let (pa, pb) = (Patch { arc: a }, Patch { arc: b });
            let pd = patch_distance(&pa, &pb, pos);
            // The kernel's witnesses, projected onto the two pieces themselves, seed the
            // search (realised pairs: they can only make the reference smaller, the test
            // stricter). Projected onto the whole chain they could land on a neighbouring
            // piece and be lost, leaving the reference up to 1e-3 of the scale above the
            // kernel's value on pieces the search alone did not resolve.
            let (_, mut wp) = closest_on_chain(&cfg.a[i..=i], &pd.point_a);
            let (_, mut wq) = closest_on_chain(&cfg.b[j..=j], &(pos.inverse() * pd.point_b));
            (wp.piece, wq.piece) = (i, j);
            let seeds = [Pair::new(&cfg.a, &cfg.b, pos, wp, wq)];
            let r = reference(cfg, (i, j), &seeds);
            let d = r.distance;
            chain_ref = chain_ref.min(d);
            let what = |name: &str| {
                let c = cfg.clone();
                let name = format!("{name}, piece pair ({i}, {j})");
                move || describe(&c, &name)
            };
            if !pd.sampled {
                sink.power.kernel(d, pd.distance, scale);
                mark(sink, Bound::Kernel);
                sink.record(Bound::Kernel, pd.distance, d, slack, scale, &what("kernel"));
            }
            let (da, db) = (a.bounding_disk(), b.bounding_disk());
            for (bound, value) in [
                (Bound::Sphere, sphere_bound(&da, &db, pos)),
                (Bound::Torus, torus_bound(&da, &db, pos)),
                (Bound::Shell, shell_bound(&a, &b, pos)),
                (Bound::Slab, slab_bound(&a, &b, pos)),
            ] {
                mark(sink, bound);
                sink.record(bound, value, d, 0.0, scale, &what(bound.name()));
            }
            let pair_dir = point(&cfg.b, &r.pair.q);
            let pair_dir = pos * pair_dir - point(&cfg.a, &r.pair.p);
            let random_dir = rng.direction();
            let dir = if pair_dir.norm() > 0.0 && rng.chance(0.7) {
                pair_dir
            } else {
                random_dir
            };
            if sink.wants(Bound::Hull) {
                mark(sink, Bound::Hull);
                for n in [dir, random_dir] {
                    let h = hull_bound(&a, &b, pos, &n);
                    sink.record(Bound::Hull, h, d, 0.0, scale, &what("hull"));
                }
                let lvl = level(rng, d, scale);
                let h = hull_bound_until(&a, &b, pos, &dir, lvl);
                sink.record(
                    Bound::Hull,
                    h,
                    d,
                    0.0,
                    scale,
                    &what(&format!("hull_until {lvl:?}")),
                );
            }
            if sink.wants(Bound::PatchLower) {
                mark(sink, Bound::PatchLower);
                let prune = level(rng, d, scale);
                let precision = if rng.chance(0.5) {
                    0.0
                } else {
                    rng.log_range(1e-9, 1e-3) * scale
                };
                let l = patch_lower(&pa, &pb, pos, prune, precision, &mut CoreMemo::default());
                sink.record(
                    Bound::PatchLower,
                    l.lower,
                    d,
                    0.0,
                    scale,
                    &what(&format!(
                        "patch_lower prune {prune:?} precision {precision:?}"
                    )),
                );
            }
            if sink.wants(Bound::Subdivision) {
                mark(sink, Bound::Subdivision);
                let precision = rng.log_range(1e-12, 1e-6) * scale;
                let n: Option<Vector3<f64>> = rng.chance(0.5).then_some(dir);
                let l = patch_lower_bound(&a, &b, pos, d, precision, CERTIFY_MAX_PAIRS, n.as_ref());
                sink.record(
                    Bound::Subdivision,
                    l,
                    d,
                    0.0,
                    scale,
                    &what(&format!(
                        "patch_lower_bound precision {precision:?} dir {n:?}"
                    )),
                );
            }
            if sink.wants(Bound::Sectors) {
                mark(sink, Bound::Sectors);
                let precision = rng.log_range(1e-12, 1e-6) * scale;
                let n: Option<Vector3<f64>> = rng.chance(0.5).then_some(dir);
                let l =
                    sector_lower_bound(&a, &b, pos, d, precision, CERTIFY_MAX_PAIRS, n.as_ref());
                sink.record(
                    Bound::Sectors,
                    l,
                    d,
                    0.0,
                    scale,
                    &what(&format!(
                        "sector_lower_bound precision {precision:?} dir {n:?}"
                    )),
                );
            }
        }
    }
    if let Some(c) = cfg.contact {
        let g = c.d;
        if g >= 0.0 {
            sink.power.contacts += 1;
            if chain_ref <= g + 1e-12 * scale {
                sink.power.contacts_met += 1;
            }
        }
    }
    let whole = |name: &'static str| {
        let c = cfg.clone();
        move || describe(&c, name)
    };
    let (la, lb) = (&ta.nodes[ta.root as usize], &tb.nodes[tb.root as usize]);
    if sink.wants(Bound::NodeSphere) {
        mark(sink, Bound::NodeSphere);
        let v = node_pair_bound(
            &la.bound,
            &lb.bound,
            pos,
            BoundKind::Sphere,
            f64::INFINITY,
            None,
        );
        sink.record(
            Bound::NodeSphere,
            v,
            chain_ref,
            0.0,
            scale,
            &whole("node sphere"),
        );
    }
    if sink.wants(Bound::NodeTorus) {
        mark(sink, Bound::NodeTorus);
        let hulls = (cfg.a.len() <= 2 && cfg.b.len() <= 2)
            .then(|| {
                Some((
                    NodeHull::of_pieces(&cfg.a, 0.0)?,
                    NodeHull::of_pieces(&cfg.b, 0.0)?,
                ))
            })
            .flatten();
        let prune = level(rng, chain_ref, scale);
        let v = node_pair_bound(
            &la.bound,
            &lb.bound,
            pos,
            BoundKind::Torus,
            prune,
            hulls.as_ref().map(|(x, y)| (x, y)),
        );
        sink.record(
            Bound::NodeTorus,
            v,
            chain_ref,
            0.0,
            scale,
            &whole("node torus"),
        );
    }
    if sink.wants(Bound::LeafStages) {
        mark(sink, Bound::LeafStages);
        let prune = level(rng, chain_ref, scale);
        let mut lp = LeafPair::new(&ta, &tb, pos);
        let (ra, rb) = (ta.root, tb.root);
        if let Some(r) = lp.bounds(ra, rb, prune, f64::INFINITY) {
            sink.record(
                Bound::LeafStages,
                r.lower,
                chain_ref,
                slack,
                scale,
                &whole("LeafPair::bounds"),
            );
        }
        let t = lp.tightened_lower(ra, rb, prune);
        sink.record(
            Bound::LeafStages,
            t,
            chain_ref,
            slack,
            scale,
            &whole("LeafPair::tightened_lower"),
        );
        let e = lp.exact(ra, rb, prune);
        sink.record(
            Bound::LeafStages,
            e.lower,
            chain_ref,
            slack,
            scale,
            &whole("LeafPair::exact"),
        );
    }
    for (k, s) in seen.iter().enumerate() {
        if *s {
            sink.tallies[k].1.configs += 1;
        }
    }
}

/// The MPFR reference of one pair of pieces alone (reproducers and tests): the smallest
/// realised distance the search finds between them, evaluated at 256 bits.
pub fn piece_pair_reference(a: &ProfileArc, b: &ProfileArc, pos_ab: &Isometry3<f64>) -> f64 {
    let cfg = PieceConfig {
        family: super::pieces::Family::Generic,
        scale: 1.0,
        a: vec![*a],
        b: vec![*b],
        pos_ab: *pos_ab,
        contact: None,
    };
    reference(&cfg, (0, 0), &[]).distance
}
