//! `fractal gallery`: every built-in scene rendered from its own camera at one time, each written as
//! `<dir>/<scene>.png`, and a labelled contact sheet of them all, `<dir>/gallery.png`.

use std::time::Instant;

use fractal_render::frame::ParamValues;
use fractal_render::image::Image;

use crate::cli::args::{GalleryArgs, RenderOptions};
use crate::cli::error::CliError;
use crate::cli::render::{open_renderer, render_frame};
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::frame_precision::FramePrecision;
use crate::output::contact_sheet;
use crate::output::png::{prepare_output, write_png};

/// The contact sheet's file name in the gallery folder.
pub const SHEET: &str = "gallery.png";

pub fn gallery(args: &GalleryArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let sheet_path = args.output.join(SHEET);
    prepare_output(&sheet_path)?;
    let options = RenderOptions { size: args.size, device: args.device, params: vec![], samples: args.samples };
    let mut renderer = open_renderer(&options)?;
    let mut tiles: Vec<(&str, Image)> = Vec::new();
    for &(name, _) in library.scenes {
        let mut loaded = LoadedScene::load(name, library)?;
        loaded.set_samples(args.samples)?;
        let params = ParamValues::defaults(&loaded.scene);
        let start = Instant::now();
        let mut precision = FramePrecision::new(args.device.precision, format!("fractal: {name}: "));
        let image = render_frame(renderer.as_mut(), &loaded, &params, (args.time, args.size), &mut precision)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let path = args.output.join(format!("{name}.png"));
        write_png(&path, &image)?;
        eprintln!("{name:<24} {}x{} {ms:8.1} ms  {}", args.size.0, args.size.1, path.display());
        tiles.push((name, image));
    }
    let labelled: Vec<(&str, &Image)> = tiles.iter().map(|(n, i)| (*n, i)).collect();
    let sheet = contact_sheet(&labelled, args.columns);
    write_png(&sheet_path, &sheet)?;
    eprintln!("wrote {} ({} scenes, {}x{})", sheet_path.display(), tiles.len(), sheet.width, sheet.height);
    Ok(())
}
