//! What `fractal export` and `fractal mesh` write: every target, the engine packages, the glTF camera path, meshes.

use super::*;

#[test]
fn export_writes_every_target() {
    let dir = scratch("export");
    for target in ["opencl", "wgsl-kernel", "glsl-kernel", "hlsl-kernel", "msl", "spirv"] {
        let file = format!("kernel.{target}");
        assert_ok(&run_in(&dir, &["export", "sphere_box", "--target", target, "-o", &file]));
        let bytes = fs::read(dir.join(&file)).unwrap();
        assert!(bytes.len() > 200, "{target}: only {} bytes", bytes.len());
        if target == "spirv" {
            assert_eq!(bytes[..4], 0x0723_0203u32.to_le_bytes(), "not a SPIR-V module");
        } else {
            let text = String::from_utf8(bytes).expect("text");
            assert!(text.contains("render") || text.contains("main"), "{target} has no entry point");
        }
    }
    // Text to standard output when there is no -o; file scenes export too.
    let out = run_in(&dir, &["export", &fixture("sphere_param.fractal"), "--target", "wgsl-kernel"]);
    assert_ok(&out);
    assert!(stdout(&out).contains("fn render"), "{}", stdout(&out));
}

/// Engine packages go into the directory -o names; a one-file package (Shadertoy) goes to standard output without
/// it. The packages' contents are checked by `fractal-runtime/tests/tools/engines.rs`.
#[test]
fn export_writes_engine_packages() {
    let dir = scratch("export_engines");
    let expected: [(&str, &[&str]); 8] = [
        ("bevy", &["README.md", "sphere_box.wesl", "sphere_box_material.wesl"]),
        ("godot", &["README.md", "sphere_box.gdshader", "sphere_box.gdshaderinc"]),
        ("unity", &["README.md", "sphere_box.hlsl", "sphere_box.shader"]),
        ("unreal", &["README.md", "sphere_box.ush", "sphere_box_custom_node.hlsl"]),
        ("shadertoy", &["sphere_box.glsl"]),
        ("glsl", &["README.md", "sphere_box.glsl"]),
        ("hlsl", &["README.md", "sphere_box.hlsl"]),
        ("wgsl", &["README.md", "sphere_box.wgsl"]),
    ];
    for (engine, files) in expected {
        let out = run_in(&dir, &["export", "sphere_box", "--target", engine, "-o", engine]);
        assert_ok(&out);
        let written: Vec<String> = files_in(&dir.join(engine)).into_iter().collect();
        assert_eq!(written, files.iter().map(|f| f.to_string()).collect::<Vec<_>>(), "{engine}");
    }
    let out = run_in(&dir, &["export", "sphere_box", "--target", "shadertoy"]);
    assert_ok(&out);
    assert!(stdout(&out).contains("void mainImage("), "{}", stdout(&out));
}

/// `--camera-path` writes a glTF 2.0 file that the `gltf` crate imports (buffers included): one perspective camera
/// with the scene's field of view, and an animation sampled at every key and every 1/fps second, whose first and last
/// translations are the path's first and last positions with z mirrored (glTF is right-handed).
#[test]
fn export_writes_the_camera_path_as_gltf() {
    let dir = scratch("export_camera");
    assert_ok(&run_in(&dir, &["export", "mandelbrot_zoom", "--camera-path", "--fps", "2", "-o", "camera.gltf"]));
    let (document, buffers, _) = gltf::import(dir.join("camera.gltf")).expect("the export imports as glTF");
    let camera = document.cameras().next().expect("a camera");
    let gltf::camera::Projection::Perspective(perspective) = camera.projection() else { panic!("not perspective") };
    assert!((perspective.yfov() - 55f32.to_radians()).abs() < 1e-6);
    assert!((perspective.aspect_ratio().unwrap() - 16.0 / 9.0).abs() < 1e-6);

    let animation = document.animations().next().expect("an animation");
    assert_eq!(animation.channels().count(), 2);
    let mut translations = Vec::new();
    for channel in animation.channels() {
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let times: Vec<f32> = reader.read_inputs().expect("times").collect();
        // Keys every 5 s from 0 to 90, frames every 0.5 s: 181 samples, in order.
        assert_eq!(times.len(), 181);
        assert!(times.windows(2).all(|w| w[0] < w[1]) && times[0] == 0.0 && times[180] == 90.0);
        match reader.read_outputs().expect("values") {
            gltf::animation::util::ReadOutputs::Translations(t) => translations = t.collect(),
            gltf::animation::util::ReadOutputs::Rotations(r) => {
                let unit = |q: [f32; 4]| (q.iter().map(|c| c * c).sum::<f32>() - 1.0).abs() < 1e-5;
                assert!(r.into_f32().all(unit), "rotations are unit quaternions");
            }
            _ => panic!("only translation and rotation are animated"),
        }
    }
    assert_eq!(translations.first(), Some(&[-0.7, 2.4, 0.048]));
    let last = translations.last().unwrap();
    assert!((last[1] - 5.4e-13).abs() < 1e-18 && (last[0] + 0.743_643_9).abs() < 1e-6, "{last:?}");

    // A still camera: the node's transform, no animation.
    assert_ok(&run_in(&dir, &["export", "hello_world", "--camera-path", "-o", "still.gltf"]));
    let (still, _, _) = gltf::import(dir.join("still.gltf")).expect("the export imports as glTF");
    assert_eq!((still.cameras().count(), still.animations().count()), (1, 0));
}

/// `fractal mesh` writes every format; the .glb imports with the `gltf` crate and holds positions, normals, colours
/// and indices of a closed mesh.
#[test]
fn mesh_writes_every_format() {
    let dir = scratch("mesh");
    for ext in ["glb", "ply", "stl", "obj"] {
        let file = format!("sphere.{ext}");
        let out = run_in(&dir, &["mesh", "hello_world", "--resolution", "24", "-o", &file]);
        assert_ok(&out);
        assert!(stderr(&out).contains("closed"), "{}", stderr(&out));
        assert!(fs::metadata(dir.join(&file)).unwrap().len() > 1000, "{ext}: too small");
    }
    let (document, buffers, _) = gltf::import(dir.join("sphere.glb")).expect("the mesh imports as glTF");
    let primitive = document.meshes().next().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().expect("positions").collect();
    let indices: Vec<u32> = reader.read_indices().expect("indices").into_u32().collect();
    assert_eq!(reader.read_normals().expect("normals").count(), positions.len());
    assert_eq!(reader.read_colors(0).expect("colours").into_rgb_f32().count(), positions.len());
    assert!(indices.len().is_multiple_of(3) && indices.iter().all(|&i| (i as usize) < positions.len()));
    // hello_world's sphere of radius 1 at the origin: every vertex within a cell (2/24 of a side) of it.
    let cell = 2.0 / 24.0;
    assert!(positions.iter().all(|p| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < cell));
    let stl = fs::read(dir.join("sphere.stl")).unwrap();
    assert_eq!(stl.len(), 84 + 50 * indices.len() / 3, "STL: one 50-byte record per triangle");

    // A sequence: one file per frame, each of the scene at its own time (julia's constant drifts with t).
    let out = run_in(
        &dir,
        &["mesh", "julia", "--resolution", "16", "--frames", "0..2", "--fps", "0.5", "-o", "seq/%03d.ply"],
    );
    assert_ok(&out);
    assert_eq!(files_in(&dir.join("seq")), ["000.ply".to_string(), "001.ply".to_string()].into());
    assert_ne!(fs::read(dir.join("seq/000.ply")).unwrap(), fs::read(dir.join("seq/001.ply")).unwrap());
}
