//! The pairs of the OpenCASCADE sweep ([`super::occt`]; `docs/verification.md`, "OpenCASCADE
//! on the true curved surfaces") and the family each belongs to.

use super::shapes::{MORPH_FRAMES, PAPER_MODELS};

/// Which family a pair belongs to (for the timing table).
pub fn family(a: &str, b: &str) -> &'static str {
    if a.starts_with(revdist::models::MORPH_PREFIX) || b.starts_with(revdist::models::MORPH_PREFIX)
    {
        "M_t frames"
    } else if a.ends_with("_ff") || b.ends_with("_ff") {
        "freeform"
    } else {
        "exact"
    }
}

/// The 15 pairs of the paper models, the 15 of their freeform variants, then each M_t frame
/// against each paper model.
pub fn occt_pairs() -> Vec<(String, String)> {
    let mut v = Vec::new();
    for models in [&PAPER_MODELS[..], &revdist::models::FREEFORM_NAMES[..]] {
        for (i, a) in models.iter().enumerate() {
            for b in &models[i..] {
                v.push((a.to_string(), b.to_string()));
            }
        }
    }
    for m in MORPH_FRAMES {
        for b in PAPER_MODELS {
            v.push((m.to_string(), b.to_string()));
        }
    }
    v
}
