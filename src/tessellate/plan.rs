//! Choosing the budget split: the tree's share of `eps` and `n_theta`, for the fewest
//! triangles.
//!
//! The triangle count is `2 n_theta` times the number of meridian segments (less at poles).
//! `n_theta` grows like `1 / sqrt(revolution share)`, the chords of an arc like
//! `1 / sqrt(chord share)` and the leaves like `tree share^(-1/3)`, with weights that depend on
//! the profile (exact circles need few leaves at any eps; wiggly freeform curves many), so the
//! split is searched rather than fixed: [`TREE_FRACTIONS`] times [`REVOLUTION_FRACTIONS`], each
//! candidate costing one meridian build (cheap next to the tree builds). Whatever is chosen,
//! the bound is certified by the construction, not by the search.

use super::meridian::{self, Meridian, MeridianBudget};
use super::revolve::{n_theta_for, revolution_factor, triangle_count, MIN_N_THETA};
use super::{TessellateError, TessellateOptions, ROUNDING_SLACK_REL};
use crate::biarc::{BiarcTree, TreeError};
use crate::profile::Profile;

/// Shares of the budget tried for the biarc tree.
pub const TREE_FRACTIONS: [f64; 4] = [0.05, 0.15, 0.3, 0.5];

/// Shares of what the tree leaves that are tried for the revolution at the largest `rho` (the
/// meridian chords take the rest, and more near the axis).
pub const REVOLUTION_FRACTIONS: [f64; 8] = [0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];

/// How often the meridian is rebuilt with a budget lowered by the excess when vertex moves
/// (joins, poles: at most the profile's join tolerance) push its bound above the target.
const BUDGET_RETRIES: usize = 4;

/// The chosen split and its meridian.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Leaf bound the tree was built with.
    pub tree_eps: f64,
    /// Vertices per ring.
    pub n_theta: usize,
    /// The meridian polyline with its bounds (before rounding slack).
    pub meridian: Meridian,
    /// Rounding slack to add to the meridian's bound.
    pub rounding_slack: f64,
    /// Triangles the mesh will have.
    pub triangles: usize,
}

/// Searches the split of `eps` (or uses the one fixed in `options`) and returns the plan with
/// the fewest triangles whose bound plus rounding slack is at most `eps`.
pub fn plan(
    profile: &Profile,
    eps: f64,
    options: &TessellateOptions,
) -> Result<Plan, TessellateError> {
    validate(eps, options)?;
    let bbox = profile.bounding_box();
    let size = bbox.diagonal();
    let rounding_slack = ROUNDING_SLACK_REL * size;
    let target = eps - rounding_slack;
    if target <= 0.0 {
        return Err(too_small(eps, "the rounding slack alone exceeds eps"));
    }
    // The control box contains the curve, so this bounds rho on the profile.
    let rho_max = bbox.max.x.max(f64::MIN_POSITIVE);
    let fractions: Vec<f64> = match options.tree_fraction {
        Some(f) => vec![f],
        None => TREE_FRACTIONS.to_vec(),
    };
    let mut best: Option<Plan> = None;
    let mut tree_error: Option<TreeError> = None;
    for f in fractions {
        let tree_eps = f * target;
        let tree = match BiarcTree::build(profile, tree_eps) {
            Ok(t) => t,
            Err(e) => {
                tree_error = Some(e);
                continue;
            }
        };
        let mut candidates: Vec<usize> = match options.n_theta {
            Some(n) => vec![n],
            None => REVOLUTION_FRACTIONS
                .iter()
                .map(|g| n_theta_for(g * (target - tree_eps) / rho_max, options.placement))
                .collect(),
        };
        candidates.dedup();
        for n in candidates {
            let tau = revolution_factor(n, options.placement);
            let Some(m) = meridian_within(&tree, profile, size, tau, target, options) else {
                continue;
            };
            let triangles = triangle_count(&m, n);
            if best.as_ref().is_none_or(|b| triangles < b.triangles) {
                best = Some(Plan {
                    tree_eps,
                    n_theta: n,
                    meridian: m,
                    rounding_slack,
                    triangles,
                });
            }
        }
    }
    match (best, tree_error) {
        (Some(p), _) => Ok(p),
        (None, Some(e)) => Err(e.into()),
        (None, None) => Err(too_small(
            eps,
            &match options.n_theta {
                Some(n) => format!(
                    "n_theta = {n} alone deviates up to {:e} from the surface (at rho = {rho_max})",
                    revolution_factor(n, options.placement) * rho_max
                ),
                None => "the tree and revolution shares leave no budget for the chords".into(),
            },
        )),
    }
}

/// The meridian for `tau` whose bound is at most `target`, lowering the per-segment budget by
/// the excess when vertex moves exceed it.
fn meridian_within(
    tree: &BiarcTree,
    profile: &Profile,
    size: f64,
    tau: f64,
    target: f64,
    options: &TessellateOptions,
) -> Option<Meridian> {
    let mut budget = MeridianBudget {
        tau,
        budget: target,
        placement: options.placement,
        max_edge: options.max_meridian_edge,
    };
    for _ in 0..BUDGET_RETRIES {
        let m = meridian::build(tree, profile.kind(), size, &budget)?;
        if m.bound <= target {
            return Some(m);
        }
        budget.budget -= 2.0 * (m.bound - target);
    }
    None
}

fn validate(eps: f64, options: &TessellateOptions) -> Result<(), TessellateError> {
    if !(eps > 0.0 && eps.is_finite()) {
        return Err(TessellateError::InvalidEps(eps));
    }
    let bad = |s: String| Err(TessellateError::InvalidOption(s));
    if let Some(f) = options.tree_fraction {
        if !(f > 0.0 && f < 1.0) {
            return bad(format!("tree_fraction must be in (0, 1), got {f}"));
        }
    }
    if let Some(n) = options.n_theta {
        if n < MIN_N_THETA {
            return bad(format!("n_theta must be at least {MIN_N_THETA}, got {n}"));
        }
    }
    if let Some(m) = options.max_meridian_edge {
        if !(m > 2.0 * eps && m.is_finite()) {
            return bad(format!(
                "max_meridian_edge must be finite and above 2 eps = {:e}, got {m}",
                2.0 * eps
            ));
        }
    }
    Ok(())
}

fn too_small(eps: f64, detail: &str) -> TessellateError {
    TessellateError::BudgetTooSmall {
        eps,
        detail: detail.to_string(),
    }
}
