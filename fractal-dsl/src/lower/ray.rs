//! The ray program ([`crate::ray`]) traced into lowered code: the per-pixel body of the render and trace kernels,
//! and the functions of an engine library (`sdf_raymarch`, `sdf_normal`, `sdf_display`). The program is the one the
//! CPU renderer runs; here the scene is calls of `scene_de` and `scene_sample`, and the camera and lights are the
//! kernel's frame (a library's lights are constants).

use super::code::{Body, FrameField, SceneFn, Ty, Val};
use super::trace::{trace, Sym, SymMask};
use super::Program;
use crate::eval::Sample;
use crate::number::math::{v3, V3};
use crate::number::{Mask, Num};
use crate::ray::{march, pixel, shade, Light, Rules, SceneFns, View};

/// The scene as the traced program reads it: calls of the kernel's scene functions.
struct Calls {
    /// Whether `scene_sample` takes the point relative to the camera (a perturbation reference).
    offset: bool,
}

impl SceneFns<Sym> for Calls {
    fn distance(&self, p: V3<Sym>) -> Sym {
        Sym(Sym::scene_call(SceneFn::Distance, vec![Sym::vector(p)]))
    }
    fn sample(&self, p: V3<Sym>, offset: V3<Sym>) -> Sample<Sym> {
        let mut args = vec![Sym::vector(p)];
        if self.offset {
            args.push(Sym::vector(offset));
        }
        let s = Sym::scene_call(SceneFn::Sample, args);
        let field = |i: u8| Sym(Sym::field(s, i));
        Sample {
            distance: field(0),
            albedo: Sym::components(Sym::field(s, 1)),
            ambient: field(2),
            diffuse: field(3),
            specular: field(4),
            shininess: field(5),
        }
    }
    fn normal(&self, p: V3<Sym>, h: Sym) -> V3<Sym> {
        Sym::components(Sym::scene_call(SceneFn::Normal, vec![Sym::vector(p), h.0]))
    }
    fn occlusion(&self, _: &Rules, p: V3<Sym>, n: V3<Sym>) -> Sym {
        Sym(Sym::scene_call(SceneFn::Occlusion, vec![Sym::vector(p), Sym::vector(n)]))
    }
    fn shadow(&self, _: &Rules, (ro, rd): (V3<Sym>, V3<Sym>), limit: Sym, eps: Sym, _: SymMask) -> Sym {
        // Called where the surface faces the light: every lane of a kernel's call is live.
        Sym(Sym::scene_call(SceneFn::Shadow, vec![Sym::vector(ro), Sym::vector(rd), limit.0, eps.0]))
    }
}

/// A function of the ray program a kernel or library defines by name ([`SceneFn::Normal`], [`SceneFn::Occlusion`],
/// [`SceneFn::Shadow`]), traced.
#[derive(Clone, Debug, PartialEq)]
pub struct RayFunction {
    pub f: SceneFn,
    /// Parameter names and types, in order.
    pub params: Vec<(&'static str, Ty)>,
    pub body: Body,
    pub result: Val,
}

/// The ray program's named functions the scene needs: the normal, and ambient occlusion and the shadow march where
/// the scene has them. Each calls `scene_de`.
pub fn functions(program: &Program) -> Vec<RayFunction> {
    let rules = program.rules();
    let scene = program.calls();
    let mut wanted = vec![SceneFn::Normal];
    if rules.ambient_occlusion.is_some() {
        wanted.push(SceneFn::Occlusion);
    }
    if rules.shadows != crate::Shadows::None {
        wanted.push(SceneFn::Shadow);
    }
    wanted
        .into_iter()
        .map(|f| {
            let params: Vec<(&'static str, Ty)> = match f {
                SceneFn::Normal => vec![("p", Ty::V3), ("e", Ty::F)],
                SceneFn::Occlusion => vec![("p", Ty::V3), ("n", Ty::V3)],
                _ => vec![("ro", Ty::V3), ("rd", Ty::V3), ("limit", Ty::F), ("eps", Ty::F)],
            };
            if let (SceneFn::Normal, Some((body, result))) = (f, &program.normal) {
                // The scene's gradient, traced with the scene functions ([`Program::normal`]); `e` goes unread.
                return RayFunction { f, params, body: body.clone(), result: *result };
            }
            let (body, result) = trace(|| {
                let v = |i: usize| Sym::components(Sym::arg_of(params[i].0, Ty::V3));
                let s = |i: usize| Sym::arg(params[i].0);
                match f {
                    SceneFn::Normal => Sym::vector(crate::ray::scene::normal(&scene, v(0), s(1))),
                    SceneFn::Occlusion => crate::ray::scene::occlusion(&rules, &scene, v(0), v(1)).0,
                    _ => crate::ray::scene::shadow(&rules, &scene, (v(0), v(1)), s(2), s(3), SymMask::splat(true)).0,
                }
            });
            RayFunction { f, params, body: body.pruned(&[result]), result }
        })
        .collect()
}

impl Program {
    /// The ray program's rules for this scene.
    pub fn rules(&self) -> Rules {
        Rules::from_settings(&self.settings, (self.refine, self.specular), self.bound, self.lens)
    }

    fn calls(&self) -> Calls {
        Calls { offset: self.reference.is_some() }
    }
}

/// What the render and trace kernels write of a pixel, as values of [`pixel()`]'s body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelVals {
    /// The colour as displayed (clamped, gamma-encoded), V3.
    pub display: Val,
    /// The linear colour, V3.
    pub colour: Val,
    /// The normal at a hit, zero on a miss, V3.
    pub normal: Val,
    /// The ray distance the march ended at.
    pub t: Val,
    /// 1 at a hit, 0 otherwise.
    pub hit: Val,
    /// The march's distance evaluations.
    pub steps: Val,
    /// 1 where the march ran out of steps, 0 otherwise.
    pub out_of_steps: Val,
    /// The samples the pixel took.
    pub samples: Val,
}

impl PixelVals {
    pub fn all(&self) -> [Val; 8] {
        [self.display, self.colour, self.normal, self.t, self.hit, self.steps, self.out_of_steps, self.samples]
    }
}

/// The argument names of [`pixel()`]'s body: the pixel's column and row (whole numbers, as F).
pub const PIXEL_ARGS: [&str; 2] = ["fx", "fy"];

/// The frame's view as the traced program reads it: the frame uniform's camera and lights.
fn frame_view(program: &Program) -> View<Sym> {
    let frame = |f: FrameField| Sym::components(Sym::frame(f));
    let scalar = |f: FrameField| Sym(Sym::frame(f));
    let lights = (0..program.lights.len())
        .map(|i| {
            let (position, radiance) = (frame(FrameField::LightPosition(i)), frame(FrameField::LightRadiance(i)));
            match program.lights[i] {
                super::LightShape::Directional => Light::Directional { direction: position, radiance },
                super::LightShape::Point => Light::Point { position, radiance },
            }
        })
        .collect();
    View {
        anchor: if program.anchored { frame(FrameField::Anchor) } else { V3::splat(Sym::lit(0.0)) },
        origin: frame(FrameField::Origin),
        right: frame(FrameField::Right),
        up: frame(FrameField::Up),
        forward: frame(FrameField::Forward),
        width: scalar(FrameField::Width),
        height: scalar(FrameField::Height),
        footprint: scalar(FrameField::Footprint),
        lights,
    }
}

fn flag(m: SymMask) -> Sym {
    Sym::select(m, Sym::lit(1.0), Sym::lit(0.0))
}

/// The render kernel's per-pixel body: steps 1–7 of the ray program's first pass for pixel ([`PIXEL_ARGS`]) of the
/// frame ([`crate::ray::pixel::first_pass`]). The body computes every value of [`PixelVals`]: prune it to those the
/// kernel writes.
pub fn pixel(program: &Program) -> (Body, PixelVals) {
    let rules = program.rules();
    let (body, vals) = trace(|| {
        let view = frame_view(program);
        let scene = program.calls();
        let (x, y) = (Sym::arg(PIXEL_ARGS[0]), Sym::arg(PIXEL_ARGS[1]));
        let drawn = crate::ray::pixel::first_pass(&rules, &view, &scene, x, y);
        let m = drawn.centre;
        PixelVals {
            display: Sym::vector(shade::display(&rules, drawn.shaded.colour)),
            colour: Sym::vector(drawn.shaded.colour),
            normal: Sym::vector(drawn.shaded.normal),
            t: m.t.0,
            hit: m.hit.0,
            steps: m.steps.0,
            out_of_steps: flag(m.out_of_steps(rules.max_steps)).0,
            samples: Sym::lit(1.0).0,
        }
    });
    (body, vals)
}

/// What the refine kernel writes of a pixel, as values of [`refine`]'s body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefineVals {
    /// 1 where the pixel took more samples, 0 where it keeps its first pass.
    pub refined: Val,
    /// The colour as displayed, V3.
    pub display: Val,
    /// The mean of the samples' clamped linear colours, V3.
    pub colour: Val,
    /// The samples the pixel took.
    pub samples: Val,
}

/// The argument names of [`refine`]'s body beside [`PIXEL_ARGS`]: the first pass's displayed colours (V3, channels
/// in [0, 1]) of the pixel and of its eight neighbours, row by row without the pixel itself (a neighbour outside the
/// image is the nearest pixel inside it).
pub const SHOWN_ARGS: [&str; 9] = ["shown", "n0", "n1", "n2", "n3", "n4", "n5", "n6", "n7"];

/// The refine kernel's per-pixel body: the ray program's second pass for pixel ([`PIXEL_ARGS`]) from the first
/// pass's colours around it ([`SHOWN_ARGS`]; [`crate::ray::pixel::refine`]).
pub fn refine(program: &Program) -> (Body, RefineVals) {
    let rules = program.rules();
    trace(|| {
        let view = frame_view(program);
        let scene = program.calls();
        let (x, y) = (Sym::arg(PIXEL_ARGS[0]), Sym::arg(PIXEL_ARGS[1]));
        let shown = SHOWN_ARGS.map(|name| Sym::components(Sym::arg_of(name, Ty::V3)));
        let [centre, neighbours @ ..] = shown.map(|c| pixel::shown_luma(&rules, c));
        let refines = pixel::refines(&rules, centre, neighbours);
        let all = pixel::refine(&rules, &view, &scene, (x, y), pixel::undisplay(&rules, shown[0]), refines);
        let colour = all.mean();
        RefineVals {
            refined: flag(refines).0,
            display: Sym::vector(shade::display(&rules, colour)),
            colour: Sym::vector(colour),
            samples: all.count.0,
        }
    })
}

/// The argument names of [`raymarch`]'s body: the ray's origin and unit direction (V3), the pixel's footprint per
/// unit distance (F).
pub const RAYMARCH_ARGS: [(&str, Ty); 3] = [("ro", Ty::V3), ("rd", Ty::V3), ("footprint", Ty::F)];

/// A library's `sdf_raymarch` body: steps 2–6 along a ray with the library's constant `lights` (unit direction or
/// position, and radiance, in the program's light order). Its values: the linear colour (V3), and the hit's ray
/// distance or −1 for a miss.
pub fn raymarch(program: &Program, lights: &[([f64; 3], [f64; 3])]) -> (Body, [Val; 2]) {
    let rules = program.rules();
    let (body, vals) = trace(|| {
        let lit3 = |c: [f64; 3]| v3(Sym::lit(c[0]), Sym::lit(c[1]), Sym::lit(c[2]));
        let [ro, rd] = [0, 1].map(|i| Sym::components(Sym::arg_of(RAYMARCH_ARGS[i].0, Ty::V3)));
        let lights = program
            .lights
            .iter()
            .zip(lights)
            .map(|(shape, &(position, radiance))| match shape {
                super::LightShape::Directional => {
                    Light::Directional { direction: lit3(position), radiance: lit3(radiance) }
                }
                super::LightShape::Point => Light::Point { position: lit3(position), radiance: lit3(radiance) },
            })
            .collect();
        let zero = lit3([0.0; 3]);
        // A library's caller makes the ray: only the footprint and lights of the view are read.
        let view = View {
            anchor: zero,
            origin: zero,
            right: zero,
            up: zero,
            forward: zero,
            width: Sym::lit(1.0),
            height: Sym::lit(1.0),
            footprint: Sym::arg(RAYMARCH_ARGS[2].0),
            lights,
        };
        let scene = program.calls();
        let (m, _) = march::march(&rules, &view, &scene, ro, rd);
        let shaded = shade::shade(&rules, &view, &scene, (ro, rd), &m);
        [Sym::vector(shaded.colour), Sym::select(m.hit(), m.t, Sym::lit(-1.0)).0]
    });
    (body.pruned(&vals), vals)
}

/// A library's `sdf_normal` body: the normal at the point `p` (V3 argument), taps `epsilon` apart (an expression the
/// body spells as written: the library's constant).
pub fn normal(program: &Program, epsilon: &'static str) -> (Body, Val) {
    let (body, val) = trace(|| {
        let p = Sym::components(Sym::arg_of("p", Ty::V3));
        Sym::vector(program.calls().normal(p, Sym::arg(epsilon)))
    });
    (body.pruned(&[val]), val)
}

/// A library's `sdf_display` body: the linear colour `colour` (V3 argument) as the viewer displays it; with `linear`,
/// `sdf_display_linear`'s: that display value decoded from sRGB (what an sRGB target must be given to show it).
pub fn display(program: &Program, linear: bool) -> (Body, Val) {
    let rules = program.rules();
    let (body, val) = trace(|| {
        let colour = Sym::components(Sym::arg_of("colour", Ty::V3));
        Sym::vector(if linear { shade::display_linear(&rules, colour) } else { shade::display(&rules, colour) })
    });
    (body.pruned(&[val]), val)
}
