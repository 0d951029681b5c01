//! Closed meshes and shared edges: no holes.

use super::*;

/// Pixel rays of the head-on camera land exactly (to f64 rounding) on the grid points.
fn assert_rays_land_on(spec_name: &str, scene: &Scene, size: u32, step: f64, plane_z: f64) {
    let camera = camera_of(scene, size, size);
    let t = camera.tables::<f64>(1, 1);
    let c = (size as usize - 1) / 2;
    for (j, i) in [(0i64, 0i64), (1, 0), (0, 1), (-3, 5), (8, -8)] {
        let (x, y) = ((c as i64 + j) as usize, (c as i64 - i) as usize);
        let d = t.dir_x1(x, y);
        let s = (camera.eye.z - plane_z) / -d[2];
        let (px, py) = (camera.eye.x + s * d[0], camera.eye.y + s * d[1]);
        let (ex, ey) = (j as f64 * step, i as f64 * step);
        assert!(
            (px - ex).abs() < 1e-12 && (py - ey).abs() < 1e-12,
            "{spec_name}: pixel ({x}, {y}) lands on ({px}, {py}), not ({ex}, {ey})"
        );
    }
}

/// A few generic views of `shapes` from random directions.
fn oblique_views(name: &str, seed: u64, shapes: &[Shape], mesh: Mesh, min_hit: f64) {
    let (w, h) = (96, 72);
    let mut rng = Rng::new(seed);
    for k in 0..3 {
        let mut cam = random_camera(&mut rng);
        cam.look = DVec3::ZERO;
        cam.eye = cam.eye.normalize() * 7.0;
        let scene = build_scene(&format!("{name}.sc"), cam, shapes);
        check_near_and_far(&format!("{name} view {k}"), &scene, w, h, mesh, min_hit);
    }
}

#[test]
fn cube_has_no_holes() {
    let shapes = triangles(&cube(DVec3::ZERO, 2.0));
    // Head-on: the front face (z = 2) has vertices at (+-2, +-2), its diagonal runs through
    // pixel centres, and its outline is shared with the side faces, seen exactly edge-on.
    let step = 0.125;
    let cam = head_on(2.0, 6.0, 41, step);
    let scene = build_scene("cube.sc", cam, &shapes);
    assert_rays_land_on("cube", &scene, 41, step, 2.0);
    check_near_and_far("cube head-on", &scene, 41, 41, Mesh::Convex, 0.5);
    // Looking at a corner: three faces meet at the vertex under the centre pixel.
    let cam = spec(DVec3::splat(6.0), DVec3::splat(2.0), DVec3::Y, 50.0);
    let scene = build_scene("cube-corner.sc", cam, &shapes);
    check_near_and_far("cube corner", &scene, 81, 61, Mesh::Convex, 0.3);
    oblique_views("cube", 11, &shapes, Mesh::Convex, 0.05);
}

#[test]
fn icosphere_has_no_holes() {
    for subdiv in [1, 2] {
        let shapes = triangles(&icosphere(DVec3::ZERO, 2.0, subdiv));
        // Looking straight at vertex 1 of the icosahedron, (1, t, 0) normalised: five (then
        // six) triangles meet under the centre pixel.
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let v = DVec3::new(1.0, t, 0.0).normalize() * 2.0;
        let cam = spec(v * 3.0, v, DVec3::Z, 45.0);
        let scene = build_scene("ico.sc", cam, &shapes);
        check_near_and_far(
            &format!("icosphere/{subdiv} at vertex"),
            &scene,
            81,
            61,
            Mesh::Convex,
            0.2,
        );
        oblique_views(
            &format!("icosphere/{subdiv}"),
            20 + subdiv as u64,
            &shapes,
            Mesh::Convex,
            0.05,
        );
    }
}

#[test]
fn fan_has_no_holes() {
    // Eight triangles around a hub at the origin, rim at integer points: seen head-on the hub
    // is under the centre pixel and the spokes run along pixel rows, columns and diagonals.
    let rim: Vec<DVec3> = [
        (2, 0),
        (2, 2),
        (0, 2),
        (-2, 2),
        (-2, 0),
        (-2, -2),
        (0, -2),
        (2, -2),
    ]
    .iter()
    .map(|&(x, y)| DVec3::new(x as f64, y as f64, 0.0))
    .collect();
    for hub_z in [0.0, 0.5, -0.75] {
        // Flat, the fan covers exactly the square [-2, 2]^2.
        let mesh = if hub_z == 0.0 {
            Mesh::Rect
        } else {
            Mesh::Watertight
        };
        let shapes = triangles(&fan(DVec3::new(0.0, 0.0, hub_z), &rim));
        let step = 0.125;
        let cam = head_on(0.0, 5.0, 41, step);
        let scene = build_scene("fan.sc", cam, &shapes);
        if hub_z == 0.0 {
            assert_rays_land_on("fan", &scene, 41, step, 0.0);
        }
        check_near_and_far(
            &format!("fan hub z {hub_z} head-on"),
            &scene,
            41,
            41,
            mesh,
            0.5,
        );
        oblique_views(&format!("fan hub z {hub_z}"), 30, &shapes, mesh, 0.02);
    }
}

#[test]
fn grid_of_quads_has_no_holes() {
    // 12 x 12 unit squares; step 1/8: a vertex under every 8th pixel, rays along every edge.
    let shapes = grid_quads(12, 0.0);
    let step = 0.125;
    let cam = head_on(0.0, 10.0, 121, step);
    let scene = build_scene("grid.sc", cam, &shapes);
    assert_rays_land_on("grid", &scene, 121, step, 0.0);
    check_near_and_far("grid quads head-on", &scene, 121, 121, Mesh::Rect, 0.6);
    oblique_views("grid quads", 40, &shapes, Mesh::Rect, 0.05);
}

#[test]
fn grid_of_triangles_has_no_holes() {
    // The same grid split along alternating diagonals, which also run through pixel centres.
    let shapes = grid_triangles(12, 0.0);
    let step = 0.125;
    let cam = head_on(0.0, 10.0, 121, step);
    let scene = build_scene("grid-tri.sc", cam, &shapes);
    assert_rays_land_on("grid-tri", &scene, 121, step, 0.0);
    check_near_and_far("grid tris head-on", &scene, 121, 121, Mesh::Rect, 0.6);
    oblique_views("grid tris", 50, &shapes, Mesh::Rect, 0.05);
}
