//! Memory of the rule set and of the live-pair table per 1,000 colliders,
//! measured with a counting allocator: live bytes after building them,
//! minus live bytes before.
//!
//! Run with `cargo bench --bench memory`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};

use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;

struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);

// SAFETY: forwards every call to `System` and only counts sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE.fetch_add(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn live() -> isize {
    LIVE.load(Ordering::Relaxed)
}

/// `n` dynamic boxes in touching columns of ten on a ground slab.
fn pile(n: usize) -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(200.0, 0.5, 200.0), Some(ground));
    let side = ((n / 10) as f32).sqrt().ceil() as usize;
    let bodies = (0..n)
        .map(|i| {
            let column = i / 10;
            let (x, z) = ((column % side) as f32 * 1.5, (column / side) as f32 * 1.5);
            let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
                x,
                0.5 + (i % 10) as f32 * 1.02,
                z,
            )));
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect();
    (world, bodies)
}

fn main() {
    let n = 1000;
    let (mut world, bodies) = pile(n);

    let before = live();
    let mut rules = CollisionRuleSet::default();
    let group = rules.create_group();
    for (i, &body) in bodies.iter().enumerate() {
        rules.set_personal(body, CollisionRule::Normal);
        rules.set_group(body, Some(group));
        rules.set_specific(body, bodies[(i + 1) % n], CollisionRule::NoResponse);
    }
    let rule_set = live() - before;

    // What the hooks keep (the pair table, the plan, the collider roster),
    // the rule set included: live bytes freed when they are dropped.
    let mut hooks = RuleHooks::new(rules);
    hooks.set_planner(false);
    for _ in 0..10 {
        hooks.step(&mut world);
    }
    let pairs = hooks.pairs(&world).count();
    let before = live();
    drop(hooks);
    let kept = before - live();
    let with_hooks = kept - rule_set;
    let rapier = 0;

    println!("per {n} colliders, each body with a personal rule, a group and one specific entry:");
    println!(
        "  rule set: {} KiB ({} B per collider)",
        rule_set / 1024,
        rule_set / n as isize
    );
    println!(
        "  hooks, every collider hooked, {pairs} live pairs: {} KiB ({} B per collider)",
        (with_hooks - rapier) / 1024,
        (with_hooks - rapier) / n as isize
    );
}
