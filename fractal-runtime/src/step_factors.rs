//! Step factors of formulas written in the scene language, measured and remembered. A formula's estimate is derived
//! by the compiler, but how far a march may trust it is measured: `fractal accuracy --estimators SCENE` runs the
//! estimator study on the scene's fractals (`truth::estimate`), takes 1 / the p99.9 ratio of estimate to true
//! distance at points anywhere near the set, rounded down to 0.05, and records it here, keyed by the formula's canonical text. A scene file loaded
//! later whose formula has no `.step_factor(k)` steps by the recorded factor, and says so; a formula with none steps by
//! half its estimate ([`UNMEASURED_STEP_FACTOR`]) with a warning naming the command.
//!
//! The record is a text file, one `factor<TAB>formula` line per formula, in `$FRACTAL_CACHE_DIR`, else
//! `$XDG_CACHE_HOME/fractal`, else `~/.cache/fractal`.

use std::path::PathBuf;

use fractal_dsl::formula::user::UNMEASURED_STEP_FACTOR;
use fractal_dsl::ir::formula::Formula;
use fractal_dsl::ir::fractal::STEP_FACTOR_RANGE;
use fractal_dsl::{Node, Scene};

const FILE: &str = "step-factors.tsv";

/// The folder the record lives in.
fn cache_dir() -> Option<PathBuf> {
    let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    var("FRACTAL_CACHE_DIR")
        .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("fractal")))
        .or_else(|| var("HOME").map(|d| d.join(".cache").join("fractal")))
}

/// The key a formula is recorded under: its canonical text.
pub fn key(formula: &Formula) -> String {
    fractal_dsl::print::formula_call(formula)
}

/// The recorded (key, factor) pairs; an unreadable record reads as empty.
fn read() -> Vec<(String, f64)> {
    let Some(path) = cache_dir().map(|d| d.join(FILE)) else { return Vec::new() };
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines()
        .filter_map(|line| {
            let (factor, key) = line.split_once('\t')?;
            let factor: f64 = factor.parse().ok()?;
            (factor > STEP_FACTOR_RANGE.0 && factor <= STEP_FACTOR_RANGE.1).then(|| (key.to_string(), factor))
        })
        .collect()
}

/// The factor recorded for `formula`, if any.
pub fn recorded(formula: &Formula) -> Option<f64> {
    let key = key(formula);
    read().into_iter().rev().find(|(k, _)| *k == key).map(|(_, f)| f)
}

/// Records `factor` for `formula`, replacing an earlier record; returns where it was written.
pub fn record(formula: &Formula, factor: f64) -> Result<PathBuf, String> {
    let dir = cache_dir().ok_or("no cache folder: set FRACTAL_CACHE_DIR or HOME")?;
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let key = key(formula);
    let mut lines: Vec<String> =
        read().into_iter().filter(|(k, _)| *k != key).map(|(k, f)| format!("{f}\t{k}")).collect();
    lines.push(format!("{factor}\t{key}"));
    let path = dir.join(FILE);
    std::fs::write(&path, lines.join("\n") + "\n").map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path)
}

/// The largest step factor the study records: past 1 a march steps beyond the estimate itself, and the study's points
/// do not stand for every point a ray meets near the surface (docs/formulas.md: the Burning Ship bulb at 1.45, from
/// its p99.9, sent 5.9 % of its rays through the surface).
pub const LARGEST_MEASURED: f64 = 1.0;

/// The step factor the study's ratios ask for: 1 / the largest of the p99.9 ratios given, rounded down to 0.05, at
/// least 0.05 and at most [`LARGEST_MEASURED`].
pub fn from_ratios(p999: impl IntoIterator<Item = f64>) -> Option<f64> {
    let worst = p999.into_iter().filter(|r| r.is_finite()).fold(f64::NAN, f64::max);
    if worst.is_nan() || worst <= 0.0 {
        return None;
    }
    let factor = ((1.0 / worst) * 20.0).floor() / 20.0;
    Some(factor.clamp(0.05, LARGEST_MEASURED.min(STEP_FACTOR_RANGE.1)))
}

/// Gives every formula of `scene` that sets no step factor its recorded one; returns a line per formula saying which
/// factor it steps by and where it came from (`file` names the scene in the advice).
pub fn apply_recorded(scene: &mut Scene, file: &str) -> Vec<String> {
    let mut notes = Vec::new();
    let record = read();
    each_formula(&mut scene.root, &mut |f| {
        let Some(formula) = f.formula() else { return };
        if f.step_factor.is_some() {
            return;
        }
        let key = key(formula);
        let short: String = key.chars().take(48).collect();
        match record.iter().rev().find(|(k, _)| *k == key) {
            Some(&(_, factor)) => {
                f.step_factor = Some(factor);
                notes
                    .push(format!("{short}…: steps by its measured factor {factor} (recorded by the estimator study)"));
            }
            None => notes.push(format!(
                "warning: {short}… has no measured step factor and steps by {UNMEASURED_STEP_FACTOR} of its estimate; \
                 measure one with `fractal accuracy --estimators {file}`, or set .step_factor(k)"
            )),
        }
    });
    notes
}

/// Calls `f` on every fractal of the tree.
fn each_formula(node: &mut Node, f: &mut dyn FnMut(&mut fractal_dsl::Fractal)) {
    match node {
        Node::Fractal(fr) => f(fr),
        Node::Op(op) => op.shapes.iter_mut().for_each(|s| each_formula(s, f)),
        Node::Material(child, _) => each_formula(child, f),
        Node::Prim(_) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 1 / the worst ratio, rounded down to 0.05 and kept within the range a scene may set; no finite ratio, none.
    #[test]
    fn the_factor_follows_the_worst_ratio() {
        assert_eq!(from_ratios([0.659, 0.5]), Some(LARGEST_MEASURED));
        assert_eq!(from_ratios([1.05, 0.5]), Some(0.95));
        assert_eq!(from_ratios([1.339]), Some(0.7));
        assert_eq!(from_ratios([218.0]), Some(0.05));
        assert_eq!(from_ratios([0.1]), Some(LARGEST_MEASURED));
        assert_eq!(from_ratios([f64::NAN]), None);
        assert_eq!(from_ratios([]), None);
    }

    /// A scene's formula without a factor gets a warning naming the command when nothing is recorded for it.
    #[test]
    fn an_unmeasured_formula_is_warned_about() {
        let mut scene = fractal_dsl::parse::parse_str("escape_time(|z, c| z * z.x + c * 0.987654321)").unwrap();
        let notes = apply_recorded(&mut scene, "my.fractal");
        assert_eq!(notes.len(), 1);
        assert!(notes[0].contains("fractal accuracy --estimators my.fractal"), "{}", notes[0]);
    }
}
