//! An exported fractal material in a real Bevy app. `render` draws five shots of one view into PNGs: the fractal
//! alone, an opaque unlit green cube in front of it alone and with the fractal, and a cube behind it alone and with
//! the fractal. `check` (in `check.rs`) reads them back with the project's own render of the same view.
//!
//! The material's Rust side is the package README's own module (`fractal_material.rs`, written by `run.sh`), so this
//! app also proves that the README compiles against the release it names.

mod check;
mod fractal_material;

use std::path::PathBuf;
use std::process::ExitCode;

use bevy::camera::ClearColorConfig;
use bevy::prelude::*;
use bevy::render::view::screenshot::{save_to_disk, Screenshot};
use bevy::render::view::{Msaa, Tonemapping};
use bevy::window::WindowResolution;

use fractal_material::{fractal_cube, FractalMaterial};

/// The clear colour: pure magenta, which no shaded fractal pixel or the green cube is.
const BACKGROUND: Color = Color::srgb(1.0, 0.0, 1.0);

/// The shots, in the order they are drawn; the last one only with `--glb`.
const SHOTS: [Shot; 6] = [Shot::Fractal, Shot::FrontCube, Shot::Front, Shot::BehindCube, Shot::Behind, Shot::Mesh];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shot {
    Fractal,
    FrontCube,
    Front,
    BehindCube,
    Behind,
    /// The scene's mesh (`fractal mesh`), imported from its `.glb`, lit by one light.
    Mesh,
}

impl Shot {
    fn name(self) -> &'static str {
        match self {
            Shot::Fractal => "fractal",
            Shot::FrontCube => "front_cube",
            Shot::Front => "front",
            Shot::BehindCube => "behind_cube",
            Shot::Behind => "behind",
            Shot::Mesh => "mesh",
        }
    }
    /// Whether `image` shows everything this shot should: the green cube, and a surface (neither the magenta
    /// background, nor the black of a window not drawn yet, nor the cube).
    fn complete(self, image: &image::RgbImage) -> bool {
        let has = |wanted: &dyn Fn([u8; 3]) -> bool| image.pixels().any(|p| wanted(p.0));
        let cube = has(&|p| p == [0, 255, 0]);
        let surface = has(&|p| p != [255, 0, 255] && p != [0, 0, 0] && p != [0, 255, 0]);
        let background = has(&|p| p == [255, 0, 255]);
        // (The cube behind may be wholly hidden by a scene with a floor.)
        let wants_cube = matches!(self, Shot::FrontCube | Shot::Front | Shot::BehindCube);
        let wants_surface = self.shows_fractal() || self == Shot::Mesh;
        background && (cube || !wants_cube) && (surface || !wants_surface)
    }

    fn shows_fractal(self) -> bool {
        matches!(self, Shot::Fractal | Shot::Front | Shot::Behind)
    }
}

/// The view and the cubes, in the scene's frame (left-handed, y up); the app mirrors z into Bevy's.
#[derive(Resource, Clone, Debug)]
struct Setup {
    eye: Vec3,
    target: Vec3,
    fov_degrees: f32,
    size: (u32, u32),
    front: (Vec3, f32),
    behind: (Vec3, f32),
    out: PathBuf,
    /// A `.glb` under `assets/` to import and draw as the last shot.
    glb: Option<String>,
}

/// Where the shot sequence stands.
#[derive(Resource, Default)]
struct Progress {
    shot: usize,
    frames: u32,
    requested: bool,
    retries: u32,
}

#[derive(Component)]
struct FractalProxy;
#[derive(Component)]
struct FrontCube;
#[derive(Component)]
struct BehindCube;
#[derive(Component)]
struct ImportedMesh;

fn mirror(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

fn parse_vec3(text: &str) -> Result<Vec3, String> {
    let parts: Vec<f32> = text
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("`{text}`: {e}"))?;
    match parts[..] {
        [x, y, z] => Ok(Vec3::new(x, y, z)),
        _ => Err(format!("`{text}`: expected X,Y,Z")),
    }
}

fn parse_setup(args: &[String]) -> Result<Setup, String> {
    let value = |flag: &str| -> Result<String, String> {
        let i = args.iter().position(|a| a == flag).ok_or(format!("missing {flag}"))?;
        args.get(i + 1).cloned().ok_or(format!("{flag} needs a value"))
    };
    let size = value("--size")?;
    let (w, h) = size.split_once('x').ok_or(format!("--size `{size}`: expected WxH"))?;
    Ok(Setup {
        eye: parse_vec3(&value("--eye")?)?,
        target: parse_vec3(&value("--target")?)?,
        fov_degrees: value("--fov")?.parse().map_err(|e| format!("--fov: {e}"))?,
        size: (w.parse().map_err(|e| format!("--size: {e}"))?, h.parse().map_err(|e| format!("--size: {e}"))?),
        front: (Vec3::ZERO, 0.0),
        behind: (Vec3::ZERO, 0.0),
        out: PathBuf::from(value("--out")?),
        glb: value("--glb").ok(),
    })
    .and_then(|setup| {
        check::place_cubes(setup_view(&setup), &PathBuf::from(value("--depth")?)).map(|(front, behind)| Setup {
            front,
            behind,
            ..setup
        })
    })
}

/// The view as `check` reads it.
fn setup_view(setup: &Setup) -> check::View {
    check::View { eye: setup.eye, target: setup.target, fov_degrees: setup.fov_degrees, size: setup.size }
}

const USAGE: &str = "usage:\n  bevy-engine-check render --eye X,Y,Z --target X,Y,Z --fov DEG --size WxH \
--depth EXR --out DIR\n  bevy-engine-check check --out DIR --reference PNG --depth EXR";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("render") => match parse_setup(&args[1..]) {
            Ok(setup) => render(setup),
            Err(e) => {
                eprintln!("{e}\n{USAGE}");
                ExitCode::from(2)
            }
        },
        Some("check") => check::run(&args[1..]),
        _ => {
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
    }
}

fn render(setup: Setup) -> ExitCode {
    std::fs::create_dir_all(&setup.out).expect("create the output folder");
    let (w, h) = setup.size;
    App::new()
        .add_plugins(
            DefaultPlugins
                .set(WindowPlugin {
                    primary_window: Some(Window {
                        title: "fractal in Bevy".into(),
                        resolution: WindowResolution::new(w, h).with_scale_factor_override(1.0),
                        resizable: false,
                        ..default()
                    }),
                    ..default()
                })
                .set(AssetPlugin { file_path: "assets".into(), ..default() }),
        )
        .add_plugins(MaterialPlugin::<FractalMaterial>::default())
        .insert_resource(setup)
        .init_resource::<Progress>()
        .add_systems(Startup, spawn)
        .add_systems(Update, advance)
        .run();
    ExitCode::SUCCESS
}

fn spawn(
    mut commands: Commands,
    setup: Res<Setup>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut fractals: ResMut<Assets<FractalMaterial>>,
    mut standard: ResMut<Assets<StandardMaterial>>,
    assets: Res<AssetServer>,
) {
    commands.spawn((
        Camera3d::default(),
        Camera { clear_color: ClearColorConfig::Custom(BACKGROUND), ..default() },
        Projection::Perspective(PerspectiveProjection { fov: setup.fov_degrees.to_radians(), ..default() }),
        // Linear colour into the sRGB target, as the project writes a pixel; one sample per pixel.
        Tonemapping::None,
        Msaa::Off,
        Transform::from_translation(mirror(setup.eye)).looking_at(mirror(setup.target), Vec3::Y),
    ));
    commands.spawn((
        FractalProxy,
        Mesh3d(meshes.add(fractal_cube())),
        MeshMaterial3d(fractals.add(FractalMaterial::default())),
    ));
    let green = standard.add(StandardMaterial { base_color: Color::srgb(0.0, 1.0, 0.0), unlit: true, ..default() });
    for (centre, half, behind) in [(setup.front.0, setup.front.1, false), (setup.behind.0, setup.behind.1, true)] {
        let cube = (
            Mesh3d(meshes.add(Cuboid::from_length(2.0 * half))),
            MeshMaterial3d(green.clone()),
            Transform::from_translation(mirror(centre)),
            Visibility::Hidden,
        );
        if behind {
            commands.spawn((BehindCube, cube));
        } else {
            commands.spawn((FrontCube, cube));
        }
    }
    if let Some(glb) = &setup.glb {
        // The mesh is in the scene's frame, written by `fractal mesh` with z mirrored for glTF (right-handed).
        let mesh: Handle<Mesh> =
            assets.load(GltfAssetLabel::Primitive { mesh: 0, primitive: 0 }.from_asset(glb.clone()));
        let grey = standard.add(StandardMaterial { base_color: Color::srgb(0.8, 0.8, 0.8), ..default() });
        commands.spawn((ImportedMesh, Mesh3d(mesh), MeshMaterial3d(grey), Visibility::Hidden));
        commands.spawn((
            DirectionalLight { illuminance: 10_000.0, ..default() },
            Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
        ));
    }
}

/// Frames drawn before the first shot: Bevy compiles pipelines in the background, and a frame drawn before the
/// material's pipeline is ready shows no fractal.
const WARM_UP_FRAMES: u32 = 10;
/// Shots taken again while they show nothing.
const MAX_RETRIES: u32 = 60;
/// Frames drawn after changing what is shown, before the shot.
const SETTLE_FRAMES: u32 = 4;

#[allow(clippy::type_complexity)]
fn advance(
    mut commands: Commands,
    setup: Res<Setup>,
    mut progress: ResMut<Progress>,
    mut visibility: ParamSet<(
        Query<&mut Visibility, With<FractalProxy>>,
        Query<&mut Visibility, With<FrontCube>>,
        Query<&mut Visibility, With<BehindCube>>,
        Query<&mut Visibility, With<ImportedMesh>>,
    )>,
    mut exit: MessageWriter<AppExit>,
) {
    let shots = if setup.glb.is_some() { SHOTS.len() } else { SHOTS.len() - 1 };
    let Some(&shot) = SHOTS[..shots].get(progress.shot) else {
        return;
    };
    let path = setup.out.join(format!("bevy-{}.png", shot.name()));
    if progress.requested {
        // The screenshot is written on a task: the next shot starts once its file is complete.
        let Ok(image) = image::open(&path) else {
            return;
        };
        progress.requested = false;
        progress.frames = 0;
        // Pipelines compile and assets load in the background, and the first frames may not be presented yet: a
        // shot that lacks what it should show is taken again.
        if !shot.complete(&image.to_rgb8()) {
            if progress.retries < MAX_RETRIES {
                progress.retries += 1;
                return;
            }
            eprintln!("the {} shot still lacks what it should show after {MAX_RETRIES} tries", shot.name());
        }
        progress.shot += 1;
        progress.retries = 0;
        if progress.shot == shots {
            exit.write(AppExit::Success);
        }
        return;
    }
    let show = |on: bool| if on { Visibility::Inherited } else { Visibility::Hidden };
    for mut v in visibility.p0().iter_mut() {
        *v = show(shot.shows_fractal());
    }
    for mut v in visibility.p1().iter_mut() {
        *v = show(matches!(shot, Shot::FrontCube | Shot::Front));
    }
    for mut v in visibility.p2().iter_mut() {
        *v = show(matches!(shot, Shot::BehindCube | Shot::Behind));
    }
    for mut v in visibility.p3().iter_mut() {
        *v = show(shot == Shot::Mesh);
    }
    progress.frames += 1;
    let wait = if progress.shot == 0 { WARM_UP_FRAMES } else { SETTLE_FRAMES };
    if progress.frames >= wait {
        let _ = std::fs::remove_file(&path);
        commands.spawn(Screenshot::primary_window()).observe(save_to_disk(path));
        progress.requested = true;
    }
}
