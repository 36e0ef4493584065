//! `scene!` and `scene_file!`: compile a scene at build time. The macro only parses (with fractal-dsl's parser), asks
//! fractal-dsl's writers for the kernels, the native evaluator, the code that constructs the IR and the parameters'
//! defaults, and wraps them in a `CompiledScene`; it has no code generation of its own.

use proc_macro::TokenStream;
use proc_macro2::{Span, TokenStream as TokenStream2};
use quote::quote;

/// Compiles a scene written as a Rust expression into OpenCL C, WGSL and a native evaluator:
///
/// ```ignore
/// let s = scene! { union(mandelbulb(8), sphere(1.0).translate(vec3(1.5, 0.0, 0.0))) };
/// ```
/// A malformed scene is a compile error at the offending token.
#[proc_macro]
pub fn scene(input: TokenStream) -> TokenStream {
    match fractal_dsl::parse::parse_tokens(input.into()) {
        Ok(scene) => expand(&scene, Span::call_site()).into(),
        Err(e) => e.to_compile_error().into(),
    }
}

/// Compiles a `.fractal` file (path relative to the crate's manifest directory) exactly like `scene!`. The path is a
/// string literal or `concat!` of string literals (so a `macro_rules!` list can build it from a scene's name).
#[proc_macro]
pub fn scene_file(input: TokenStream) -> TokenStream {
    let lit = match path_literal(input.into()) {
        Ok(lit) => lit,
        Err(e) => return e.to_compile_error().into(),
    };
    let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
    let path = std::path::Path::new(&dir).join(lit.value());
    let text = match fractal_dsl::parse::read_source(&path) {
        Ok(t) => t,
        Err(e) => {
            return syn::Error::new(lit.span(), format!("cannot read {}: {e}", path.display()))
                .to_compile_error()
                .into()
        }
    };
    // Lex the file as text, with proc-macro2's own lexer, so errors carry the file's line:column (the compiler's
    // lexer would place every token at the macro call).
    proc_macro2::fallback::force();
    let parsed = fractal_dsl::parse::parse_str(&text);
    proc_macro2::fallback::unforce();
    match parsed {
        Ok(scene) => {
            let expanded = expand(&scene, lit.span());
            // Rebuild when the file changes.
            let path_str = path.to_string_lossy().into_owned();
            quote!({ const _: &[u8] = include_bytes!(#path_str); #expanded }).into()
        }
        Err(e) => syn::Error::new(lit.span(), format!("{}:{e}", lit.value())).to_compile_error().into(),
    }
}

/// The path given to `scene_file!`: a string literal, or `concat!` of string literals joined into one.
fn path_literal(input: TokenStream2) -> syn::Result<syn::LitStr> {
    match syn::parse2::<syn::Expr>(input)? {
        syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(lit), .. }) => Ok(lit),
        syn::Expr::Macro(m) if m.mac.path.is_ident("concat") => {
            let parts =
                m.mac.parse_body_with(syn::punctuated::Punctuated::<syn::LitStr, syn::Token![,]>::parse_terminated)?;
            let joined: String = parts.iter().map(syn::LitStr::value).collect();
            Ok(syn::LitStr::new(&joined, m.mac.path.segments[0].ident.span()))
        }
        other => {
            Err(syn::Error::new_spanned(other, "scene_file! takes a path: a string literal or concat!(\"..\", ..)"))
        }
    }
}

/// The path of fractal-dsl as the calling crate sees it: directly, or through the `fractal` facade.
fn dsl_path() -> TokenStream2 {
    use proc_macro_crate::{crate_name, FoundCrate};
    match crate_name("fractal-dsl") {
        Ok(FoundCrate::Itself) => quote!(crate),
        Ok(FoundCrate::Name(name)) => {
            let ident = syn::Ident::new(&name, Span::call_site());
            quote!(::#ident)
        }
        Err(_) => match crate_name("fractal") {
            Ok(FoundCrate::Name(name)) => {
                let ident = syn::Ident::new(&name, Span::call_site());
                quote!(::#ident::dsl)
            }
            _ => quote!(::fractal::dsl),
        },
    }
}

fn expand(scene: &fractal_dsl::Scene, span: Span) -> TokenStream2 {
    if let Err(errors) = fractal_dsl::validate::validate(scene) {
        let message = errors.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n");
        return syn::Error::new(span, message).to_compile_error();
    }
    let krate = dsl_path();
    let kernels = match fractal_dsl::compile(scene) {
        Ok(kernels) => kernels,
        Err(e) => return syn::Error::new(span, e.to_string()).to_compile_error(),
    };
    let native_src = fractal_dsl::back::rust::write(&kernels.program, &krate.to_string().replace(' ', ""));
    let native: TokenStream2 = match native_src.parse() {
        Ok(tokens) => tokens,
        Err(e) => {
            return syn::Error::new(span, format!("internal error: the native evaluator does not lex: {e}"))
                .to_compile_error()
        }
    };
    let distance = syn::Ident::new(fractal_dsl::back::rust::DISTANCE_FN, Span::call_site());
    let sample = syn::Ident::new(fractal_dsl::back::rust::SAMPLE_FN, Span::call_site());
    let normal = if kernels.program.normal.is_some() {
        let f = syn::Ident::new(fractal_dsl::back::rust::NORMAL_FN, Span::call_site());
        quote! { ::core::option::Option::Some(#krate::NormalFns { f32: #f::<f32>, f64: #f::<f64>, x8: #f::<#krate::number::lanes::F32x8> }) }
    } else {
        quote! { ::core::option::Option::None }
    };
    let ir = fractal_dsl::back::rust::ir_tokens::scene(scene, &krate);
    let (defaults_f32, defaults_f64) = fractal_dsl::back::rust::ir_tokens::default_params(scene);
    let (source, opencl, opencl_f64) = (kernels.source, kernels.opencl, kernels.opencl_f64);
    let (wgsl, wgsl_f64) = (kernels.wgsl, kernels.wgsl_f64);
    let lanes = quote! { #krate::number::lanes::F32x8 };
    let point = quote! { #krate::number::math::V3<#lanes> };
    let env = quote! { &#krate::eval::Env<#lanes> };
    let sample_x8 = quote! { #krate::eval::Sample<#lanes> };
    quote! {{
        #native
        // The packet instances, compiled twice on x86-64: for the build's baseline and for AVX2 (eight lanes in one
        // instruction), chosen when the CPU has it. The arithmetic is the same; only the vector width differs.
        #[allow(clippy::all)]
        fn __fractal_distance_x8(p: #point, env: #env) -> #lanes {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                unsafe fn wide(p: #point, env: #env) -> #lanes {
                    #distance::<#lanes>(p, env)
                }
                if #krate::number::lanes::has_avx2() {
                    // SAFETY: the CPU has AVX2, checked just above.
                    return unsafe { wide(p, env) };
                }
            }
            #distance::<#lanes>(p, env)
        }
        #[allow(clippy::all)]
        fn __fractal_distance_slice_x8(x: &[f32], y: &[f32], z: &[f32], out: &mut [f32], env: #env) {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                unsafe fn wide(x: &[f32], y: &[f32], z: &[f32], out: &mut [f32], env: #env) {
                    #krate::eval::packet::each_packet(
                        #[inline(always)] |p| #distance::<#lanes>(p, env), x, y, z, out)
                }
                if #krate::number::lanes::has_avx2() {
                    // SAFETY: the CPU has AVX2, checked just above.
                    return unsafe { wide(x, y, z, out, env) };
                }
            }
            #krate::eval::packet::each_packet(|p| #distance::<#lanes>(p, env), x, y, z, out)
        }
        #[allow(clippy::all)]
        fn __fractal_sample_x8(p: #point, env: #env) -> #sample_x8 {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                unsafe fn wide(p: #point, env: #env) -> #sample_x8 {
                    #sample::<#lanes>(p, env)
                }
                if #krate::number::lanes::has_avx2() {
                    // SAFETY: the CPU has AVX2, checked just above.
                    return unsafe { wide(p, env) };
                }
            }
            #sample::<#lanes>(p, env)
        }
        #[allow(clippy::all)]
        fn __fractal_scene() -> #krate::Scene {
            #ir
        }
        #[allow(clippy::all)]
        const __FRACTAL_DEFAULTS: #krate::compiled::DefaultParams =
            #krate::compiled::DefaultParams { f32: #defaults_f32, f64: #defaults_f64 };
        #krate::CompiledScene::new(
            #source,
            (#opencl, #opencl_f64),
            (#wgsl, #wgsl_f64),
            #krate::NativeFns {
                distance_f32: #distance::<f32>,
                distance_f64: #distance::<f64>,
                sample_f32: #sample::<f32>,
                sample_f64: #sample::<f64>,
                distance_x8: __fractal_distance_x8,
                sample_x8: __fractal_sample_x8,
                distance_slice_x8: __fractal_distance_slice_x8,
                normal: #normal,
            },
            __fractal_scene,
            __FRACTAL_DEFAULTS,
        )
    }}
}
