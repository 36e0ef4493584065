//! The ray program: every step of a pixel's ray — camera ray, bound clip, march with its variants, sign refinement,
//! normal, material, lights, shadows, occlusion, glow and fog — written once over any [`Num`](crate::number::Num), as
//! the leaf formulas are. The CPU renderer runs it in f32, f64 and [`crate::number::lanes::F32x8`] packets; what a
//! renderer adds is only how it finds its pixels, schedules rays and writes its image.
//!
//! The program reads a scene through [`SceneFns`] (distance and material, from whichever evaluator runs it), its
//! settings as [`Rules`] (fixed per scene: code the scene does not need is not run) and a frame's camera and lights
//! as a [`View`]. [`march`] owns steps 2–3b of the algorithm below, [`shade`] steps 4–6.
//!
//! Per pixel (x, y) of a w×h image:
//! 1. **Ray.** u = (2(x + 0.5) − w)/h, v = −(2(y + 0.5) − h)/h; ro = origin; rd = normalize(forward + u·right + v·up).
//! 2. **Clip** to the scene bound (slab test, direction components kept [`MIN_DIRECTION`] from 0); unbounded scenes
//!    march from 0 to max_distance.
//! 3. **March**: sphere tracing with a hit epsilon of at least [`T_SPACING`]·t, over-relaxed where the scene asks
//!    (Keinert et al. 2014), glow accumulated where the scene has it.
//!    **3b. Sign refinement** ([`crate::analyse::sign_refinement`]): near the surface a hit is a sign change, found
//!    by sign steps and refined by the Illinois false position.
//! 4. **Shading** at a hit: normal (tetrahedral; a scene with an escape-time formula takes its gradient, by
//!    forward-mode differentiation: [`crate::eval::plan::Plan::shaded_by_gradient`]), material, ambient occlusion,
//!    per light diffuse, specular and shadow, fog. 5. **Miss**: background. 6. **Glow** on hits and misses. 7. **Display**: clamp and gamma.

pub mod march;
pub mod pixel;
pub mod rules;
pub mod scene;
pub mod shade;

pub use rules::*;
pub use scene::SceneFns;

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// The ray program's constants, which a second spelling of the march or the shading would need.
    const CONSTANTS: [&str; 12] = [
        "T_SPACING",
        "MIN_DIRECTION",
        "GLOW_FALLOFF",
        "GLOW_NORM",
        "AO_START",
        "AO_SPAN",
        "AO_SAMPLES",
        "PROBE_SHARE",
        "PROBE_REACH",
        "MEMBERSHIP_STEP",
        "REFINE_STEPS",
        "REFINED_NORMAL_SHARE",
    ];

    fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("a readable source folder").flatten() {
            let path = entry.path();
            let name = entry.file_name();
            if path.is_dir() && name != "target" && !name.to_string_lossy().starts_with('.') {
                sources(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }

    /// Every step of the ray is written once, here: no other Rust file of the workspace names its constants.
    #[test]
    fn no_other_file_spells_a_step_of_the_ray() {
        let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
        let workspace = crate_dir.parent().expect("the crate sits in the workspace");
        let own = crate_dir.join("src").join("ray");
        let mut files = Vec::new();
        sources(workspace, &mut files);
        assert!(files.len() > 100, "only {} Rust files found under {}", files.len(), workspace.display());
        for file in files.iter().filter(|f| !f.starts_with(&own)) {
            let text = std::fs::read_to_string(file).expect("a readable source file");
            for name in CONSTANTS {
                let named = text.match_indices(name).any(|(i, _)| {
                    let before = text[..i].chars().next_back().is_some_and(|c| c.is_alphanumeric() || c == '_');
                    let after = text[i + name.len()..].chars().next().is_some_and(|c| c.is_alphanumeric() || c == '_');
                    !before && !after
                });
                assert!(!named, "{} names {name}: the ray program is written in fractal-dsl/src/ray/", file.display());
            }
        }
    }
}
