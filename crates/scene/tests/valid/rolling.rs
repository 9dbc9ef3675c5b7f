//! Rolling: a `roll` path expands into transform keys that keep the ball on its path and
//! turning rigidly, without slipping; the expansion reads back and holds under a closed
//! shutter.

use reyes_scene::Transform;

use crate::traced::TRACED;
use crate::{ok, reads_back};

/// An `f32` vector of the scene in `f64`.
fn dvec(a: &[f32; 3]) -> glam::DVec3 {
    glam::DVec3::new(f64::from(a[0]), f64::from(a[1]), f64::from(a[2]))
}

/// The object-to-world matrix of a transform list, as the dicer builds it (first item first),
/// in `f64`.
fn matrix(list: &[Transform]) -> glam::DMat4 {
    use glam::DMat4;
    list.iter().fold(DMat4::IDENTITY, |m, t| {
        let step = match t {
            Transform::Translate(d) => DMat4::from_translation(dvec(d)),
            Transform::Rotate { angle, axis } => {
                DMat4::from_axis_angle(dvec(axis).normalize(), f64::from(*angle).to_radians())
            }
            Transform::Scale(s) => DMat4::from_scale(dvec(s)),
            Transform::Matrix(rows) => {
                DMat4::from_cols_array_2d(&rows.map(|r| r.map(f64::from))).transpose()
            }
        };
        step * m
    })
}

/// A ball of radius 0.5 on a plane tilted 30 degrees about x, rolling along an L-shaped path
/// (two segments at right angles, then back), with a rest orientation.
fn rolling(steps: u32) -> String {
    let tilt = 30f64.to_radians();
    let up = [0.0, tilt.cos(), -tilt.sin()];
    let across = [1.0, 0.0, 0.0];
    let along = [0.0, tilt.sin(), tilt.cos()];
    let at = |a: f64, b: f64| {
        let p: Vec<String> = (0..3)
            .map(|k| format!("{:?}", (0.5 * up[k] + a * across[k] + b * along[k]) as f32))
            .collect();
        format!("({})", p.join(", "))
    };
    format!(
        "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 2.0, -10.0), look_at: (0.0, 0.0, 0.0)),
         objects: [(name: \"ball\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5)),
           transform: [Rotate(angle: 70.0, axis: (1.0, 2.0, 0.5)), Scale((1.0, 1.0, 1.0))],
           roll: Some((radius: 0.5, up: ({:?}, {:?}, {:?}), steps: {steps},
             path: [(time: 0.0, position: {}), (time: 0.4, position: {}), (time: 0.7, position: {}),
                    (time: 1.0, position: {})])))])",
        up[0] as f32,
        up[1] as f32,
        up[2] as f32,
        at(0.0, 0.0),
        at(1.2, 0.0),
        at(1.2, 0.9),
        at(0.3, 0.3),
    )
}

#[test]
fn rolling_expands_into_transform_keys() {
    let scene = ok(&rolling(4));
    let ball = &scene.objects[0];
    let roll = ball.roll.as_ref().unwrap_or_else(|| panic!("the roll is kept"));
    // One key at the start and `steps` per segment, times strictly increasing.
    assert_eq!(ball.motion.len(), 1 + 3 * 4);
    let times: Vec<f32> = ball.motion.iter().map(|k| k.time).collect();
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    assert_eq!((times[0], times[4], times[8], times[12]), (0.0, 0.4, 0.7, 1.0));
    assert!((times[2] - 0.2).abs() < 1e-6);
    for (k, key) in ball.motion.iter().enumerate() {
        // The rest orientation comes first, the centre last.
        assert_eq!(key.transform[..2], ball.transform[..], "key {k}");
        assert!(matches!(key.transform.last(), Some(Transform::Translate(_))), "key {k}");
        // At most: rest, finished turns, current turn, translation.
        assert!(key.transform.len() <= ball.transform.len() + 3, "key {k}");
        let m = matrix(&key.transform);
        // The ball's centre (the object's origin) is on the path ...
        let segment = (k.saturating_sub(1) / 4).min(2);
        let f = if k == 0 { 0.0 } else { ((k - 1) % 4 + 1) as f64 / 4.0 };
        let p = |i: usize| dvec(&roll.path[i].position);
        let expected = p(segment) + (p(segment + 1) - p(segment)) * f;
        let centre = m.transform_point3(glam::DVec3::ZERO);
        assert!((centre - expected).length() < 1e-5, "key {k}: {centre} vs {expected}");
        // ... and the ball turns rigidly about it.
        for q in [glam::DVec3::X, glam::DVec3::new(0.3, -0.2, 0.4)] {
            let rest = matrix(&ball.transform).transform_point3(q).length();
            assert!(((m.transform_point3(q) - centre).length() - rest).abs() < 1e-5);
        }
    }
    // The first segment (2.4 radii) turns the ball 137.5 degrees in all.
    let turned = |k: usize| {
        ball.motion[k].transform.iter().fold(0.0f32, |sum, t| match t {
            Transform::Rotate { angle, .. } if !ball.transform.contains(t) => sum + angle,
            _ => sum,
        })
    };
    assert!((turned(4) - 137.509_87).abs() < 1e-3, "{}", turned(4));
    assert!((turned(2) - 68.754_93).abs() < 1e-3, "{}", turned(2));
}

/// Rolling without slipping: the material point at the bottom of the ball (the contact
/// point, `centre - radius * up`) is instantaneously at rest. At each key strictly inside a
/// segment, the central difference over the neighbouring keys of where the engines put that
/// material point (the keys' matrices, linearly interpolated) is ~0, while the centre moves;
/// its error is second order in the step angle, so it shrinks as the steps get finer. The
/// opposite turn would move the contact point at twice the centre's speed.
#[test]
fn the_contact_point_does_not_slip() {
    let mut worst = Vec::new();
    for steps in [8, 32, 128] {
        let scene = ok(&rolling(steps));
        let ball = &scene.objects[0];
        let roll = ball.roll.as_ref().unwrap_or_else(|| panic!("no roll"));
        let up = dvec(&roll.up).normalize();
        let radius = f64::from(roll.radius);
        let keys = &ball.motion;
        let mut ratio: f64 = 0.0;
        let mut flipped: f64 = f64::INFINITY;
        let steps = steps as usize;
        for k in 1..keys.len() - 1 {
            if k % steps == 0 {
                continue; // a corner of the path: the velocity changes there
            }
            let (before, here, after) = (
                matrix(&keys[k - 1].transform),
                matrix(&keys[k].transform),
                matrix(&keys[k + 1].transform),
            );
            let dt = f64::from(keys[k + 1].time - keys[k - 1].time);
            let centre = here.transform_point3(glam::DVec3::ZERO);
            let contact = here.inverse().transform_point3(centre - up * radius);
            let velocity =
                (after.transform_point3(contact) - before.transform_point3(contact)) / dt;
            let centre_velocity = (after.transform_point3(glam::DVec3::ZERO)
                - before.transform_point3(glam::DVec3::ZERO))
                / dt;
            assert!(centre_velocity.length() > 1.0, "key {k}: the ball should be moving");
            ratio = ratio.max(velocity.length() / centre_velocity.length());
            // The top of the ball moves at twice the centre's speed, in its direction.
            let top = here.inverse().transform_point3(centre + up * radius);
            let top_velocity = (after.transform_point3(top) - before.transform_point3(top)) / dt;
            assert!(
                (top_velocity - centre_velocity * 2.0).length() < 0.1 * centre_velocity.length()
            );
            // Rolling the other way would drag the contact point at twice the centre's speed.
            flipped =
                flipped.min((centre_velocity * 2.0 - velocity).length() / centre_velocity.length());
        }
        assert!(flipped > 1.5, "steps {steps}: {flipped}");
        worst.push(ratio);
    }
    // Step angles of about 17, 4.3 and 1.1 degrees: relative error ~ angle^2 / 6.
    assert!(worst[0] < 0.02 && worst[1] < 2e-3 && worst[2] < 2e-4, "{worst:?}");
    assert!(worst[0] > worst[1] && worst[1] > worst[2], "{worst:?}");
    eprintln!("contact speed / centre speed at 8, 32, 128 steps per segment: {worst:?}");
}

#[test]
fn a_rolled_scene_reads_back_from_what_ron_writes() {
    let scene = ok(&rolling(8));
    assert!(!scene.objects[0].motion.is_empty() && scene.objects[0].roll.is_some());
    // The written motion is exactly what the roll expands to, so it is accepted with it.
    reads_back(&scene);
    reads_back(&ok(TRACED));
}

/// A closed shutter: every path key at `open`, the ball held at its first position.
#[test]
fn rolling_under_a_closed_shutter() {
    let text = TRACED
        .replacen(
            "look_at: (0.0, 1.0, 0.0))",
            "look_at: (0.0, 1.0, 0.0), shutter: (open: 0.5, close: 0.5))",
            1,
        )
        .replacen("(time: 0.0, position", "(time: 0.5, position", 1)
        .replacen("(time: 1.0, position", "(time: 0.5, position", 1)
        .replacen("motion: [(time: 0.0), (time: 1.0,", "motion: [(time: 0.5), (time: 0.5,", 1);
    let scene = ok(&text);
    let keys = &scene.objects[2].motion;
    assert_eq!(keys.len(), 2);
    assert!(keys.iter().all(|k| k.time == 0.5));
    assert_eq!(keys[0].transform, [Transform::Translate([-1.0, 0.5, 0.0])]);
}
