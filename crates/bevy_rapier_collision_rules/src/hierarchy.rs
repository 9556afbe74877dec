//! The parent map from Bevy's hierarchy: a rigid body's parent is its
//! nearest ancestor entity (through `ChildOf`) that is a rigid body of the
//! same context (`docs/bevy.md`).

use bevy::prelude::*;
use bevy_rapier::prelude::{RapierContextEntityLink, RapierRigidBodyHandle};
use bevy_rapier::rapier::prelude::RigidBodyHandle;

use super::CollisionRules;
use super::ledger::Ledger;

type Bodies<'w, 's> = Query<
    'w,
    's,
    (
        &'static RapierRigidBodyHandle,
        &'static RapierContextEntityLink,
    ),
>;

/// Follows re-parenting, new bodies and context changes (an entity moved
/// to another context gets a new body from bevy_rapier), as the plugin's
/// observers noted them: the bodies at or below each such entity get their
/// parent again. Nothing else is looked at.
pub(crate) fn follow_hierarchy(
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<&mut CollisionRules>,
    bodies: Bodies,
    parents: Query<&ChildOf>,
    children: Query<&Children>,
) {
    if ledger.moved.is_empty() {
        return;
    }
    let roots = std::mem::take(&mut ledger.moved);
    // A body below a moved entity keeps its nearest body ancestor unless
    // there is none between them: the bodies nearest to each root.
    let mut affected = Vec::new();
    let mut stack = Vec::new();
    for root in roots {
        if bodies.contains(root) {
            affected.push(root);
        }
        stack.extend(children.get(root).into_iter().flatten().copied());
        while let Some(entity) = stack.pop() {
            if bodies.contains(entity) {
                affected.push(entity);
            } else {
                stack.extend(children.get(entity).into_iter().flatten().copied());
            }
        }
    }
    affected.sort_unstable();
    affected.dedup();
    let wanted: Vec<_> = affected
        .iter()
        .filter_map(|&body| {
            let (handle, link) = bodies.get(body).ok()?;
            Some((
                link.0,
                handle.0,
                parent_body(&bodies, &parents, body, link.0),
            ))
        })
        .collect();
    // Links that change are cut first, so that no new link meets a stale
    // one and closes a cycle.
    for &(context, child, parent) in &wanted {
        if let Ok(mut rules) = contexts.get_mut(context)
            && rules.rules().parent(child) != parent
        {
            rules.rules_mut().remove_parent(child);
        }
    }
    for &(context, child, parent) in &wanted {
        if let (Ok(mut rules), Some(parent)) = (contexts.get_mut(context), parent)
            && rules.rules().parent(child) != Some(parent)
        {
            // Bevy's hierarchy is a tree and the changed links were cut:
            // no cycle can form, and both bodies exist.
            let linked = rules.rules_mut().set_parent(child, parent);
            debug_assert!(linked.is_ok(), "{linked:?}");
        }
    }
}

/// The nearest ancestor of `entity` that is a rigid body, if it is in
/// `context`.
fn parent_body(
    bodies: &Bodies,
    parents: &Query<&ChildOf>,
    entity: Entity,
    context: Entity,
) -> Option<RigidBodyHandle> {
    let mut at = entity;
    while let Ok(child_of) = parents.get(at) {
        at = child_of.parent();
        if let Ok((handle, link)) = bodies.get(at) {
            return (link.0 == context).then_some(handle.0);
        }
    }
    None
}
