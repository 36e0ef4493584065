//! The IR as Rust: [`scene`] spells a [`Scene`] as a Rust expression that constructs it, and [`default_params`] its
//! parameters' defaults as constant slices, so the `scene!` macro's expansion holds its IR and default parameter
//! block without parsing anything or walking the IR at run time.
//!
//! Every IR value is written exactly: numbers as suffixed literals that read back as the same `f64` (non-finite
//! ones as the `f64` constants), names as string literals, and every enum by its full path under `krate`, the path of
//! fractal-dsl in the crate the expansion lands in. The matches are exhaustive, so an IR change that this file does
//! not follow is a compile error here.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::ir::fractal::FractalArgValue;
use crate::ir::*;
use crate::vocab::fractals::families::FRACTALS;
use crate::vocab::ops::decl::OPS;
use crate::vocab::prims::decl::PRIMS;

/// A Rust expression of type `Scene` (named through `krate`) that constructs `scene` exactly.
pub fn scene(scene: &Scene, krate: &TokenStream) -> TokenStream {
    let w = Writer { k: krate };
    let root = w.node(&scene.root);
    let lights = scene.lights.iter().map(|l| w.light(l));
    let camera = w.camera(&scene.camera);
    let settings = w.settings(&scene.settings);
    let k = krate;
    quote! {
        #k::Scene {
            root: #root,
            lights: ::std::vec![#(#lights),*],
            camera: #camera,
            settings: #settings,
        }
    }
}

/// Constant expressions of type `&'static [f32]` and `&'static [f64]`: the defaults of the scene's parameters in
/// [`Scene::params`] order (uniform slot order), rounded to f32 the way [`crate::number::math::Real::c`] rounds them.
pub fn default_params(scene: &Scene) -> (TokenStream, TokenStream) {
    let params = scene.params();
    let single = params.iter().map(|p| f32_lit(p.default as f32));
    let double = params.iter().map(|p| f64_lit(p.default));
    (quote!(&[#(#single),*]), quote!(&[#(#double),*]))
}

/// An `f64` literal (with its sign) that reads back as exactly `v`.
fn f64_lit(v: f64) -> TokenStream {
    if v.is_nan() {
        quote!(::core::f64::NAN)
    } else if v.is_infinite() {
        if v > 0.0 {
            quote!(::core::f64::INFINITY)
        } else {
            quote!(::core::f64::NEG_INFINITY)
        }
    } else {
        // Negative literals are written as a negation so the token stays an ordinary literal; `-0.0` keeps its sign.
        let magnitude = Literal::f64_suffixed(v.abs());
        if v.is_sign_negative() {
            quote!(-#magnitude)
        } else {
            quote!(#magnitude)
        }
    }
}

/// An `f32` literal (with its sign) that reads back as exactly `v`.
fn f32_lit(v: f32) -> TokenStream {
    if v.is_nan() {
        quote!(::core::f32::NAN)
    } else if v.is_infinite() {
        if v > 0.0 {
            quote!(::core::f32::INFINITY)
        } else {
            quote!(::core::f32::NEG_INFINITY)
        }
    } else {
        let magnitude = Literal::f32_suffixed(v.abs());
        if v.is_sign_negative() {
            quote!(-#magnitude)
        } else {
            quote!(#magnitude)
        }
    }
}

fn u32_lit(v: u32) -> Literal {
    Literal::u32_suffixed(v)
}

fn f64_array<const N: usize>(v: &[f64; N]) -> TokenStream {
    let items = v.iter().map(|&x| f64_lit(x));
    quote!([#(#items),*])
}

/// Spells IR values with the types named through `k`.
struct Writer<'a> {
    k: &'a TokenStream,
}

impl Writer<'_> {
    fn boxed(&self, inner: TokenStream) -> TokenStream {
        quote!(::std::boxed::Box::new(#inner))
    }

    fn option<T>(&self, v: &Option<T>, some: impl Fn(&T) -> TokenStream) -> TokenStream {
        match v {
            Some(x) => {
                let x = some(x);
                quote!(::core::option::Option::Some(#x))
            }
            None => quote!(::core::option::Option::None),
        }
    }

    fn expr(&self, e: &Expr) -> TokenStream {
        let k = self.k;
        match e {
            Expr::Lit(v) => {
                let v = f64_lit(*v);
                quote!(#k::Expr::Lit(#v))
            }
            Expr::Time => quote!(#k::Expr::Time),
            Expr::Point(axis) => quote!(#k::Expr::Point(#axis)),
            Expr::Param(p) => {
                let p = self.boxed(self.param(p));
                quote!(#k::Expr::Param(#p))
            }
            Expr::Neg(a) => {
                let a = self.boxed(self.expr(a));
                quote!(#k::Expr::Neg(#a))
            }
            Expr::Bin(op, a, b) => {
                let op = self.bin_op(*op);
                let (a, b) = (self.boxed(self.expr(a)), self.boxed(self.expr(b)));
                quote!(#k::Expr::Bin(#op, #a, #b))
            }
            Expr::Call(f, args) => {
                let f = self.func(*f);
                let args = args.iter().map(|a| self.expr(a));
                quote!(#k::Expr::Call(#f, ::std::vec![#(#args),*]))
            }
        }
    }

    fn param(&self, p: &ParamDecl) -> TokenStream {
        let k = self.k;
        let ParamDecl { name, default, min, max } = p;
        let (default, min, max) = (f64_lit(*default), f64_lit(*min), f64_lit(*max));
        quote! {
            #k::ParamDecl { name: ::std::string::String::from(#name), default: #default, min: #min, max: #max }
        }
    }

    fn bin_op(&self, op: BinOp) -> TokenStream {
        let k = self.k;
        match op {
            BinOp::Add => quote!(#k::BinOp::Add),
            BinOp::Sub => quote!(#k::BinOp::Sub),
            BinOp::Mul => quote!(#k::BinOp::Mul),
            BinOp::Div => quote!(#k::BinOp::Div),
        }
    }

    fn func(&self, f: Func) -> TokenStream {
        let k = self.k;
        match f {
            Func::Sin => quote!(#k::Func::Sin),
            Func::Cos => quote!(#k::Func::Cos),
            Func::Abs => quote!(#k::Func::Abs),
            Func::Sqrt => quote!(#k::Func::Sqrt),
            Func::Min => quote!(#k::Func::Min),
            Func::Max => quote!(#k::Func::Max),
            Func::Pow => quote!(#k::Func::Pow),
            Func::Clamp => quote!(#k::Func::Clamp),
            Func::Mix => quote!(#k::Func::Mix),
            Func::Noise2 => quote!(#k::Func::Noise2),
            Func::Noise3 => quote!(#k::Func::Noise3),
            Func::Fbm2 => quote!(#k::Func::Fbm2),
            Func::Fbm3 => quote!(#k::Func::Fbm3),
            Func::Mandelbrot => quote!(#k::Func::Mandelbrot),
        }
    }

    fn vec3(&self, v: &Vec3Expr) -> TokenStream {
        let k = self.k;
        let items = v.0.iter().map(|e| self.expr(e));
        quote!(#k::Vec3Expr([#(#items),*]))
    }

    fn vec4(&self, v: &Vec4Expr) -> TokenStream {
        let k = self.k;
        let items = v.0.iter().map(|e| self.expr(e));
        quote!(#k::Vec4Expr([#(#items),*]))
    }

    fn node(&self, n: &Node) -> TokenStream {
        let k = self.k;
        match n {
            Node::Prim(p) => {
                let p = self.prim(p);
                quote!(#k::Node::Prim(#p))
            }
            Node::Fractal(f) => {
                let f = self.boxed(self.fractal(f));
                quote!(#k::Node::Fractal(#f))
            }
            Node::Op(op) => {
                let op = self.op(op);
                quote!(#k::Node::Op(#op))
            }
            Node::Material(c, m) => {
                let (c, m) = (self.boxed(self.node(c)), self.boxed(self.material(m)));
                quote!(#k::Node::Material(#c, #m))
            }
        }
    }

    fn args(&self, args: &[ArgValue]) -> TokenStream {
        let k = self.k;
        let args = args.iter().map(|a| match a {
            ArgValue::Num(e) => {
                let e = self.expr(e);
                quote!(#k::ArgValue::Num(#e))
            }
            ArgValue::Vec3(v) => {
                let v = self.vec3(v);
                quote!(#k::ArgValue::Vec3(#v))
            }
        });
        quote!(::std::vec![#(#args),*])
    }

    /// A primitive names its declaration by its place in the table (the same table the macro read).
    fn prim(&self, p: &Prim) -> TokenStream {
        let k = self.k;
        let index = PRIMS.iter().position(|d| d.name == p.name()).unwrap_or_default();
        let args = self.args(&p.args);
        quote!(#k::Prim { kind: #k::PrimKind(#k::vocab::prims::decl::PRIMS[#index]), args: #args })
    }

    /// An operator names its declaration by its place in the table (the same table the macro read).
    fn op(&self, op: &Op) -> TokenStream {
        let k = self.k;
        let index = OPS.iter().position(|d| d.name == op.name()).unwrap_or_default();
        let shapes = op.shapes.iter().map(|s| self.node(s));
        let args = self.args(&op.args);
        quote! {
            #k::Op { kind: #k::OpKind(#k::vocab::ops::decl::OPS[#index]), shapes: ::std::vec![#(#shapes),*], args: #args }
        }
    }

    /// A fractal names its family by its place in the table (the same table the macro read).
    fn fractal(&self, f: &Fractal) -> TokenStream {
        let k = self.k;
        let Fractal { kind, arg, iterations, settings, step_factor } = f;
        let index = FRACTALS.iter().position(|d| d.name == kind.0.name).unwrap_or_default();
        let arg = match arg {
            FractalArgValue::Num(e) => {
                let e = self.expr(e);
                quote!(#k::ir::fractal::FractalArgValue::Num(#e))
            }
            FractalArgValue::Vec3(v) => {
                let v = self.vec3(v);
                quote!(#k::ir::fractal::FractalArgValue::Vec3(#v))
            }
            FractalArgValue::Vec4(v) => {
                let v = self.vec4(v);
                quote!(#k::ir::fractal::FractalArgValue::Vec4(#v))
            }
            FractalArgValue::Levels => quote!(#k::ir::fractal::FractalArgValue::Levels),
            // A formula is written as its canonical text, read back when the IR is first asked for: the text the
            // kernels were compiled from, which the printer's round trip keeps exact.
            FractalArgValue::Formula(formula) => {
                let text = crate::print::formula_call(formula);
                quote!(#k::ir::fractal::FractalArgValue::Formula(::std::boxed::Box::new(#k::parse::formula_from_source(#text))))
            }
        };
        let iterations = self.option(iterations, |&n| {
            let n = u32_lit(n);
            quote!(#n)
        });
        let settings = settings.iter().map(|s| self.option(s, |e| self.expr(e)));
        let step_factor = self.option(step_factor, |&k| f64_lit(k));
        quote! {
            #k::Fractal {
                kind: #k::FractalKind(#k::vocab::fractals::families::FRACTALS[#index]),
                arg: #arg,
                iterations: #iterations,
                settings: [#(#settings),*],
                step_factor: #step_factor,
            }
        }
    }

    fn material(&self, m: &Material) -> TokenStream {
        let k = self.k;
        let Material { albedo, ambient, diffuse, specular, shininess } = m;
        let albedo = match albedo {
            Albedo::Rgb(c) => {
                let c = self.vec3(c);
                quote!(#k::Albedo::Rgb(#c))
            }
            Albedo::OrbitTrap(a, b) => {
                let (a, b) = (self.vec3(a), self.vec3(b));
                quote!(#k::Albedo::OrbitTrap(#a, #b))
            }
        };
        let (ambient, diffuse) = (self.expr(ambient), self.expr(diffuse));
        let (specular, shininess) = (self.expr(specular), self.expr(shininess));
        quote! {
            #k::Material {
                albedo: #albedo,
                ambient: #ambient,
                diffuse: #diffuse,
                specular: #specular,
                shininess: #shininess,
            }
        }
    }

    fn light(&self, l: &Light) -> TokenStream {
        let k = self.k;
        let Light { kind, color, intensity } = l;
        let kind = match kind {
            LightKind::Directional { direction } => {
                let direction = self.vec3(direction);
                quote!(#k::LightKind::Directional { direction: #direction })
            }
            LightKind::Point { position } => {
                let position = self.vec3(position);
                quote!(#k::LightKind::Point { position: #position })
            }
        };
        let (color, intensity) = (self.vec3(color), self.expr(intensity));
        quote!(#k::Light { kind: #kind, color: #color, intensity: #intensity })
    }

    fn camera(&self, c: &Camera) -> TokenStream {
        let k = self.k;
        let Camera { placement, fov_degrees, aperture, focus } = c;
        let placement = match placement {
            CameraPlacement::LookAt { position, target } => {
                let (position, target) = (self.vec3(position), self.vec3(target));
                quote!(#k::CameraPlacement::LookAt { position: #position, target: #target })
            }
            CameraPlacement::Path { keys, interpolation, looped } => {
                let keys = keys.iter().map(|key| {
                    let CameraKey { time, position, target } = key;
                    let (time, position, target) = (f64_lit(*time), f64_array(position), f64_array(target));
                    quote!(#k::CameraKey { time: #time, position: #position, target: #target })
                });
                let interpolation = match interpolation {
                    PathInterpolation::Linear => quote!(#k::PathInterpolation::Linear),
                    PathInterpolation::CatmullRom => quote!(#k::PathInterpolation::CatmullRom),
                };
                quote! {
                    #k::CameraPlacement::Path {
                        keys: ::std::vec![#(#keys),*],
                        interpolation: #interpolation,
                        looped: #looped,
                    }
                }
            }
        };
        let (fov_degrees, aperture) = (f64_lit(*fov_degrees), f64_lit(*aperture));
        let focus = self.option(focus, |&d| f64_lit(d));
        quote!(#k::Camera { placement: #placement, fov_degrees: #fov_degrees, aperture: #aperture, focus: #focus })
    }

    fn settings(&self, s: &RenderSettings) -> TokenStream {
        let k = self.k;
        let RenderSettings {
            max_steps,
            max_distance,
            epsilon,
            over_relaxation,
            normal_epsilon,
            membership_hits,
            shadows,
            ambient_occlusion,
            glow,
            fog,
            background,
            gamma,
            samples,
            sample_threshold,
        } = s;
        let max_steps = u32_lit(*max_steps);
        let max_distance = f64_lit(*max_distance);
        let epsilon = match epsilon {
            HitEpsilon::Fixed(e) => {
                let e = f64_lit(*e);
                quote!(#k::HitEpsilon::Fixed(#e))
            }
            HitEpsilon::Pixel(f) => {
                let f = f64_lit(*f);
                quote!(#k::HitEpsilon::Pixel(#f))
            }
        };
        let over_relaxation = f64_lit(*over_relaxation);
        let normal_epsilon = self.option(normal_epsilon, |&k| f64_lit(k));
        let shadows = match shadows {
            Shadows::None => quote!(#k::Shadows::None),
            Shadows::Hard => quote!(#k::Shadows::Hard),
            Shadows::Soft(sharpness) => {
                let sharpness = f64_lit(*sharpness);
                quote!(#k::Shadows::Soft(#sharpness))
            }
        };
        let ambient_occlusion = self.option(ambient_occlusion, |&a| f64_lit(a));
        let glow = self.option(glow, f64_array);
        let fog = self.option(fog, |f| {
            let Fog { color, density } = f;
            let (color, density) = (f64_array(color), f64_lit(*density));
            quote!(#k::Fog { color: #color, density: #density })
        });
        let background = f64_array(background);
        let gamma = f64_lit(*gamma);
        let (samples, sample_threshold) = (u32_lit(*samples), f64_lit(*sample_threshold));
        quote! {
            #k::RenderSettings {
                max_steps: #max_steps,
                max_distance: #max_distance,
                epsilon: #epsilon,
                over_relaxation: #over_relaxation,
                normal_epsilon: #normal_epsilon,
                membership_hits: #membership_hits,
                shadows: #shadows,
                ambient_occlusion: #ambient_occlusion,
                glow: #glow,
                fog: #fog,
                background: #background,
                gamma: #gamma,
                samples: #samples,
                sample_threshold: #sample_threshold,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{default_params, f32_lit, f64_lit};
    use crate::builder::*;
    use proc_macro2::TokenStream;
    use quote::quote;

    fn text(tokens: TokenStream) -> String {
        tokens.to_string()
    }

    #[test]
    fn numbers_are_written_exactly_with_their_sign() {
        assert_eq!(text(f64_lit(0.1)), "0.1f64");
        assert_eq!(text(f64_lit(-2.5)), "- 2.5f64");
        assert_eq!(text(f64_lit(-0.0)), "- 0f64");
        assert_eq!(text(f64_lit(f64::INFINITY)), ":: core :: f64 :: INFINITY");
        assert_eq!(text(f32_lit(0.1)), "0.1f32");
        let third = 1.0f64 / 3.0;
        let written = text(f64_lit(third));
        assert_eq!(written.trim_end_matches("f64").parse::<f64>().unwrap(), third);
    }

    #[test]
    fn the_scene_is_one_rust_expression_naming_the_ir_through_the_crate_path() {
        let s = scene(
            union(sphere(param("r", 1.0, 0.5..2.0)), mandelbulb(8).translate(vec3(1.5, 0.0, 0.0)))
                .material(rgb(0.9, 0.2, 0.1)),
        );
        let tokens = super::scene(&s, &quote!(::fractal_dsl));
        let parsed: syn::Expr = syn::parse2(tokens.clone()).expect("the emitted scene is a Rust expression");
        assert!(matches!(parsed, syn::Expr::Struct(_)));
        let written = text(tokens);
        for part in
            [":: fractal_dsl :: Scene", ":: fractal_dsl :: vocab :: ops :: decl :: OPS [0usize]", "\"r\"", "1.5f64"]
        {
            assert!(written.contains(part), "{part} missing from {written}");
        }
    }

    #[test]
    fn defaults_follow_the_parameter_order_in_both_precisions() {
        let s = scene(sphere(param("a", 0.1, 0.0..1.0) + param("b", -0.5, -1.0..1.0) + param("a", 0.1, 0.0..1.0)));
        let (single, double) = default_params(&s);
        assert_eq!(text(single), "& [0.1f32 , - 0.5f32]");
        assert_eq!(text(double), "& [0.1f64 , - 0.5f64]");
    }
}
