//! Bad and hostile input through the `fractal` program: one clear line, the right exit status, nothing written.

use super::*;

#[test]
fn bad_input_is_one_clear_line_and_the_right_exit_status() {
    let dir = scratch("bad_input");
    fs::write(dir.join("a-file"), b"not a directory").unwrap();
    let broken = fixture("broken.fractal");
    let empty_path = dir.join("no-programs");
    fs::create_dir_all(&empty_path).unwrap();
    let cases: Vec<(Vec<&str>, i32, String)> = vec![
        (vec!["render", "missing.fractal"], 1, "cannot read scene file missing.fractal".into()),
        (vec!["render", &broken], 1, format!("{broken}:4:10: `vec3` takes 3 arguments")),
        (vec!["render", "no_such_scene"], 2, "unknown scene `no_such_scene`".into()),
        (vec!["render", "no_such_scene"], 2, "mandelbulb, mandelbulb_bench, mandelbulb_powers, julia".into()),
        (vec!["render", "hello_world", "--size", "0x0"], 2, "image size 0x0 is invalid".into()),
        (vec!["render", "hello_world", "--size", "100000x100000"], 2, "image size 100000x100000 is invalid".into()),
        (vec!["render", "hello_world", "--size", "big"], 2, "expected WIDTHxHEIGHT".into()),
        (vec!["render", "hello_world", "--backend", "vulkan"], 2, "unknown backend `vulkan`".into()),
        (vec!["render", "hello_world", "-o", "a-file/out.png"], 1, "cannot write a-file/out.png".into()),
        (vec!["render", "hello_world", "--frames", "10..2"], 2, "frame range `10..2` is empty".into()),
        (vec!["render", "hello_world", "--frames", "0-9"], 2, "expected START..END".into()),
        (vec!["render", "hello_world", "--frames", "0..9", "--shard", "3/3"], 2, "shard `3/3`".into()),
        (vec!["render", "hello_world", "--frames", "0..9", "--shard", "1"], 2, "expected INDEX/COUNT".into()),
        (vec!["render", "hello_world", "--frames", "0..9", "-o", "out.png"], 2, "a sequence needs a pattern".into()),
        (vec!["render", "hello_world", "-o", "clip.mp4"], 2, "give the frames to encode with --frames".into()),
        (vec!["render", "hello_world", "-o", "out.jpg"], 2, "images are written as .png".into()),
        (vec!["render", "hello_world", "--param", "radius=2"], 2, "no parameter named `radius`".into()),
        (vec!["render", "hello_world", "--time", "inf"], 2, "not finite".into()),
        (vec!["render", "hello_world", "--samples", "0"], 2, "whole number in 1..=256".into()),
        (vec!["view", "hello_world", "--samples", "257"], 2, "got `257`".into()),
        (vec!["accuracy", "hello_world", "--samples", "1,4"], 2, "a list of --samples is for --image".into()),
        (vec!["render", "hello_world", "--progressive", "-1"], 2, "--progressive takes seconds".into()),
        (vec!["bench", "hello_world", "--frames", "0"], 2, "invalid value '0'".into()),
        (vec!["export", "hello_world", "--target", "dxil"], 2, "unknown export target `dxil`".into()),
        (vec!["export", "mandelbrot_zoom", "--camera-path", "--fps", "1e9"], 2, "lower --fps".into()),
        (vec!["export", "hello_world", "--target", "wgsl", "--fps", "24"], 2, "go with --camera-path".into()),
        (vec!["export", "hello_world", "--target", "godot"], 2, "name a directory for them with -o DIR".into()),
        (vec!["mesh", "hello_world", "-o", "out.fbx"], 2, "meshes are written as .glb, .ply, .stl or .obj".into()),
        (vec!["mesh", "hello_world", "-o", "a.ply", "--resolution", "4"], 2, "invalid value '4'".into()),
        (vec!["mesh", "hello_world", "-o", "a.ply", "--bounds", "1,1,1,0,0,0"], 2, "each minimum must be below".into()),
        (vec!["bench", "hello_world", "--csv", "a-file/b.csv"], 1, "cannot write a-file/b.csv".into()),
        (vec!["accuracy", "hello_world", "--backend", "auto"], 2, "accuracy needs one backend".into()),
        (vec!["accuracy", "hello_world", "--report"], 2, "give no scene with it".into()),
        (vec!["accuracy", "--report", "--time", "2"], 2, "give no --time with it".into()),
        (vec!["accuracy", "hello_world", "--truth-step", "0"], 2, "the truth step is a number of footprints".into()),
        (vec!["accuracy", "hello_world", "--truth-factor", "0"], 2, "0 is not in 1..=64".into()),
        (vec!["accuracy", "hello_world", "--csv", "a-file/a.csv"], 1, "cannot write a-file/a.csv".into()),
    ];
    for (args, code, message) in &cases {
        let out = run_in(&dir, args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(*code), "fractal {}: exit status\n{err}", args.join(" "));
        assert!(err.contains(message.as_str()), "fractal {}: expected `{message}` in\n{err}", args.join(" "));
        assert_eq!(err.trim().lines().count(), 1, "fractal {}: not one line:\n{err}", args.join(" "));
        assert!(!err.contains("panicked"), "{err}");
    }
    // Grammar errors: clap's own message and usage lines, status 2.
    let grammar: [(&[&str], &str); 2] = [
        (&["export", "hello_world"], "--target <TARGET>"),
        (&["export", "hello_world", "--target", "wgsl", "--camera-path"], "cannot be used with"),
    ];
    for (args, message) in grammar {
        let out = run_in(&dir, args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "fractal {}: exit status\n{err}", args.join(" "));
        assert!(err.contains(message), "fractal {}: expected `{message}` in\n{err}", args.join(" "));
        assert!(!err.contains("panicked"), "{err}");
    }
    // Missing ffmpeg: an empty PATH, so no ffmpeg can be found.
    let out = Command::new(FRACTAL)
        .args(["render", "hello_world", "--size", "16x16", "--backend", "cpu", "--frames", "0..2", "-o", "clip.mp4"])
        .current_dir(&dir)
        .env("PATH", &empty_path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("ffmpeg was not found on PATH"), "{}", stderr(&out));
    assert!(stderr(&out).contains("%05d.png"), "the error does not suggest a PNG sequence: {}", stderr(&out));
    assert!(!dir.join("clip.mp4").exists() && !dir.join("clip.mp4.partial").exists());
}

/// The hostile inputs: counts, sizes and times a user can type are bounded before any work starts, files are read
/// with a cap, echoed text is escaped and cut, and nothing is written by a refused command.
#[test]
fn hostile_input_is_refused_before_anything_is_written() {
    let dir = scratch("hostile_input");
    fs::create_dir_all(dir.join("existing")).unwrap();
    let long_name = format!("scene({}(1.0))", "x".repeat(1 << 20));
    let files = [
        ("long_name.fractal", long_name.as_str()),
        ("nul.fractal", "scene(sph\0ere(1.0))"),
        ("suffix.fractal", "scene(sphere(300u8))"),
        ("setting.fractal", "scene(sphere(1.0).max_steps(10))"),
        ("sqrt_time.fractal", "scene(sphere(1.0).translate(vec3(sqrt(t - 5.0), 0.0, 0.0)))"),
    ];
    for (name, text) in files {
        fs::write(dir.join(name), text).unwrap();
    }
    let sum = format!("scene(sphere({}))", vec!["0.001"; 2000].join(" + "));
    fs::write(dir.join("sum.fractal"), sum).unwrap();
    let param = fixture("sphere_param.fractal");
    let before = files_in(&dir);
    let cases: Vec<(Vec<&str>, i32, &str)> = vec![
        (vec!["render", "hello_world", "--frames", "0..18446744073709551615"], 2, "at most 1000000 are rendered"),
        (
            vec!["render", "hello_world", "--frames", "0..100", "--fps", "1e-320"],
            2,
            "frame 1 at 1e-320 fps: time inf is outside",
        ),
        (vec!["render", "hello_world", "--frames", "0..10", "--fps", "-30"], 2, "frame rate `-30` must be greater"),
        (vec!["render", "hello_world", "--time", "1e300"], 2, "time 1e300 is outside ±100000 s"),
        (vec!["bench", "hello_world", "--seconds", "1e300"], 2, "must be in (0, 3600] seconds"),
        (vec!["bench", "hello_world", "--frames", "4294967295"], 2, "4294967295 is not in 1..=100000"),
        (vec!["render", "/dev/zero"], 1, "larger than 8 MiB: not a scene file"),
        (vec!["render", "hello_world", "-o", "out/.png"], 2, "the file name before .png is empty"),
        (vec!["render", "hello_world", "-o", "existing"], 2, "existing: it is a directory"),
        (vec!["render", &param, "--param", "radius=1e308"], 2, "= 1e308 is outside its range 0.1..1.5"),
        (vec!["render", "long_name.fractal"], 1, "unknown function `xxxxxxxx"),
        (vec!["render", "nul.fractal"], 1, "`\\u{0}` is not part of the scene language"),
        (vec!["render", "suffix.fractal"], 1, "integer suffixes such as `u8` are not part of the scene language"),
        (vec!["render", "setting.fractal"], 1, "settings such as max_steps go on scene(..)"),
        (vec!["render", "sum.fractal"], 1, "chains more than 256 operators"),
        (vec!["render", "sqrt_time.fractal"], 1, "`sqrt(t - 5.0)` is NaN at time 0"),
    ];
    for (args, code, message) in &cases {
        let out = run_in(&dir, args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(*code), "fractal {}: exit status\n{err}", args.join(" "));
        assert!(err.contains(message), "fractal {}: expected `{message}` in\n{err}", args.join(" "));
        assert_eq!(err.trim().lines().count(), 1, "fractal {}: not one line:\n{err}", args.join(" "));
        assert!(err.len() < 400, "fractal {}: the message is {} bytes", args.join(" "), err.len());
        assert!(!err.contains('\0') && !err.contains("panicked"), "{err}");
        assert_eq!(files_in(&dir), before, "fractal {} wrote something", args.join(" "));
    }
}
