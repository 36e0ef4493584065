//! A scene's camera as a glTF 2.0 camera animation (`fractal export <scene> --camera-path -o camera.gltf`), so shots
//! rendered here line up with a compositor's, Blender's or an engine's.
//!
//! The file holds one node with one perspective camera (`yfov` from the scene's field of view) and, when the camera
//! moves, one animation with a translation and a rotation channel, both LINEAR. It is sampled at every key of a
//! camera path and every 1/fps second between the first and the last; a look-at camera that reads `t` is sampled
//! from 0 to the given duration; a still camera gets no animation. The samples are one buffer, embedded as a base64
//! data URI, so the file stands alone.
//!
//! **Coordinates.** The renderer looks along +z with +x to the right of the image and +y up: a left-handed frame.
//! glTF is right-handed and a glTF camera looks along its −z. The export mirrors z — glTF (x, y, z) = fractal
//! (x, y, −z), the convention every export of geometry must share — so a point and the camera keep their places in
//! the picture. The camera's rotation takes glTF's camera axes (+x right, +y up, −z forward) onto the mirrored right,
//! up and forward.

use base64::Engine as _;
use fractal_dsl::{CameraPlacement, Scene};
use fractal_render::camera::Pose;
use fractal_render::error::CameraError;
use glam::{DMat3, DQuat, DVec3};
use serde_json::json;

/// Near and far clip distances written into the camera (glTF requires znear; a zfar makes it a finite frustum).
const ZNEAR: f64 = 0.001;

/// The span of scene time the camera export covers: a path's first to last key, 0 to `duration` for a look-at
/// camera that reads `t`, and the single moment 0 for a still camera.
pub fn time_span(scene: &Scene, duration: f64) -> (f64, f64) {
    match &scene.camera.placement {
        CameraPlacement::Path { keys, .. } => {
            keys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| (lo.min(k.time), hi.max(k.time)))
        }
        CameraPlacement::LookAt { position, target } => {
            let moves = position.0.iter().chain(target.0.iter()).any(|e| e.uses_time());
            (0.0, if moves { duration } else { 0.0 })
        }
    }
}

/// The times the camera is sampled at, in order: every 1/fps second over [`time_span`], and every key of a path.
pub fn sample_times(scene: &Scene, fps: f64, duration: f64) -> Vec<f64> {
    let (start, end) = time_span(scene, duration);
    let keys = match &scene.camera.placement {
        CameraPlacement::Path { keys, .. } => keys.iter().map(|k| k.time).collect(),
        CameraPlacement::LookAt { .. } => Vec::new(),
    };
    let steps = ((end - start) * fps).floor().max(0.0) as u64;
    let mut times: Vec<f64> = (0..=steps).map(|i| start + i as f64 / fps).chain(keys).collect();
    times.push(end);
    times.sort_by(f64::total_cmp);
    // Samples closer than a microsecond are one sample (a key on a frame time).
    times.dedup_by(|b, a| (*b - *a).abs() < 1e-6);
    times
}

/// The camera of `scene` as a glTF 2.0 document (JSON text), sampled at [`sample_times`].
pub fn camera_gltf(scene: &Scene, fps: f64, duration: f64, aspect_ratio: f64) -> Result<String, CameraError> {
    let times = sample_times(scene, fps, duration);
    let poses: Vec<Pose> =
        times.iter().map(|&t| Pose::from_camera(&scene.camera, t, &|p| p.default)).collect::<Result<_, _>>()?;
    let (translations, rotations): (Vec<[f32; 3]>, Vec<[f32; 4]>) = poses.iter().map(gltf_transform).unzip();

    let camera = json!({
        "type": "perspective",
        "perspective": {
            "yfov": scene.camera.fov_degrees.to_radians(),
            "aspectRatio": aspect_ratio,
            "znear": ZNEAR,
            "zfar": scene.settings.max_distance,
        }
    });
    let mut node = json!({ "name": "fractal camera", "camera": 0 });
    node["translation"] = json!(translations[0]);
    node["rotation"] = json!(rotations[0]);
    let mut document = json!({
        "asset": { "version": "2.0", "generator": concat!("fractal ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [node],
        "cameras": [camera],
    });

    if times.len() > 1 {
        let n = times.len();
        let mut bytes = Vec::with_capacity(n * 4 * 8);
        times.iter().for_each(|&t| bytes.extend_from_slice(&(t as f32).to_le_bytes()));
        translations.iter().flatten().for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
        rotations.iter().flatten().for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
        let (t_len, v_len) = (n * 4, n * 12);
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bytes)
        );
        let (t_min, t_max) = (times[0] as f32, times[n - 1] as f32);
        document["buffers"] = json!([{ "byteLength": bytes.len(), "uri": uri }]);
        document["bufferViews"] = json!([
            { "buffer": 0, "byteOffset": 0, "byteLength": t_len },
            { "buffer": 0, "byteOffset": t_len, "byteLength": v_len },
            { "buffer": 0, "byteOffset": t_len + v_len, "byteLength": n * 16 },
        ]);
        // 5126: FLOAT. Animation inputs must carry min and max.
        document["accessors"] = json!([
            { "bufferView": 0, "componentType": 5126, "count": n, "type": "SCALAR", "min": [t_min], "max": [t_max] },
            { "bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5126, "count": n, "type": "VEC4" },
        ]);
        document["animations"] = json!([{
            "name": "camera path",
            "channels": [
                { "sampler": 0, "target": { "node": 0, "path": "translation" } },
                { "sampler": 1, "target": { "node": 0, "path": "rotation" } },
            ],
            "samplers": [
                { "input": 0, "output": 1, "interpolation": "LINEAR" },
                { "input": 0, "output": 2, "interpolation": "LINEAR" },
            ],
        }]);
    }
    Ok(serde_json::to_string_pretty(&document).expect("a JSON value always serialises"))
}

/// Mirrors z: fractal's left-handed coordinates to glTF's right-handed ones (see the module documentation).
pub fn to_gltf(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.y, -v.z)
}

/// The glTF node translation and unit rotation quaternion (x, y, z, w) of a pose.
fn gltf_transform(pose: &Pose) -> ([f32; 3], [f32; 4]) {
    let (right, up, forward) = pose.basis();
    // glTF camera axes: +x right, +y up, +z backwards (it looks along −z).
    let axes = DMat3::from_cols(to_gltf(right), to_gltf(up), -to_gltf(forward));
    let rotation = DQuat::from_mat3(&axes).normalize();
    (to_gltf(pose.position).as_vec3().to_array(), rotation.as_quat().to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::*;

    #[test]
    fn a_still_camera_has_one_sample_and_a_path_has_its_keys_and_frames() {
        let still = scene(sphere(1.0)).camera(camera([0.0, 1.0, -3.0], [0.0; 3]));
        assert_eq!(sample_times(&still, 30.0, 10.0), [0.0]);
        let path = scene(sphere(1.0)).camera(camera_path([
            key(0.0, [0.0, 0.0, -3.0], [0.0; 3]),
            key(0.25, [1.0, 0.0, -3.0], [0.0; 3]),
            key(1.0, [2.0, 0.0, -3.0], [0.0; 3]),
        ]));
        let times = sample_times(&path, 4.0, 10.0);
        assert_eq!(times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    }

    /// The exported transform puts the camera where the renderer has it, looking the same way, once z is mirrored.
    #[test]
    fn the_transform_maps_gltf_camera_axes_onto_the_mirrored_pose() {
        let pose = Pose::look_at(DVec3::new(1.0, 2.0, -3.0), DVec3::new(0.5, 0.0, 0.0), 50.0).unwrap();
        let (t, r) = gltf_transform(&pose);
        assert_eq!(t, [1.0, 2.0, 3.0]);
        let q = DQuat::from_array(r.map(f64::from));
        let (right, up, forward) = pose.basis();
        let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-6;
        assert!(close(q * DVec3::NEG_Z, to_gltf(forward)));
        assert!(close(q * DVec3::Y, to_gltf(up)));
        assert!(close(q * DVec3::X, to_gltf(right)));
    }
}
