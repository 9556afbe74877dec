//! A game's collision table with groups: players, enemies, projectiles and
//! debris. Prints the table as `resolve` decides it and checks each entry,
//! draws it as a matrix (`docs/group_matrix.svg`, as Unity's layer
//! collision matrix shows its layers), then drops debris on a player to show
//! it in a world.
//!
//! `cargo run --example groups`

use std::fmt::Write as _;

use approx::abs_diff_eq;
use rapier_collision_rules::{
    CollisionGroup, CollisionRule, CollisionRuleSet, RuleColor, RuleHooks, RulePalette, Stage,
};
use rapier3d::prelude::*;
// The legend's file names the crate's tree for the dimension `rules`.
use rapier_collision_rules::dim3 as rules;

#[path = "common/legend.rs"]
mod legend;

/// The game's groups and their table: players, enemies, projectiles, debris.
fn game_rules() -> (CollisionRuleSet, [CollisionGroup; 4]) {
    let mut rules = CollisionRuleSet::default();
    let [players, enemies, projectiles, debris] = [(); 4].map(|_| rules.create_group());
    // Players and enemies collide with everything by default (no entry).
    // Projectiles pass through each other; enemies walk through each other.
    rules.set_group_rule(projectiles, projectiles, CollisionRule::NoPair);
    rules.set_group_rule(enemies, enemies, CollisionRule::NoResponse);
    // Debris never bothers a player or a projectile, but lands on the world.
    rules.set_group_rules_with_set(debris, &[players, projectiles], CollisionRule::NoPair);
    (rules, [players, enemies, projectiles, debris])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut rules, [players, enemies, projectiles, debris]) = game_rules();

    // One body per group, and a collider on each.
    let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    let names = ["player", "enemy", "projectile", "debris"];
    let mut handles = Vec::new();
    for group in [players, enemies, projectiles, debris] {
        for _ in 0..2 {
            let body = bodies.insert(RigidBodyBuilder::dynamic());
            rules.set_group(body, Some(group));
            handles.push(colliders.insert_with_parent(
                ColliderBuilder::ball(0.5),
                body,
                &mut bodies,
            ));
        }
    }
    use CollisionRule::*;
    let expected = [
        [Normal, Normal, Normal, NoPair],
        [Normal, NoResponse, Normal, Normal],
        [Normal, Normal, NoPair, NoPair],
        [NoPair, Normal, NoPair, Normal],
    ];
    // Each cell of the matrix: the rule `resolve` gives, and the later stage
    // that decided it if the table has no entry for the two groups.
    let groups = [players, enemies, projectiles, debris];
    let mut cells = Vec::new();
    print!("{:>12}", "");
    for name in names {
        print!("{name:>12}");
    }
    println!();
    for (i, row) in expected.iter().enumerate() {
        print!("{:>12}", names[i]);
        for (j, &want) in row.iter().enumerate() {
            // The second member of group i against the first of group j.
            let got = rules.resolve(&bodies, &colliders, handles[2 * i + 1], handles[2 * j]);
            print!("{:>12}", format!("{got:?}"));
            // No entry (`Defer`): say which later stage decided.
            let later = (rules.group_rule(groups[i], groups[j]) == Defer).then(|| {
                let why = rules.explain(&bodies, &colliders, handles[2 * i + 1], handles[2 * j]);
                match why.stage {
                    Stage::Specific => "specific rule",
                    Stage::Personal => "personal rule",
                    Stage::Group => "group table",
                    Stage::Default => "default",
                }
            });
            cells.push((i, j, got, later));
            if got != want {
                return Err(
                    format!("{} vs {}: {got:?}, expected {want:?}", names[i], names[j]).into(),
                );
            }
        }
        println!();
    }

    // The table as a picture, regenerated with the README's other pictures.
    let svg = matrix(&["players", "enemies", "projectiles", "debris"], &cells);
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("target/groups");
    std::fs::create_dir_all(&out)?;
    std::fs::write(out.join("group_matrix.svg"), &svg)?;
    let docs = root.join("docs");
    std::fs::create_dir_all(&docs)?;
    std::fs::write(docs.join("group_matrix.svg"), &svg)?;
    println!(
        "the matrix: {} (and docs/group_matrix.svg)",
        out.join("group_matrix.svg").display()
    );

    // In a world: debris falls through a standing player onto the ground. A
    // rule set belongs to one world (its rules are keyed by the world's
    // handles), so the world gets its own.
    let (mut rules, [players, _, _, debris]) = game_rules();
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    let player =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    world.insert_collider(ColliderBuilder::capsule_y(0.5, 0.5), Some(player));
    let rock =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 4.0, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.2, 0.2, 0.2), Some(rock));
    rules.set_group(player, Some(players));
    rules.set_group(rock, Some(debris));
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..120 {
        hooks.step(&mut world);
    }
    let (py, ry) = (
        world.bodies[player].translation().y,
        world.bodies[rock].translation().y,
    );
    println!("after 2 s: the player stands at y = {py:.2}, the rock lies at y = {ry:.2}");
    if !abs_diff_eq!(py, 1.0, epsilon = 0.05) || !abs_diff_eq!(ry, 0.2, epsilon = 0.05) {
        return Err("the debris did not fall through the player onto the ground".into());
    }
    println!(
        "{} of {} colliders needed the hook",
        hooks.stats().hooked_colliders,
        world.colliders.len()
    );
    Ok(())
}

/// Black or white, whichever reads better on `fill`.
fn ink_on(fill: RuleColor) -> &'static str {
    let luminance =
        0.2126 * f32::from(fill.0) + 0.7152 * f32::from(fill.1) + 0.0722 * f32::from(fill.2);
    if luminance < 140.0 {
        "#ffffff"
    } else {
        "#111111"
    }
}

/// The group table as a matrix, one row and one column per group, each cell
/// in the palette's colour of the rule a collider of the row's group gets
/// against one of the column's. The full square is drawn (not Unity's
/// triangle): the table is symmetric, and a row reads as everything one
/// group does. A cell without a table entry names the later stage its rule
/// came from (here the default).
fn matrix(names: &[&str], cells: &[(usize, usize, CollisionRule, Option<&str>)]) -> String {
    let palette = RulePalette::default();
    let (cell_w, cell_h, left, top) = (150.0, 60.0, 130.0, 92.0);
    let n = names.len() as f32;
    let (width, height) = (left + n * cell_w + 30.0, top + n * cell_h + 100.0);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="DejaVu Sans, Helvetica, Arial, sans-serif">"#
    );
    let _ = writeln!(
        svg,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    let _ = writeln!(
        svg,
        r##"<text x="16" y="26" font-size="16" font-weight="bold" fill="#111111">The group table as a matrix</text>
<text x="16" y="46" font-size="12" fill="#444444">each cell: the rule resolve gives a collider of the row's group against one of the column's</text>"##
    );
    for (k, name) in names.iter().enumerate() {
        let k = k as f32;
        let _ = writeln!(
            svg,
            r##"<text x="{}" y="{}" font-size="13" font-weight="bold" text-anchor="middle" fill="#111111">{name}</text>"##,
            left + (k + 0.5) * cell_w,
            top - 10.0
        );
        let _ = writeln!(
            svg,
            r##"<text x="{}" y="{}" font-size="13" font-weight="bold" text-anchor="end" fill="#111111">{name}</text>"##,
            left - 10.0,
            top + (k + 0.5) * cell_h + 5.0
        );
    }
    for &(i, j, rule, later) in cells {
        let (x, y) = (left + j as f32 * cell_w, top + i as f32 * cell_h);
        let fill = palette.rule(Some(rule));
        let ink = ink_on(fill);
        let _ = writeln!(
            svg,
            r##"<rect x="{x}" y="{y}" width="{cell_w}" height="{cell_h}" fill="{}" stroke="#ffffff" stroke-width="2"/>"##,
            fill.hex()
        );
        let (cx, cy) = (x + cell_w / 2.0, y + cell_h / 2.0);
        if let Some(stage) = later {
            let _ = writeln!(
                svg,
                r#"<text x="{cx}" y="{}" font-size="14" font-weight="bold" text-anchor="middle" fill="{ink}">{rule:?} ({stage})</text><text x="{cx}" y="{}" font-size="11" text-anchor="middle" fill="{ink}">no table entry</text>"#,
                cy - 2.0,
                cy + 14.0
            );
        } else {
            let _ = writeln!(
                svg,
                r#"<text x="{cx}" y="{}" font-size="14" font-weight="bold" text-anchor="middle" fill="{ink}">{rule:?}</text>"#,
                cy + 5.0
            );
        }
    }
    // The legend: the palette's rule colours.
    let y = top + n * cell_h + 36.0;
    legend::rule_swatches(&mut svg, &palette, (16.0, y), "#111111");
    let _ = writeln!(
        svg,
        r##"<text x="16" y="{}" font-size="12" fill="#444444">"(default)": the table has no entry for the two groups (group_rule gives Defer),</text>
<text x="16" y="{}" font-size="12" fill="#444444">so the last stage decides: the default rule, Normal.</text>"##,
        y + 26.0,
        y + 44.0
    );
    svg.push_str("</svg>\n");
    svg
}

#[test]
fn the_table_and_the_world_agree() {
    main().expect("the example's own checks");
}
