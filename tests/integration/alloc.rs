//! `resolve` allocates nothing: a counting allocator for this test binary,
//! counting per thread so that tests running in parallel do not interfere.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicIsize, Ordering};

use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
use rapier3d::prelude::*;

pub struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Bytes allocated and not yet freed, all threads together.
static LIVE_BYTES: AtomicIsize = AtomicIsize::new(0);

/// Bytes allocated and not yet freed by the whole test binary.
pub fn live_bytes() -> isize {
    LIVE_BYTES.load(Ordering::Relaxed)
}

// SAFETY: every call is forwarded to `System` unchanged; the counter is a
// const-initialised thread-local `Cell`, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        LIVE_BYTES.fetch_add(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE_BYTES.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        LIVE_BYTES.fetch_add(
            new_size as isize - layout.size() as isize,
            Ordering::Relaxed,
        );
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// How many allocations `f` makes on this thread.
pub fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// Two colliders on chains of `depth` bodies, every node with rules of every kind.
fn deep_scene(
    depth: usize,
) -> (
    RigidBodySet,
    ColliderSet,
    CollisionRuleSet,
    [ColliderHandle; 2],
) {
    let mut bodies = RigidBodySet::new();
    let mut colliders = ColliderSet::new();
    let mut rules = CollisionRuleSet::default();
    let group = rules.create_group();
    let stranger = bodies.insert(RigidBodyBuilder::dynamic());
    let mut leaves = [ColliderHandle::invalid(); 2];
    for leaf in &mut leaves {
        let chain: Vec<_> = (0..depth)
            .map(|_| bodies.insert(RigidBodyBuilder::dynamic()))
            .collect();
        for pair in chain.windows(2) {
            rules.set_parent(pair[0], pair[1]).unwrap();
        }
        *leaf = colliders.insert_with_parent(ColliderBuilder::ball(0.5), chain[0], &mut bodies);
        for &body in &chain {
            rules.set_specific(body, stranger, CollisionRule::NoPair);
            rules.set_group(body, Some(group));
        }
    }
    (bodies, colliders, rules, leaves)
}

#[test]
fn resolve_allocates_nothing_for_chains_up_to_sixteen_nodes() {
    for depth in [1, 2, 4, 8, 15] {
        let (bodies, colliders, rules, [a, b]) = deep_scene(depth);
        let mut rule = CollisionRule::Defer;
        let count = allocations(|| {
            rule = rules.resolve(&bodies, &colliders, a, b);
            let _ = rules.explain(&bodies, &colliders, b, a);
        });
        assert_eq!(rule, CollisionRule::Normal);
        assert_eq!(count, 0, "resolve at depth {depth} allocated {count} times");
    }
}

#[test]
fn the_counter_sees_allocations() {
    let count = allocations(|| drop(std::hint::black_box(vec![1u8; 64])));
    assert_eq!(count, 1, "the counting allocator is not in place");
}
