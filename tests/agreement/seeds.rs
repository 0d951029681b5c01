//! Seed scenes.

use super::*;

#[test]
fn seed_scenes_agree_with_the_oracle() {
    for (name, scene) in seed_scenes() {
        check(&name, &scene, 320, 240, Mesh::Loose, 0.0);
    }
}

#[test]
fn seed_scenes_far_from_the_origin_agree_with_the_oracle() {
    for (name, scene) in seed_scenes() {
        check(
            &format!("{name} far"),
            &translated(&scene, FAR),
            320,
            240,
            Mesh::Loose,
            0.0,
        );
    }
}
