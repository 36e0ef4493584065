//! Effect and quality overrides: the viewer's changes to a scene's shadows, ambient occlusion, glow, fog, step budget
//! and hit epsilon. They are compiled into the kernels (a disabled effect costs nothing), so applying a changed
//! override means recompiling. Overrides outlive hot reloads: a reloaded file gets the user's changes again.

use fractal_dsl::{Fog, HitEpsilon, RenderSettings, Shadows};

/// The step budget the viewer lets the user reach, both ways.
const STEPS_RANGE: (u32, u32) = (8, 4096);

/// Soft-shadow sharpness used when the scene never chose one.
const DEFAULT_SOFT_SHADOW_K: f64 = 16.0;
const DEFAULT_AO_STRENGTH: f64 = 1.0;
const DEFAULT_GLOW: [f64; 3] = [1.0, 0.7, 0.4];
const DEFAULT_FOG_DENSITY: f64 = 0.05;

/// Which effects the user switched; `None` keeps the scene's own setting.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EffectOverrides {
    shadows: Option<Shadows>,
    ambient_occlusion: Option<Option<f64>>,
    glow: Option<Option<[f64; 3]>>,
    fog: Option<Option<Fog>>,
    max_steps: Option<u32>,
    epsilon: Option<HitEpsilon>,
    samples: Option<u32>,
}

impl EffectOverrides {
    /// `authored` with the overrides applied.
    pub fn apply(&self, authored: &RenderSettings) -> RenderSettings {
        let mut s = authored.clone();
        if let Some(shadows) = self.shadows {
            s.shadows = shadows;
        }
        if let Some(ao) = self.ambient_occlusion {
            s.ambient_occlusion = ao;
        }
        if let Some(glow) = self.glow {
            s.glow = glow;
        }
        if let Some(fog) = &self.fog {
            s.fog = fog.clone();
        }
        if let Some(steps) = self.max_steps {
            s.max_steps = steps;
        }
        if let Some(epsilon) = self.epsilon {
            s.epsilon = epsilon;
        }
        if let Some(samples) = self.samples {
            s.samples = samples;
        }
        s
    }

    /// At most `samples` rays per pixel (`None` keeps the scene's own).
    pub fn with_samples(mut self, samples: Option<u32>) -> EffectOverrides {
        self.samples = samples;
        self
    }

    /// `samples` rays per pixel (the panel's entry).
    pub fn set_samples(&mut self, samples: u32) {
        self.samples = Some(samples.max(1));
    }

    /// A step budget of `steps`, within 8..=4096 (the panel's entry).
    pub fn set_steps(&mut self, steps: u32) {
        self.max_steps = Some(steps.clamp(STEPS_RANGE.0, STEPS_RANGE.1));
    }

    /// The hit epsilon (the panel's entry), within the ranges [`EffectOverrides::scale_epsilon`] keeps.
    pub fn set_epsilon(&mut self, epsilon: HitEpsilon) {
        self.epsilon = Some(match epsilon {
            HitEpsilon::Fixed(e) => HitEpsilon::Fixed(e.clamp(1e-7, 1.0)),
            HitEpsilon::Pixel(k) => HitEpsilon::Pixel(k.clamp(1e-3, 64.0)),
        });
    }

    /// The step budget times `factor`, within 8..=4096.
    pub fn scale_steps(&mut self, authored: &RenderSettings, factor: f64) {
        let now = self.apply(authored).max_steps as f64;
        self.max_steps = Some((now * factor).round().clamp(STEPS_RANGE.0 as f64, STEPS_RANGE.1 as f64) as u32);
    }

    /// The hit epsilon (fixed or per pixel) times `factor`.
    pub fn scale_epsilon(&mut self, authored: &RenderSettings, factor: f64) {
        self.epsilon = Some(match self.apply(authored).epsilon {
            HitEpsilon::Fixed(e) => HitEpsilon::Fixed((e * factor).clamp(1e-7, 1.0)),
            HitEpsilon::Pixel(k) => HitEpsilon::Pixel((k * factor).clamp(1e-3, 64.0)),
        });
    }

    /// Shadows none → hard → soft → none; soft uses the scene's sharpness when it has one.
    pub fn cycle_shadows(&mut self, authored: &RenderSettings) {
        let soft_k = match authored.shadows {
            Shadows::Soft(k) => k,
            _ => DEFAULT_SOFT_SHADOW_K,
        };
        self.shadows = Some(match self.apply(authored).shadows {
            Shadows::None => Shadows::Hard,
            Shadows::Hard => Shadows::Soft(soft_k),
            Shadows::Soft(_) => Shadows::None,
        });
    }

    pub fn toggle_ambient_occlusion(&mut self, authored: &RenderSettings) {
        let on = self.apply(authored).ambient_occlusion.is_some();
        self.ambient_occlusion =
            Some(if on { None } else { Some(authored.ambient_occlusion.unwrap_or(DEFAULT_AO_STRENGTH)) });
    }

    pub fn toggle_glow(&mut self, authored: &RenderSettings) {
        let on = self.apply(authored).glow.is_some();
        self.glow = Some(if on { None } else { Some(authored.glow.unwrap_or(DEFAULT_GLOW)) });
    }

    /// Fog defaults to the background colour, so distant geometry fades into it.
    pub fn toggle_fog(&mut self, authored: &RenderSettings) {
        let on = self.apply(authored).fog.is_some();
        let default = || Fog { color: authored.background, density: DEFAULT_FOG_DENSITY };
        self.fog = Some(if on { None } else { Some(authored.fog.clone().unwrap_or_else(default)) });
    }
}

/// A short description of the effects in `settings`, e.g. `shadows soft(16), AO, fog`.
pub fn describe(settings: &RenderSettings) -> String {
    let mut parts = vec![match settings.shadows {
        Shadows::None => "no shadows".to_string(),
        Shadows::Hard => "hard shadows".to_string(),
        Shadows::Soft(k) => format!("soft shadows ({k})"),
    }];
    if let Some(ao) = settings.ambient_occlusion {
        parts.push(format!("AO {ao}"));
    }
    if settings.glow.is_some() {
        parts.push("glow".to_string());
    }
    if let Some(fog) = &settings.fog {
        parts.push(format!("fog {}", fog.density));
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shadows_cycle_and_keep_the_scene_sharpness() {
        let authored = RenderSettings { shadows: Shadows::Soft(8.0), ..Default::default() };
        let mut o = EffectOverrides::default();
        assert_eq!(o.apply(&authored), authored);
        o.cycle_shadows(&authored);
        assert_eq!(o.apply(&authored).shadows, Shadows::None);
        o.cycle_shadows(&authored);
        assert_eq!(o.apply(&authored).shadows, Shadows::Hard);
        o.cycle_shadows(&authored);
        assert_eq!(o.apply(&authored).shadows, Shadows::Soft(8.0));
        let plain = RenderSettings::default();
        let mut o = EffectOverrides::default();
        o.cycle_shadows(&plain);
        o.cycle_shadows(&plain);
        assert_eq!(o.apply(&plain).shadows, Shadows::Soft(DEFAULT_SOFT_SHADOW_K));
    }

    #[test]
    fn toggles_switch_and_switch_back() {
        let authored =
            RenderSettings { ambient_occlusion: Some(0.5), background: [0.1, 0.2, 0.3], ..Default::default() };
        let mut o = EffectOverrides::default();
        o.toggle_ambient_occlusion(&authored);
        o.toggle_glow(&authored);
        o.toggle_fog(&authored);
        let s = o.apply(&authored);
        assert_eq!(s.ambient_occlusion, None);
        assert_eq!(s.glow, Some(DEFAULT_GLOW));
        assert_eq!(s.fog, Some(Fog { color: [0.1, 0.2, 0.3], density: DEFAULT_FOG_DENSITY }));
        assert_eq!(describe(&s), "no shadows, glow, fog 0.05");
        o.toggle_ambient_occlusion(&authored);
        o.toggle_glow(&authored);
        o.toggle_fog(&authored);
        assert_eq!(o.apply(&authored), authored, "toggling twice restores the scene's settings");
    }
}
