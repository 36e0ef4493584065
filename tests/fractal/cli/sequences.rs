//! Sequences through the `fractal` program: resuming, shards, video and the AOVs beside each image.

use super::*;

#[test]
fn an_interrupted_sequence_resumes_without_losing_or_rewriting_frames() {
    let dir = scratch("resume");
    let scene = fixture("moving_sphere.fractal");
    let args = ["render", &scene, "--size", "32x32", "--backend", "cpu", "--frames", "0..6", "--fps", "3", "-o"];
    let run = || run_in(&dir, &[&args[..], &["out/%05d.png"]].concat());
    assert_ok(&run());
    let all: BTreeSet<String> = (0..6).map(|f| format!("{f:05}.png")).collect();
    assert_eq!(frames_in(&dir.join("out")), all);
    assert!(dir.join("out/sequence.png.settings").exists(), "the sequence's settings are not recorded");
    let frame = |f: u32| dir.join(format!("out/{f:05}.png"));
    let first: Vec<Image> = (0..6).map(|f| read_png(&frame(f)).unwrap()).collect();
    assert!(first[0] != first[5], "time does not advance the scene");

    // A crashed run: frames 2 and 4 never finished, one of them left its partial file, and a stray partial of a
    // finished frame (3) is lying around too.
    fs::remove_file(frame(2)).unwrap();
    fs::remove_file(frame(4)).unwrap();
    fs::write(dir.join("out/00004.png.partial"), b"half a PNG").unwrap();
    fs::write(dir.join("out/00003.png.partial"), b"stale").unwrap();
    let kept = [0, 1, 3, 5].map(|f| (f, modified(&frame(f))));
    std::thread::sleep(std::time::Duration::from_millis(20));

    let out = run();
    assert_ok(&out);
    assert!(stderr(&out).contains("resuming: 4 of 6"), "{}", stderr(&out));
    assert_eq!(frames_in(&dir.join("out")), all, "missing frames or leftover partial files");
    for (f, time) in kept {
        assert_eq!(modified(&frame(f)), time, "complete frame {f} was rewritten");
    }
    for f in 0..6 {
        assert!(read_png(&frame(f)).unwrap() == first[f as usize], "frame {f} differs after the resume");
    }
    // A third run has nothing left to do.
    let out = run();
    assert_ok(&out);
    assert!(stderr(&out).contains("nothing to do"), "{}", stderr(&out));
}

#[test]
fn shards_cover_every_frame_exactly_once() {
    let dir = scratch("shards");
    let shard = |i: &str, out: &str| {
        let args = [
            "render",
            "hello_world",
            "--size",
            "16x16",
            "--backend",
            "cpu",
            "--frames",
            "3..10",
            "--shard",
            i,
            "-o",
            out,
        ];
        assert_ok(&run_in(&dir, &args));
    };
    shard("0/2", "a/%d.png");
    shard("1/2", "b/%d.png");
    let (a, b) = (frames_in(&dir.join("a")), frames_in(&dir.join("b")));
    assert!(a.is_disjoint(&b), "{a:?} and {b:?} overlap");
    let all: BTreeSet<String> = (3..10).map(|f| format!("{f}.png")).collect();
    assert_eq!(a.union(&b).cloned().collect::<BTreeSet<_>>(), all);
    assert_eq!(a, ["3.png", "5.png", "7.png", "9.png"].map(String::from).into());
    // Shards may share one directory.
    shard("1/2", "both/%d.png");
    shard("0/2", "both/%d.png");
    assert_eq!(frames_in(&dir.join("both")), all);
}

#[test]
fn video_goes_through_ffmpeg() {
    let has_ffmpeg = Command::new("ffmpeg").arg("-version").output().is_ok_and(|o| o.status.success());
    if !has_ffmpeg {
        // The test command installs ffmpeg and asks for every external tool; elsewhere the video path is optional.
        assert!(!backends_required(), "ffmpeg is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but not installed");
        eprintln!("note: skipping, ffmpeg is not installed");
        return;
    }
    let dir = scratch("video");
    let out = run_in(
        &dir,
        &["render", "hello_world", "--size", "32x32", "--backend", "cpu", "--frames", "0..4", "-o", "clip.mp4"],
    );
    assert_ok(&out);
    assert!(fs::metadata(dir.join("clip.mp4")).unwrap().len() > 100);
    assert_eq!(files_in(&dir), ["clip.mp4".to_string()].into());
}

/// A finished sequence rerun with other settings is refused, not reported as done with the old frames kept.
#[test]
fn a_sequence_resumed_with_other_settings_is_refused() {
    let dir = scratch("sequence_settings");
    let render = |size: &str| {
        run_in(
            &dir,
            &["render", "hello_world", "--backend", "cpu", "--size", size, "--frames", "0..2", "-o", "f/%02d.png"],
        )
    };
    assert_ok(&render("16x8"));
    let first = fs::read(dir.join("f/00.png")).unwrap();
    assert_ok(&render("16x8"));
    let out = render("8x8");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("2 frames of f/%02d.png were rendered with other settings"), "{}", stderr(&out));
    assert!(stderr(&out).contains("size 16x8"), "{}", stderr(&out));
    assert_eq!(fs::read(dir.join("f/00.png")).unwrap(), first);
}

/// The channels of an OpenEXR file, by name, as f32.
fn exr_channels(path: &Path) -> BTreeMap<String, Vec<f32>> {
    let image =
        exr::prelude::read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = &image.layer_data[0];
    layer.channel_data.list.iter().map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect())).collect()
}

/// `--aov` writes depth (+inf on misses), unit normals (0 on misses) and steps beside the PNG, and they describe the
/// same pixels: a pixel has a depth exactly where it has a normal, and where the PNG is not the background. The CPU
/// writes them from its traces, wgpu from its trace kernel; both describe the same frame.
#[test]
fn aovs_are_written_beside_the_image_and_agree_with_it() {
    let dir = scratch("aov");
    let size = (40u32, 24u32);
    let mut depths = Vec::new();
    for backend in ["cpu", "wgpu"] {
        let out = run_in(
            &dir,
            &[
                "render",
                "hello_world",
                "--backend",
                backend,
                "--size",
                "40x24",
                "--aov",
                "depth,normal,steps",
                // One sample: the AOVs are each pixel's centre ray, and a supersampled silhouette pixel blends the
                // surface with the background.
                "--samples",
                "1",
                "-o",
                &format!("{backend}.png"),
            ],
        );
        if backend == "wgpu" && !out.status.success() {
            let message = stderr(&out);
            assert!(!backends_required(), "wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but failed:\n{message}");
            assert!(
                message.contains("no wgpu device"),
                "wgpu failed for another reason than a missing device:\n{message}"
            );
            eprintln!("note: skipping the wgpu AOVs, no adapter: {message}");
            break;
        }
        assert_ok(&out);
        let png = read_png(&dir.join(format!("{backend}.png"))).unwrap();
        let depth = exr_channels(&dir.join(format!("{backend}.depth.exr")));
        let normal = exr_channels(&dir.join(format!("{backend}.normal.exr")));
        let steps = exr_channels(&dir.join(format!("{backend}.steps.exr")));
        assert_eq!(depth.keys().collect::<Vec<_>>(), ["Z"]);
        assert_eq!(normal.keys().collect::<Vec<_>>(), ["B", "G", "R"]);
        assert_eq!(steps.keys().collect::<Vec<_>>(), ["Y"]);
        let z = &depth["Z"];
        assert_eq!(z.len(), (size.0 * size.1) as usize);
        let background = png.rgba(0, 0).unwrap();
        let mut hits = 0;
        for (i, &t) in z.iter().enumerate() {
            let n = [normal["R"][i], normal["G"][i], normal["B"][i]];
            let length = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            let (x, y) = (i as u32 % size.0, i as u32 / size.0);
            if t.is_finite() {
                hits += 1;
                assert!(t > 0.0 && (length - 1.0).abs() < 1e-3, "{backend} pixel {i}: depth {t}, normal {n:?}");
                assert!(steps["Y"][i] >= 1.0, "{backend} pixel {i} hit in {} steps", steps["Y"][i]);
                assert_ne!(png.rgba(x, y).unwrap(), background, "{backend} pixel {i} hit but shows the background");
            } else {
                assert_eq!((t, length), (f32::INFINITY, 0.0), "{backend} pixel {i}");
                assert_eq!(png.rgba(x, y).unwrap(), background, "{backend} pixel {i} missed but is not the background");
            }
        }
        assert!(hits > 0 && hits < z.len(), "{backend}: {hits} of {} pixels hit", z.len());
        depths.push(z.clone());
    }
    if let [cpu, gpu] = &depths[..] {
        let same = cpu.iter().zip(gpu).filter(|(a, b)| a == b || (*a - *b).abs() <= 1e-3 * a.abs()).count();
        assert!(same as f64 >= 0.99 * cpu.len() as f64, "depths agree on {same} of {} pixels", cpu.len());
    }
}
