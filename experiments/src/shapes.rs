//! The shapes the experiments use, by name, and facts about them the drivers need.

use revdist::bvh::QueryTree;
use revdist::profile::Profile;

/// The paper's five static models (section 5, Figure 7).
pub const PAPER_MODELS: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];

/// The precisions of the paper's tables and figures.
pub const PAPER_EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];

/// All 15 unordered pairs (with repetition) of the five paper models, in the paper's order
/// (Figure 12): (pawn, pawn), (pawn, cup), ..., (lightmill, lightmill).
pub fn paper_pairs() -> Vec<(&'static str, &'static str)> {
    let mut v = Vec::new();
    for (i, a) in PAPER_MODELS.iter().enumerate() {
        for b in &PAPER_MODELS[i..] {
            v.push((*a, *b));
        }
    }
    v
}

/// A profile by name: `torus` (R 1, r 0.25 as one exact circle, the torus pair of
/// `fcl_bench`) or any name `revdist::models::model` accepts (built-ins and `morph@T`).
pub fn profile(name: &str) -> Result<Profile, Box<dyn std::error::Error>> {
    if name == "torus" {
        use revdist::models::primitives::{arc, deg};
        return Ok(Profile::new(
            "torus",
            vec![arc([1.0, 0.0], 0.25, deg(-90.0), deg(270.0))?],
        )?);
    }
    Ok(revdist::models::model(name)?)
}

/// Diagonal of the profile's bounding box in the (rho, z) plane: the scale of the solid.
pub fn diagonal(p: &Profile) -> f64 {
    let b = p.bounding_box();
    (b.max.x - b.min.x).hypot(b.max.y - b.min.y)
}

/// Mid-height axis point `z` and the radius of a ball about it that holds the solid.
pub fn centre(p: &Profile) -> (f64, f64) {
    let b = p.bounding_box();
    let h = 0.5 * (b.max.y - b.min.y);
    (0.5 * (b.min.y + b.max.y), b.max.x.hypot(h))
}

/// Bytes of the arrays a query touches in a [`QueryTree`] (the revdist side of Table 1).
pub fn query_tree_bytes(t: &QueryTree) -> usize {
    std::mem::size_of_val(t.nodes.as_slice())
        + std::mem::size_of_val(t.patches.as_slice())
        + std::mem::size_of_val(t.chain.as_slice())
        + std::mem::size_of_val(t.node_ends.as_slice())
        + std::mem::size_of_val(t.hulls.as_slice())
        + std::mem::size_of_val(t.upper_hulls.as_slice())
}

/// The solids of a pair at `eps` (built once when both sides name the same profile, or are
/// the same `Arc`) and the time taken to build them, in ms (biarc trees and query trees).
pub fn timed_pair(
    pa: &std::sync::Arc<Profile>,
    pb: &std::sync::Arc<Profile>,
    eps: f64,
) -> Result<(revdist::solid::Solid, revdist::solid::Solid, f64), revdist::biarc::TreeError> {
    let same = std::sync::Arc::ptr_eq(pa, pb) || pa.name() == pb.name();
    let t = std::time::Instant::now();
    let sa = revdist::solid::Solid::from_profile(std::sync::Arc::clone(pa), eps)?;
    let sb = if same {
        sa.clone()
    } else {
        revdist::solid::Solid::from_profile(std::sync::Arc::clone(pb), eps)?
    };
    Ok((sa, sb, t.elapsed().as_secs_f64() * 1e3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fifteen_pairs_and_known_shapes() {
        let pairs = paper_pairs();
        assert_eq!(pairs.len(), 15);
        assert_eq!(pairs[0], ("pawn", "pawn"));
        assert_eq!(pairs[14], ("lightmill", "lightmill"));
        for name in
            PAPER_MODELS
                .iter()
                .chain(&["torus", "morph@0.3", "morph@0.7", "pawn_ff", "table_ff"])
        {
            let p = profile(name).unwrap();
            assert!(diagonal(&p) > 0.0);
            let (_, r) = centre(&p);
            assert!(r > 0.0);
        }
        assert!(profile("teapot").is_err());
    }
}
