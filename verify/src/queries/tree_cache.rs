//! The trees of a campaign, built once per (shape, eps) and shared by the worker threads.

use super::pool::Shape;
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// A tree built once, shared by the workers that need it.
type TreeSlot = Arc<OnceLock<Result<Solid, String>>>;

/// Trees built so far, shared by the workers: one build per (shape, eps bits).
#[derive(Default)]
pub(super) struct TreeCache {
    map: Mutex<HashMap<(usize, u64), TreeSlot>>,
}

impl TreeCache {
    pub(super) fn get(&self, shapes: &[Shape], k: usize, eps: f64) -> Result<Solid, String> {
        let cell = {
            let mut m = self.map.lock().expect("not poisoned");
            Arc::clone(m.entry((k, eps.to_bits())).or_default())
        };
        cell.get_or_init(|| {
            Solid::from_profile(Arc::clone(&shapes[k].profile), eps)
                .map_err(|e| format!("tree of '{}' at eps {eps:e}: {e}", shapes[k].name))
        })
        .clone()
    }
}
