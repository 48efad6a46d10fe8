//! The structures timed at one eps: revdist's trees (with their build time and memory) and
//! FCL's certified meshes in every layout that applies.

use super::method::Method;
use super::BUILD_REPEATS;
use crate::baseline_mesh::{Layout, LAYOUT_NAMES};
use crate::shapes::query_tree_bytes;
use crate::stats::median;
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::FclMesh;

/// revdist's solids of one pair at one eps.
pub(super) struct RevLevel {
    pub(super) eps: f64,
    pub(super) a: Solid,
    pub(super) b: Solid,
    pub(super) build_ms: f64,
    pub(super) bytes: usize,
}

/// Builds revdist's solids of a pair at `eps`, timing the median of [`BUILD_REPEATS`] builds.
pub(super) fn rev_level(
    pa: &Arc<Profile>,
    pb: &Arc<Profile>,
    same: bool,
    eps: f64,
) -> Result<RevLevel, Box<dyn std::error::Error>> {
    let build = || -> Result<(Solid, Solid), Box<dyn std::error::Error>> {
        let a = Solid::from_profile(Arc::clone(pa), eps)?;
        let b = if same {
            a.clone()
        } else {
            Solid::from_profile(Arc::clone(pb), eps)?
        };
        Ok((a, b))
    };
    let mut times = Vec::with_capacity(BUILD_REPEATS);
    let mut solids = None;
    for _ in 0..BUILD_REPEATS {
        let t = Instant::now();
        solids = Some(build()?);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let (a, b) = solids.expect("BUILD_REPEATS > 0");
    let bytes = query_tree_bytes(&a.tree) + if same { 0 } else { query_tree_bytes(&b.tree) };
    Ok(RevLevel {
        eps,
        a,
        b,
        build_ms: median(&times),
        bytes,
    })
}

/// One mesh layout of a pair: A's meshes and B's (`None` when B is A).
pub(super) struct LayoutPair {
    pub(super) name: &'static str,
    pub(super) a: Layout,
    pub(super) b: Option<Layout>,
}

/// FCL's meshes of one pair at one eps, in every layout that applies: balanced, and capped
/// when the cap is above the tessellator's minimum for both shapes.
pub(super) struct FclLevel {
    pub(super) eps: f64,
    pub(super) layouts: Vec<LayoutPair>,
}

impl FclLevel {
    pub(super) fn build(
        pa: &Profile,
        pb: &Profile,
        same: bool,
        eps: f64,
    ) -> Result<FclLevel, Box<dyn std::error::Error>> {
        let mut caps = vec![(LAYOUT_NAMES[0], None, None)];
        if let (Some(ca), Some(cb)) = (Layout::capped_edge(pa, eps), Layout::capped_edge(pb, eps)) {
            caps.push((LAYOUT_NAMES[1], Some(ca), Some(cb)));
        }
        let layouts = caps
            .into_iter()
            .map(|(name, ca, cb)| {
                let a = Layout::build(pa, eps, ca)?;
                let b = if same {
                    None
                } else {
                    Some(Layout::build(pb, eps, cb)?)
                };
                Ok(LayoutPair { name, a, b })
            })
            .collect::<Result<_, Box<dyn std::error::Error>>>()?;
        Ok(FclLevel { eps, layouts })
    }
}

impl LayoutPair {
    pub(super) fn b(&self) -> &Layout {
        self.b.as_ref().unwrap_or(&self.a)
    }

    /// Sum of `f` over the distinct meshes.
    pub(super) fn sum(&self, f: impl Fn(&Layout) -> f64) -> f64 {
        f(&self.a) + self.b.as_ref().map_or(0.0, f)
    }

    /// h_a + h_b.
    pub(super) fn h_sum(&self) -> f64 {
        self.a.cm.bound + self.b().cm.bound
    }

    pub(super) fn triangles(&self) -> usize {
        self.sum(|x| x.triangles() as f64) as usize
    }
}

/// The hierarchy of `method` (FCL OBBRSS or RSS) in a layout.
pub(super) fn bvh(l: &Layout, method: Method) -> &FclMesh {
    if method == Method::FclObbrss {
        &l.obbrss
    } else {
        &l.rss
    }
}
