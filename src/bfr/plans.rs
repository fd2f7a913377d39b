//! Evaluation plans: the limit stencils of one list of coordinates over a
//! cached control hull's points, kept for the other faces that share the
//! hull and are evaluated at the same coordinates — as a mesher evaluates
//! face after face at one tessellation pattern.
//!
//! Faces whose control hulls have the same topology share one refinement
//! and patch table (Bfr's topology cache, `face_surface.rs`). Evaluating
//! such a face at (u, v) finds the same patch and the same basis weights as
//! every other face of the hull does, and its patch points are the same
//! stencils of its own control points. A plan composes both once: for each
//! coordinate, the weights of the hull's control points (and of their
//! derivatives). A face then costs one weighted sum per coordinate.
//!
//! A plan is built when a second face asks for the same coordinates (the
//! first is evaluated directly: a plan costs a few evaluations to build),
//! and plans are kept within a byte budget shared by a factory's hulls;
//! beyond it faces are evaluated directly, as without plans. Regular faces
//! get plans too, one set per patch type and boundary mask: their 16 (or
//! 12) basis weights at each coordinate.

use crate::error::Result;
use crate::patches::{Derivatives, LocationStencils};
use rustc_hash::{FxHashMap, FxHasher};
use std::cell::RefCell;
use std::hash::Hasher;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// The bytes of plans (and of the coordinate lists waiting for one) a
/// factory keeps at most.
pub(super) const PLAN_BUDGET: usize = 256 << 20;

/// The fewest coordinates worth a plan over a control hull (building one
/// costs a few evaluations of the hull's patches).
pub(super) const MIN_HULL_COORDS: usize = 16;

/// The fewest coordinates worth a plan of a regular patch (its basis
/// weights: cheap to build, and saving their evaluation on every face).
pub(super) const MIN_REGULAR_COORDS: usize = 3;

/// One hull's plans (or one kind of regular patch's), by coordinate list
/// and derivatives.
#[derive(Debug)]
pub(super) struct Plans {
    /// Tells these plans apart from every other `Plans` in the process
    /// (in the threads' [`RECENT`] plans).
    id: u64,
    /// The fewest coordinates worth a plan here.
    min_coords: usize,
    entries: Mutex<FxHashMap<u64, Vec<Entry>>>,
    /// The bytes the factory's plans may still take (shared by them all).
    budget: Arc<AtomicUsize>,
}

#[derive(Debug)]
struct Entry {
    derivatives: Derivatives,
    coords: Vec<[f64; 2]>,
    /// Faces that asked before the plan was built.
    uses: u32,
    plan: Option<Arc<LocationStencils>>,
}

/// The source of [`Plans::id`].
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// The plans a thread found kept most recently.
const RECENT_PLANS: usize = 4;

thread_local! {
    /// The plans this thread found kept last, newest first: a mesher asks
    /// for the same few coordinate lists face after face (a face's own
    /// points, all its points for texture coordinates), and finding them
    /// here costs a comparison of the lists instead of a lock and a hash
    /// lookup. Each entry holds its plan (a few kilobytes) until it is
    /// pushed out, also after its `Plans` is dropped (ids are never reused,
    /// so it is never found again).
    static RECENT: RefCell<Vec<Recent>> = const { RefCell::new(Vec::new()) };
}

/// A plan in [`RECENT`].
struct Recent {
    plans: u64,
    derivatives: Derivatives,
    coords: Vec<[f64; 2]>,
    plan: Arc<LocationStencils>,
}

/// A key of `coords` and `derivatives` (equal lists hash alike: the
/// bits of their length and of their first, middle and last coordinates —
/// hashing every coordinate was a long chain of multiplications per face;
/// lists that share the key are told apart by comparing them).
fn key(coords: &[[f64; 2]], derivatives: Derivatives) -> u64 {
    let mut h = FxHasher::default();
    h.write_u8(derivatives as u8);
    h.write_usize(coords.len());
    let n = coords.len();
    for i in [0, n / 2, n.saturating_sub(1)] {
        if let Some([u, v]) = coords.get(i) {
            h.write_u64(u.to_bits());
            h.write_u64(v.to_bits());
        }
    }
    h.finish()
}

/// Whether two coordinate lists are the same bit for bit (compared as
/// bytes: one `memcmp`).
fn same(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    bytemuck::cast_slice::<[f64; 2], u8>(a) == bytemuck::cast_slice::<[f64; 2], u8>(b)
}

/// The bytes a plan holds.
fn plan_bytes(plan: &LocationStencils) -> usize {
    let w = &plan.weights;
    let weights = [&w.point, &w.du, &w.dv, &w.duu, &w.duv, &w.dvv]
        .iter()
        .map(|c| c.len())
        .sum::<usize>();
    8 * weights
        + 4 * (plan.indices.len() + plan.sizes.len() + plan.offsets.len())
        + 8 * plan.locations.len()
}

impl Plans {
    /// No plans yet, within `budget`, for lists of at least `min_coords`
    /// coordinates.
    pub(super) fn new(budget: Arc<AtomicUsize>, min_coords: usize) -> Plans {
        Plans {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            min_coords,
            entries: Mutex::new(FxHashMap::default()),
            budget,
        }
    }

    /// The plan of `coords` with `derivatives` if one is kept, without
    /// counting a use or building one.
    pub(super) fn kept(
        &self,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
    ) -> Option<Arc<LocationStencils>> {
        if coords.len() < self.min_coords {
            return None;
        }
        let is = |r: &Recent| {
            r.plans == self.id && r.derivatives == derivatives && same(&r.coords, coords)
        };
        let recent =
            RECENT.with_borrow(|recent| recent.iter().find(|r| is(r)).map(|r| r.plan.clone()));
        if recent.is_some() {
            return recent;
        }
        let plan = {
            let k = key(coords, derivatives);
            let entries = self
                .entries
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            entries
                .get(&k)?
                .iter()
                .find(|e| e.derivatives == derivatives && same(&e.coords, coords))?
                .plan
                .clone()?
        };
        RECENT.with_borrow_mut(|recent| {
            // The oldest entry's room reused, the new one first (nothing
            // kept when there is no memory for it).
            let mut entry = match recent.pop() {
                Some(oldest) if recent.len() + 1 == RECENT_PLANS => oldest,
                other => {
                    recent.extend(other);
                    if recent.try_reserve(1).is_err() {
                        return;
                    }
                    Recent {
                        plans: self.id,
                        derivatives,
                        coords: Vec::new(),
                        plan: plan.clone(),
                    }
                }
            };
            entry.coords.clear();
            if entry.coords.try_reserve(coords.len()).is_err() {
                return;
            }
            entry.coords.extend_from_slice(coords);
            entry.plans = self.id;
            entry.derivatives = derivatives;
            entry.plan = plan.clone();
            recent.insert(0, entry);
        });
        Some(plan)
    }

    /// The plan of `coords` with `derivatives`, when one is kept or worth
    /// building now (`build` builds it, validating the coordinates):
    /// `None` for the first face to ask, for short lists, and once the
    /// budget is spent.
    pub(super) fn get(
        &self,
        coords: &[[f64; 2]],
        derivatives: Derivatives,
        build: impl FnOnce() -> Result<LocationStencils>,
    ) -> Result<Option<Arc<LocationStencils>>> {
        let budget = &*self.budget;
        if coords.len() < self.min_coords {
            return Ok(None);
        }
        let k = key(coords, derivatives);
        {
            let mut entries = self
                .entries
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            let list = entries.entry(k).or_default();
            match list
                .iter_mut()
                .find(|e| e.derivatives == derivatives && same(&e.coords, coords))
            {
                Some(Entry {
                    plan: Some(plan), ..
                }) => return Ok(Some(plan.clone())),
                Some(entry) => {
                    entry.uses = entry.uses.saturating_add(1);
                    if entry.uses < 2 {
                        return Ok(None);
                    }
                }
                None => {
                    if take(budget, 16 * coords.len()) {
                        list.push(Entry {
                            derivatives,
                            coords: coords.to_vec(),
                            uses: 1,
                            plan: None,
                        });
                    }
                    return Ok(None);
                }
            }
        }
        // Built outside the lock (other faces of the hull go on directly
        // meanwhile); the first plan stored wins.
        let plan = build()?;
        if plan.locations.len() != coords.len() || !take(budget, plan_bytes(&plan)) {
            return Ok(None);
        }
        let plan = Arc::new(plan);
        let mut entries = self
            .entries
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(entry) = entries.get_mut(&k).and_then(|list| {
            list.iter_mut()
                .find(|e| e.derivatives == derivatives && same(&e.coords, coords))
        }) {
            match &entry.plan {
                Some(kept) => {
                    budget.fetch_add(plan_bytes(&plan), Ordering::Relaxed);
                    return Ok(Some(kept.clone()));
                }
                None => entry.plan = Some(plan.clone()),
            }
        }
        Ok(Some(plan))
    }
}

/// Takes `bytes` from `budget` if it has them.
fn take(budget: &AtomicUsize, bytes: usize) -> bool {
    budget
        .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |left| {
            left.checked_sub(bytes)
        })
        .is_ok()
}
