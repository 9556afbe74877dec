//! Compound hierarchies from Rapier's joints: the parent map filled from a
//! multibody's tree, or from a root through impulse joints
//! (`docs/semantics.md`, "Decisions where the specification is silent").

use std::collections::VecDeque;

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::body_kinds::dynamic_body;
use super::super::{CollisionRuleSet, RuleError};

impl CollisionRuleSet {
    /// Gives every link of the multibody that holds `body` its parent link's
    /// body as parent in the parent map: a ragdoll built as a multibody gets
    /// its compound hierarchy in one call. Returns how many links were set
    /// (0 if `body` is in no multibody). All or nothing: a link the parent
    /// map refuses (a cycle with links already there) is reported and no
    /// link is changed.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRuleSet, RuleError};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let pelvis = world.insert_body(RigidBodyBuilder::dynamic());
    /// let thigh = world.insert_body(RigidBodyBuilder::dynamic());
    /// let shin = world.insert_body(RigidBodyBuilder::dynamic());
    /// let hip = SphericalJointBuilder::new().local_anchor2(Vector::new(0.0, 0.5, 0.0));
    /// world.multibody_joints.insert(pelvis, thigh, hip, true);
    /// world.multibody_joints.insert(thigh, shin, RevoluteJointBuilder::new(Vector::X), true);
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// assert_eq!(rules.set_parents_from_multibody(&world.multibody_joints, shin)?, 2);
    /// assert_eq!((rules.parent(shin), rules.parent(thigh)), (Some(thigh), Some(pelvis)));
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn set_parents_from_multibody(
        &mut self,
        joints: &MultibodyJointSet,
        body: RigidBodyHandle,
    ) -> Result<usize, RuleError> {
        let Some(multibody) = joints
            .rigid_body_link(body)
            .and_then(|link| joints.get_multibody(link.multibody))
        else {
            return Ok(0);
        };
        let links: Vec<(RigidBodyHandle, RigidBodyHandle)> = multibody
            .links()
            .filter_map(|link| {
                let parent = multibody.link(link.parent_id()?)?;
                Some((link.rigid_body_handle(), parent.rigid_body_handle()))
            })
            .collect();
        self.set_parents(&links)
    }

    /// Walks the impulse joints from `root` and gives every dynamic body it
    /// reaches the body it was reached from as parent in the parent map (a
    /// breadth-first tree: a loop of joints is entered once). A body that
    /// is not dynamic (the fixed ground a robot's base is bolted to, a
    /// kinematic carrier) is an anchor, not a link: it gets no parent and
    /// the walk does not go through it, so a ground that holds several
    /// robots does not make them, and everything else on it, one
    /// mechanism. Returns how many links were set. All or nothing, as
    /// [`set_parents_from_multibody`](Self::set_parents_from_multibody).
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRuleSet, RuleError};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let torso = world.insert_body(RigidBodyBuilder::dynamic());
    /// let arm = world.insert_body(RigidBodyBuilder::dynamic());
    /// let hand = world.insert_body(RigidBodyBuilder::dynamic());
    /// let joint = || SphericalJointBuilder::new().local_anchor2(Vector::new(0.0, 0.5, 0.0));
    /// world.impulse_joints.insert(torso, arm, joint(), true);
    /// world.impulse_joints.insert(hand, arm, joint(), true);
    /// // Bolted to the ground, which the walk leaves alone.
    /// world.impulse_joints.insert(ground, torso, FixedJointBuilder::new(), true);
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// let (joints, bodies) = (&world.impulse_joints, &world.bodies);
    /// assert_eq!(rules.set_parents_from_impulse_joints(joints, bodies, torso)?, 2);
    /// assert_eq!((rules.parent(hand), rules.parent(arm)), (Some(arm), Some(torso)));
    /// assert_eq!(rules.parent(ground), None);
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn set_parents_from_impulse_joints(
        &mut self,
        joints: &ImpulseJointSet,
        bodies: &RigidBodySet,
        root: RigidBodyHandle,
    ) -> Result<usize, RuleError> {
        let mut links = Vec::new();
        let mut seen: HashSet<RigidBodyHandle> = [root].into_iter().collect();
        let mut queue = VecDeque::from([root]);
        while let Some(body) = queue.pop_front() {
            for (a, b, _, _) in joints.attached_joints(body) {
                let other = if a == body { b } else { a };
                if seen.insert(other) && dynamic_body(bodies, Some(other)) {
                    links.push((other, body));
                    queue.push_back(other);
                }
            }
        }
        self.set_parents(&links)
    }

    /// Sets every `(child, parent)` link, or none: on a refusal the links
    /// already set are put back as they were.
    fn set_parents(
        &mut self,
        links: &[(RigidBodyHandle, RigidBodyHandle)],
    ) -> Result<usize, RuleError> {
        let mut before = Vec::with_capacity(links.len());
        for &(child, parent) in links {
            let was = self.parent(child);
            if let Err(error) = self.set_parent(child, parent) {
                for (child, was) in before.into_iter().rev() {
                    match was {
                        // It held before: the map was acyclic with it.
                        Some(parent) => {
                            let _ = self.set_parent(child, parent);
                        }
                        None => {
                            self.remove_parent(child);
                        }
                    }
                }
                return Err(error);
            }
            before.push((child, was));
        }
        Ok(links.len())
    }
}
