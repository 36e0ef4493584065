//! Live `param(..)` values: which parameter is selected and how the keys step it within its declared range. The values
//! are frame uniforms, so a change never recompiles anything.

use fractal_dsl::Scene;
use fractal_render::error::FrameError;
use fractal_render::frame::ParamValues;

/// Steps per range for ↑/↓; Shift steps five at a time.
const STEPS_PER_RANGE: f64 = 50.0;
const COARSE_STEPS: f64 = 5.0;

/// A scene's parameter values and the selected parameter.
#[derive(Clone, Debug)]
pub struct ParamControl {
    values: ParamValues,
    selected: usize,
}

impl ParamControl {
    /// The parameters of `scene`; those that `previous` also has (by name) keep their value, clamped to the new range.
    pub fn new(scene: &Scene, previous: Option<&ParamControl>) -> ParamControl {
        let mut values = ParamValues::defaults(scene);
        let mut selected = 0;
        if let Some(previous) = previous {
            for decl in values.decls().to_vec() {
                if let Some(old) = previous.values.get(&decl.name) {
                    // A value outside the new range is moved into it; `set` cannot fail after the clamp.
                    let _ = values.set(&decl.name, old.clamp(decl.min, decl.max));
                }
            }
            if let Some(name) = previous.selected_name() {
                selected = values.decls().iter().position(|d| d.name == name).unwrap_or(0);
            }
        }
        ParamControl { values, selected }
    }

    /// Sets a parameter by name; unknown names and values outside the range are errors.
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), FrameError> {
        self.values.set(name, value)
    }

    pub fn values(&self) -> &ParamValues {
        &self.values
    }

    fn selected_name(&self) -> Option<&str> {
        self.values.decls().get(self.selected).map(|d| d.name.as_str())
    }

    /// Selects the next (`+1`) or previous (`-1`) parameter, wrapping around.
    pub fn select(&mut self, direction: i32) -> Option<String> {
        let n = self.values.decls().len();
        if n == 0 {
            return None;
        }
        self.selected = (self.selected as i64 + direction as i64).rem_euclid(n as i64) as usize;
        self.describe()
    }

    /// Steps the selected parameter up (`+1`) or down (`-1`) by 1/50 of its range (1/10 when `coarse`), clamped to
    /// the range.
    pub fn nudge(&mut self, direction: f64, coarse: bool) -> Option<String> {
        let decl = self.values.decls().get(self.selected)?.clone();
        let step = (decl.max - decl.min) / STEPS_PER_RANGE * if coarse { COARSE_STEPS } else { 1.0 };
        let current = self.values.get(&decl.name).unwrap_or(decl.default);
        let next = (current + direction * step).clamp(decl.min, decl.max);
        let _ = self.values.set(&decl.name, next);
        self.describe()
    }

    /// Puts the selected parameter back to its default.
    pub fn reset(&mut self) -> Option<String> {
        let decl = self.values.decls().get(self.selected)?.clone();
        let _ = self.values.set(&decl.name, decl.default);
        self.describe()
    }

    /// Every parameter as the panel shows it, and which is selected.
    pub fn rows(&self) -> (Vec<super::ui::ParamRow>, usize) {
        let rows = self
            .values
            .decls()
            .iter()
            .map(|d| super::ui::ParamRow {
                name: d.name.clone(),
                value: self.values.get(&d.name).unwrap_or(d.default),
                min: d.min,
                max: d.max,
            })
            .collect();
        (rows, self.selected)
    }

    /// Sets the parameter at `index` (clamped to its range) and selects it.
    pub fn set_index(&mut self, index: usize, value: f64) -> Option<String> {
        let decl = self.values.decls().get(index)?.clone();
        let _ = self.values.set(&decl.name, value.clamp(decl.min, decl.max));
        self.selected = index;
        self.describe()
    }

    /// Puts the parameter at `index` back to its default and selects it.
    pub fn reset_index(&mut self, index: usize) -> Option<String> {
        self.values.decls().get(index)?;
        self.selected = index;
        self.reset()
    }

    /// `name = value (min..max)` of the selected parameter.
    pub fn describe(&self) -> Option<String> {
        let decl = self.values.decls().get(self.selected)?;
        let value = self.values.get(&decl.name).unwrap_or(decl.default);
        Some(format!("{} = {:.4} ({}..{})", decl.name, value, decl.min, decl.max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{param, scene, sphere};

    fn two_params() -> Scene {
        scene(sphere(param("radius", 1.0, 0.5..1.5) + param("grow", 0.0, 0.0..1.0)))
    }

    #[test]
    fn keys_step_within_the_range() {
        let s = two_params();
        let mut c = ParamControl::new(&s, None);
        assert_eq!(c.describe().unwrap(), "radius = 1.0000 (0.5..1.5)");
        c.nudge(1.0, false);
        assert!((c.values().get("radius").unwrap() - 1.02).abs() < 1e-12);
        for _ in 0..100 {
            c.nudge(1.0, true);
        }
        assert_eq!(c.values().get("radius"), Some(1.5));
        c.reset();
        assert_eq!(c.values().get("radius"), Some(1.0));
        c.select(1);
        c.nudge(-1.0, false);
        assert_eq!(c.values().get("grow"), Some(0.0), "clamped at the minimum");
        assert!(c.select(1).unwrap().starts_with("radius"), "selection wraps");
        assert!(c.select(-1).unwrap().starts_with("grow"));
    }

    #[test]
    fn values_survive_a_reload_by_name() {
        let s = two_params();
        let mut c = ParamControl::new(&s, None);
        c.nudge(1.0, true);
        c.select(1);
        let narrower = scene(sphere(param("grow", 0.0, 0.0..1.0) + param("radius", 1.0, 0.5..1.05)));
        let d = ParamControl::new(&narrower, Some(&c));
        assert_eq!(d.values().get("radius"), Some(1.05), "kept, clamped to the new range");
        assert!(d.describe().unwrap().starts_with("grow"), "the selection follows the name");
        let none = ParamControl::new(&scene(sphere(1.0)), Some(&d));
        assert!(none.describe().is_none());
        let mut none = none;
        assert!(none.nudge(1.0, false).is_none() && none.select(1).is_none());
    }
}
