//! The per-language spellings of the leaf functions (`back/*/library.rs`): every helper has a definition in each
//! language, the WGSL ones parse and validate (all together, called from an entry point, and each with only its
//! dependencies), and a helper's text calls no other helper than its declared dependencies.

use fractal_dsl::back::{opencl, wgsl, with_dependencies, Helper};

/// Parses and validates a WGSL module, reporting naga's diagnostics against the source on failure.
fn validate_wgsl(source: &str) -> Result<(), String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
        .validate(&module)
        .map_err(|e| e.emit_to_string(source))?;
    Ok(())
}

/// A WGSL call of `helper` with constant arguments, reduced to one f32.
fn wgsl_call(helper: Helper) -> String {
    let args = match helper {
        Helper::SdSphere => "p, 1.0",
        Helper::SdBox => "p, vec3<f32>(0.5, 0.6, 0.7)",
        Helper::SdRoundBox => "p, vec3<f32>(0.5, 0.6, 0.7), 0.1",
        Helper::SdTorus => "p, 1.0, 0.25",
        Helper::SdCapsule => "p, vec3<f32>(0.0, -0.5, 0.0), vec3<f32>(0.0, 0.5, 0.0), 0.2",
        Helper::SdCylinder => "p, 0.5, 1.0",
        Helper::SdCone => "p, 1.0, 0.5, 0.2",
        Helper::SdPlane => "p, vec3<f32>(0.0, 1.0, 0.0), 0.5",
        Helper::SdOctahedron => "p, 1.0",
        Helper::SdEllipsoid => "p, vec3<f32>(1.0, 0.5, 0.25)",
        Helper::SmoothMin | Helper::SmoothMax | Helper::BlendWeight => "p.x, p.y, 0.3",
        Helper::DeMandelbulb => "p, 7.0, 8, 2.0",
        Helper::DeMandelbulb8 => "p, 8, 2.0",
        Helper::DeMenger => "p, 4",
        Helper::DeSierpinski => "p, 8",
        Helper::DeJulia => "p, vec4<f32>(-0.2, 0.6, 0.2, 0.0), 10, 4.0",
        Helper::DeMandelbox => "p, -1.5, 12, 0.5, 1.0",
    };
    let call = format!("{}({args})", helper.name());
    if helper.returns_pair() {
        format!("{call}.x + {call}.y")
    } else {
        call
    }
}

/// Every helper, followed by a compute entry point that calls each one and stores the sum, so none is dead code.
fn wgsl_module_calling_all() -> String {
    let mut source = wgsl::library::helpers_source(Helper::ALL);
    source.push_str("\n@group(0) @binding(0) var<storage, read_write> out: array<f32>;\n\n");
    source.push_str("@compute @workgroup_size(1)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {\n");
    source.push_str("    let p = vec3<f32>(id) * 0.1 + vec3<f32>(0.3, -0.2, 0.5);\n    var sum = 0.0;\n");
    for helper in Helper::ALL {
        source.push_str(&format!("    sum += {};\n", wgsl_call(helper)));
    }
    source.push_str("    out[id.x] = sum;\n}\n");
    source
}

#[test]
fn wgsl_module_with_every_helper_validates() {
    let source = wgsl_module_calling_all();
    for helper in Helper::ALL {
        assert!(source.contains(&format!("    sum += {}(", helper.name())), "{} is not called", helper.name());
    }
    if let Err(report) = validate_wgsl(&source) {
        panic!("{report}\n{source}");
    }
}

#[test]
fn each_wgsl_helper_validates_with_only_its_dependencies() {
    for helper in Helper::ALL {
        let source = wgsl::library::helpers_source([helper]);
        if let Err(report) = validate_wgsl(&source) {
            panic!("{}: {report}\n{source}", helper.name());
        }
    }
}

/// Whether `text` defines a function called `name` in the given language.
fn defines(text: &str, name: &str, opencl: bool) -> bool {
    if opencl {
        ["float ", "float2 "].iter().any(|ty| text.starts_with(&format!("{ty}{name}(")))
    } else {
        text.starts_with(&format!("fn {name}("))
    }
}

/// Names of the helpers whose calls appear in `text`, other than the definition itself.
fn helpers_called(text: &str, definer: Helper) -> Vec<Helper> {
    let body = &text[text.find('{').expect("a function body")..];
    Helper::ALL
        .into_iter()
        .filter(|&h| h != definer)
        .filter(|h| {
            let call = format!("{}(", h.name());
            // A helper name preceded by an identifier character is part of a longer name (`sd_box(` in `xsd_box(`).
            body.match_indices(&call)
                .any(|(at, _)| !body[..at].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_'))
        })
        .collect()
}

#[test]
fn every_helper_is_defined_in_both_languages_and_calls_only_its_dependencies() {
    for helper in Helper::ALL {
        for (language, text) in
            [("OpenCL C", opencl::library::helper_source(helper)), ("WGSL", wgsl::library::helper_source(helper))]
        {
            let name = helper.name();
            assert!(
                defines(text, name, language == "OpenCL C"),
                "{language} text of {name} does not define it:\n{text}"
            );
            assert!(text.ends_with("}\n"), "{language} text of {name} must be one function ending in a newline");
            assert_eq!(text.matches("\n}\n").count(), 1, "{language} text of {name} must hold one function");
            let mut called = helpers_called(text, helper);
            called.sort();
            let mut deps = helper.deps().to_vec();
            deps.sort();
            assert_eq!(called, deps, "{language} {name} calls helpers other than its dependencies");
        }
    }
}

#[test]
fn opencl_pair_helpers_return_float2_and_others_float() {
    for helper in Helper::ALL {
        let text = opencl::library::helper_source(helper);
        let return_type = if helper.returns_pair() { "float2 " } else { "float " };
        assert!(text.starts_with(return_type), "{}: expected return type {return_type}", helper.name());
        let wgsl_text = wgsl::library::helper_source(helper);
        let wgsl_return = if helper.returns_pair() { "-> vec2<f32> {" } else { "-> f32 {" };
        assert!(wgsl_text.lines().next().unwrap().ends_with(wgsl_return), "{}: expected {wgsl_return}", helper.name());
    }
}

#[test]
fn helpers_source_emits_dependencies_first_separated_by_blank_lines() {
    for (language, source) in [
        ("OpenCL C", opencl::library::helpers_source([Helper::DeMenger, Helper::SmoothMax])),
        ("WGSL", wgsl::library::helpers_source([Helper::DeMenger, Helper::SmoothMax])),
    ] {
        let order = with_dependencies([Helper::DeMenger, Helper::SmoothMax]);
        let positions: Vec<usize> = order
            .iter()
            .map(|h| {
                let definition = match (language, h.returns_pair()) {
                    ("WGSL", _) => format!("fn {}(", h.name()),
                    (_, true) => format!("float2 {}(", h.name()),
                    (_, false) => format!("float {}(", h.name()),
                };
                source.find(&definition).unwrap_or_else(|| panic!("{language}: {} missing", h.name()))
            })
            .collect();
        assert!(positions.windows(2).all(|w| w[0] < w[1]), "{language}: helpers out of order");
        assert_eq!(source.matches("}\n\n").count(), order.len() - 1, "{language}: one blank line between functions");
        assert!(!source.contains("\n\n\n"));
    }
}
