//! Project automation. `cargo xtask test` is the one test command: it installs the system packages the tests need
//! (when it can), then runs every test of the workspace with the `opencl` feature, and the format and lint checks.

mod house;
mod layers;

use std::process::{exit, Command};

/// Debian packages the tests use: OpenCL on pocl, Vulkan on lavapipe (for wgpu), an X server for the viewer tests,
/// the SPIR-V and GLSL validators for the export tests, ffmpeg for video output.
const PACKAGES: &[&str] = &[
    "pocl-opencl-icd",
    "ocl-icd-libopencl1",
    "ocl-icd-opencl-dev",
    "mesa-vulkan-drivers",
    "libvulkan1",
    "xvfb",
    "xauth",
    "x11-apps",
    "spirv-tools",
    "glslang-tools",
    "ffmpeg",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("test") => test(&args[1..]),
        Some("install") => install(),
        Some("layers") => layers(args.get(1).map(String::as_str)),
        Some("fuzz") => fuzz(args.get(1).map(String::as_str).unwrap_or("1000000")),
        Some("engines") => engines(&args[1..]),
        _ => {
            eprintln!("usage: cargo xtask test [extra cargo test args]   (installs system packages, runs all tests)");
            eprintln!("       cargo xtask install                       (only installs system packages)");
            eprintln!("       cargo xtask layers                        (module cycles in any crate)");
            eprintln!("       cargo xtask layers CRATE/src              (that crate's file dependencies)");
            eprintln!("       cargo xtask fuzz [N]                      (N random scene texts, default 10^6)");
            eprintln!("       cargo xtask engines [--bevy]              (the packages in WebGL2, Godot [and Bevy])");
            exit(2);
        }
    }
}

fn missing_packages() -> Vec<&'static str> {
    PACKAGES
        .iter()
        .copied()
        .filter(|p| {
            !Command::new("dpkg-query")
                .args(["-W", "-f=${Status}", p])
                .output()
                .map(|o| String::from_utf8_lossy(&o.stdout).contains("install ok installed"))
                .unwrap_or(false)
        })
        .collect()
}

fn is_root() -> bool {
    Command::new("id").arg("-u").output().map(|o| String::from_utf8_lossy(&o.stdout).trim() == "0").unwrap_or(false)
}

fn install() {
    if Command::new("dpkg-query").arg("--version").output().is_err() {
        println!(
            "xtask: not a Debian system; install pocl, lavapipe (mesa Vulkan), Xvfb, spirv-tools and glslang yourself"
        );
        return;
    }
    let missing = missing_packages();
    if missing.is_empty() {
        println!("xtask: system packages present");
        return;
    }
    if !is_root() {
        eprintln!("xtask: missing packages {missing:?} and not root; install them with apt-get, then rerun");
        exit(1);
    }
    println!("xtask: installing {missing:?}");
    run(Command::new("apt-get").args(["update", "-qq"]));
    run(Command::new("apt-get")
        .args(["install", "-y", "-qq", "--no-install-recommends"])
        .args(&missing)
        .env("DEBIAN_FRONTEND", "noninteractive"));
}

fn test(extra: &[String]) {
    install();
    run(Command::new("cargo").args(["fmt", "--all", "--check"]));
    run(Command::new("cargo").args([
        "clippy",
        "--workspace",
        "--all-targets",
        "--features",
        "opencl",
        "--",
        "-D",
        "warnings",
    ]));
    // Broken intra-doc links are errors: the docs name the code they describe.
    run(Command::new("cargo")
        .args(["doc", "--no-deps", "--workspace", "--features", "opencl"])
        .env("RUSTDOCFLAGS", "-D warnings"));
    // The GPU-language tests fail rather than skip when their runtime is missing: this command asked for them.
    let mut tests = Command::new("cargo");
    tests.args(["test", "--workspace", "--features", "opencl", "--no-fail-fast"]).args(extra);
    tests.env("FRACTAL_REQUIRE_GPU_BACKENDS", "1");
    // Without a runtime directory the Wayland client library, probed by the Vulkan loader, prints an error line per
    // device opened; a private empty one keeps a passing run quiet (there is no Wayland server either way).
    #[cfg(unix)]
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let dir = std::env::temp_dir().join(format!("fractal-xdg-runtime-{}", std::process::id()));
        if std::fs::create_dir_all(&dir).is_ok() {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
            tests.env("XDG_RUNTIME_DIR", &dir);
        }
    }
    run(&mut tests);
}

/// The scene-language fuzz test (`tests/fuzz.rs`) over `cases` texts instead of the test command's few thousand.
fn fuzz(cases: &str) {
    if cases.parse::<u64>().is_err() {
        eprintln!("xtask: fuzz takes a number of cases, found `{cases}`");
        exit(2);
    }
    run(Command::new("cargo")
        .args(["test", "--features", "opencl", "--test", "fuzz", "--", "--nocapture"])
        .env("FRACTAL_FUZZ_CASES", cases)
        .env("FRACTAL_FUZZ_RENDERS", "200"));
}

/// The engine packages in the engines themselves (`tests/engines/*/run.sh`, docs/engines.md): WebGL2 and the Godot web
/// build in headless Chromium, and with `--bevy` a Bevy app (a long first build). Not part of `test`: they need
/// Chromium, node and Python packages, and Bevy's own toolchain.
fn engines(args: &[String]) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace");
    let out = root.join("target").join("engines");
    install();
    let apt = |package: &str| {
        let present = Command::new("dpkg-query")
            .args(["-W", "-f=${Status}", package])
            .output()
            .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).contains("install ok installed"));
        if !present && is_root() {
            run(Command::new("apt-get").args(["install", "-y", "-qq", "--no-install-recommends", package]));
        }
    };
    for package in ["chromium-headless-shell", "nodejs", "npm"] {
        apt(package);
    }
    run(Command::new("python3").args(["-m", "pip", "install", "--quiet", "numpy", "pillow", "OpenEXR"]));
    run(Command::new("cargo").args(["build", "--release", "--bin", "fractal"]).current_dir(root));
    run(Command::new(root.join("tests/engines/webgl/run.sh")).arg(out.join("webgl")));
    for scene in ["amazing_box", "kifs", "sphere_box"] {
        run(Command::new(root.join("tests/engines/godot/run.sh")).arg(scene).arg(out.join("godot").join(scene)));
    }
    if args.iter().any(|a| a == "--bevy") {
        for scene in ["amazing_box", "kifs", "sphere_box"] {
            run(Command::new(root.join("tests/engines/bevy/run.sh")).arg(scene).arg(out.join("bevy").join(scene)));
        }
    }
}

fn run(cmd: &mut Command) {
    println!("xtask: running {cmd:?}");
    match cmd.status() {
        Ok(s) if s.success() => {}
        Ok(s) => {
            eprintln!("xtask: command failed with {s}");
            exit(s.code().unwrap_or(1));
        }
        Err(e) => {
            eprintln!("xtask: cannot run {cmd:?}: {e}");
            exit(1);
        }
    }
}

/// Prints each crate's module cycles and fails when there is one; with a crate's source folder, prints its edges.
fn layers(dir: Option<&str>) {
    // The workspace the command runs in (a second checkout reads its own files), else xtask's own.
    let here = std::env::current_dir()
        .ok()
        .and_then(|d| d.ancestors().find(|a| a.join("Cargo.lock").exists()).map(Into::into));
    let root: std::path::PathBuf = here.unwrap_or_else(|| {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask lives in the workspace").to_path_buf()
    });
    let root = root.as_path();
    if let Some(dir) = dir {
        match layers::Graph::read(&root.join(dir)) {
            Ok(graph) => {
                for (from, to) in graph.edges() {
                    let names: Vec<String> = to.iter().map(|t| t.join("::")).collect();
                    println!("{} -> {}", from.join("::"), names.join(" "));
                }
            }
            Err(e) => eprintln!("xtask: {e}"),
        }
        return;
    }
    let long = house::long_files(root);
    for (file, lines) in &long {
        eprintln!("long file: {} has {lines} lines (at most {})", file.display(), house::MAX_LINES);
    }
    match layers::workspace_cycles(root) {
        Ok(cycles) if cycles.is_empty() && long.is_empty() => println!("xtask: no module cycles, no long files"),
        Ok(cycles) => {
            cycles.iter().for_each(|c| eprintln!("cycle: {c}"));
            exit(1);
        }
        Err(e) => {
            eprintln!("xtask: {e}");
            exit(1);
        }
    }
}
