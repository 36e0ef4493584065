//! The fractal families, each declared once: name, constructor argument with its rule, iteration counts, the settings
//! that apply, the leaf call, the step factor, the bound and the membership test — and its builder function. The
//! parser, printer, validation, folding, bounds, evaluation and the ground truth read these declarations
//! ([`crate::ir::fractal`]).
//!
//! A step factor keeps a march from stepping through the surface: the inverse of the estimate's largest Lipschitz
//! ratio near the set, rounded down to 0.05 (`fractal-dsl/tests/dsl/lipschitz.rs`), or, for an estimate that takes
//! the map's azimuthal stretch (the Juliabulb at power 8, the Mandelbulb below power 4), the factor that keeps it
//! below the true distance in the estimator study (`fractal accuracy --estimators`). Figures and commands:
//! `docs/settings.md`, “Step factors of the fractal families”; the bounds' margins and reaches: “Bounds of the
//! fractal families”.

use crate::ir::fractal::FractalArgValue;
use crate::ir::{Expr, Fractal, Vec3Expr, Vec4Expr};
use families::*;

/// The declarations, and the table the parser looks names up in.
pub mod families {
    use crate::analyse::interval::range;
    use crate::formula::Leaf;
    use crate::geom::{Aabb, Interval};
    use crate::ir::fractal::{
        CallArg, FractalArg, FractalArgShape, FractalDecl, FractalRule, Iterations, LeafCallOf, Membership, Setting,
        MAX_ITERATIONS,
    };
    use crate::ir::prim::PrimBound;
    use crate::ir::Fractal;
    use crate::vocab::radius::{julia_radius, juliabulb_radius, mandelbox_half_extent, mandelbulb_radius};

    /// The family called `name` in scene source.
    pub fn by_name(name: &str) -> Option<&'static FractalDecl> {
        FRACTALS.iter().copied().find(|f| f.name == name)
    }

    /// Every family, in the order documentation lists them.
    pub static FRACTALS: &[&FractalDecl] = &[
        &MANDELBULB,
        &MENGER,
        &SIERPINSKI_TETRAHEDRON,
        &JULIA,
        &MANDELBOX,
        &JULIABULB,
        &OCTAHEDRAL_KIFS,
        &ICOSAHEDRAL_KIFS,
        &ESCAPE_TIME,
        &FOLD,
    ];

    fn count(f: &Fractal) -> CallArg {
        CallArg::Count(f.iterations_or_default())
    }
    fn num(e: Expr) -> CallArg {
        CallArg::Num(e)
    }
    use crate::ir::Expr;

    /// Escape-time estimators: outside the box the raw estimate keeps a measured share of the distance to the box, so
    /// the reach takes [`PLAIN_OUTSIDE`] × the step factor, or `outside` × it for an estimate that is a fraction of
    /// that one (measured: `docs/settings.md`, “Bounds of the fractal families”). Inside the set the estimate is not a
    /// distance, so union guards over them are not exact (they stay safe: the box holds the surface).
    fn escape_time_bound(f: &Fractal, radius: Option<f64>, outside: f64) -> Option<PrimBound> {
        radius.map(|r| PrimBound { aabb: Aabb::cube(r), reach: outside * f.step_factor_or_default() })
    }

    /// The plain escape-time estimate outside its box, in distances to the box: a little below the least share
    /// measured (`docs/settings.md`, “Bounds of the fractal families”).
    const PLAIN_OUTSIDE: f64 = 0.6;

    pub static MANDELBULB: FractalDecl = FractalDecl {
        name: "mandelbulb",
        doc: "the Mandelbulb of `power` (may animate; an integer 8 compiles to the trig-free polynomial form)",
        arg: FractalArg {
            name: "power",
            what: "mandelbulb power",
            shape: FractalArgShape::Number,
            rule: FractalRule::Between(2.0, 64.0),
        },
        iterations: Iterations { default: 8, min: 1, max: MAX_ITERATIONS },
        settings: &[(Setting::Bailout, 2.0)],
        call: |f| {
            let power = f.number().cloned().unwrap_or(Expr::Lit(8.0));
            let leaf = match power.as_lit() {
                Some(8.0) => return Some((Leaf::DeMandelbulb8, vec![count(f), num(f.bailout_or_default())])),
                _ if stretched_bulb(f) => Leaf::DeMandelbulbStretched,
                _ => Leaf::DeMandelbulb,
            };
            Some((leaf, vec![num(power), count(f), num(f.bailout_or_default())]))
        },
        step_factor: |f| if stretched_bulb(f) { 1.0 } else { bulb_step_factor(bulb_powers(f).lo) },
        bound: |f| {
            // The stretch divides the plain estimate by at most the power, below 4 (measured outside the box:
            // `docs/settings.md`, “Bounds of the fractal families”).
            let outside = if stretched_bulb(f) { PLAIN_OUTSIDE / 4.0 } else { PLAIN_OUTSIDE };
            escape_time_bound(f, mandelbulb_radius(bulb_powers(f).lo), outside)
        },
        membership: Membership {
            leaves: &[
                (Leaf::DeMandelbulb8, Leaf::InMandelbulb8),
                (Leaf::DeMandelbulb, Leaf::InMandelbulb),
                (Leaf::DeMandelbulbStretched, Leaf::InMandelbulb),
            ],
            approaches_limit: true,
            signed: &[
                (Leaf::DeMandelbulb8, Leaf::DeMandelbulb8Signed),
                (Leaf::DeMandelbulb, Leaf::DeMandelbulbSigned),
                (Leaf::DeMandelbulbStretched, Leaf::DeMandelbulbStretchedSigned),
            ],
        },
    };

    pub static MENGER: FractalDecl = FractalDecl {
        name: "menger",
        doc: "the Menger sponge of `levels` levels in [-1, 1]³",
        arg: FractalArg {
            name: "levels",
            what: "menger levels",
            shape: FractalArgShape::Levels,
            rule: FractalRule::Count,
        },
        // Each level multiplies the detail by 3, and 8 is already below f32 resolution.
        iterations: Iterations { default: 4, min: 1, max: 8 },
        settings: &[],
        call: |f| Some((Leaf::DeMenger, vec![count(f)])),
        step_factor: |_| 1.0,
        // The sponge's estimate is max(box, cuts) with the box [-1, 1]³: exact.
        bound: |_| PrimBound::exact(Aabb::cube(1.0)),
        membership: Membership { leaves: &[(Leaf::DeMenger, Leaf::InMenger)], approaches_limit: false, signed: &[] },
    };

    pub static SIERPINSKI_TETRAHEDRON: FractalDecl = FractalDecl {
        name: "sierpinski_tetrahedron",
        doc: "the Sierpinski tetrahedron of `levels` folds, vertices (1,1,1), (-1,-1,1), (1,-1,-1), (-1,1,-1)",
        arg: FractalArg {
            name: "levels",
            what: "sierpinski_tetrahedron levels",
            shape: FractalArgShape::Levels,
            rule: FractalRule::Count,
        },
        // Each fold halves the detail; 24 reaches f32 resolution.
        iterations: Iterations { default: 8, min: 1, max: 24 },
        settings: &[],
        call: |f| Some((Leaf::DeSierpinski, vec![count(f)])),
        step_factor: |_| 1.0,
        // The folds keep points in the tetrahedron's symmetry; far away the estimate is a plane distance, which falls
        // shortest of the distance to the cube along the diagonals (`docs/settings.md`, “Bounds of the fractal
        // families”).
        bound: |f| Some(PrimBound { aabb: Aabb::cube(1.0), reach: 0.32 * f.step_factor_or_default() }),
        membership: Membership {
            leaves: &[(Leaf::DeSierpinski, Leaf::InSierpinski)],
            approaches_limit: false,
            signed: &[],
        },
    };

    pub static JULIA: FractalDecl = FractalDecl {
        name: "julia",
        doc: "the quaternion Julia set z ← z² + c in the slice w = 0",
        arg: FractalArg {
            name: "c",
            what: "julia constant c",
            shape: FractalArgShape::Vec4,
            rule: FractalRule::Finite,
        },
        iterations: Iterations { default: 11, min: 1, max: MAX_ITERATIONS },
        settings: &[(Setting::Bailout, 4.0)],
        call: |f| {
            let mut args: Vec<CallArg> = f.arg_exprs().iter().cloned().map(num).collect();
            args.extend([count(f), num(f.bailout_or_default())]);
            Some((Leaf::DeJulia, args))
        },
        step_factor: |_| 0.85,
        bound: |f| {
            let norm = f.arg_exprs().iter().map(|e| range(e).max_abs().powi(2)).sum::<f64>().sqrt();
            escape_time_bound(f, julia_radius(norm), PLAIN_OUTSIDE)
        },
        membership: Membership {
            leaves: &[(Leaf::DeJulia, Leaf::InJulia)],
            approaches_limit: true,
            signed: &[(Leaf::DeJulia, Leaf::DeJuliaSigned)],
        },
    };

    pub static MANDELBOX: FractalDecl = FractalDecl {
        name: "mandelbox",
        doc: "the Mandelbox of `scale` (box fold at fold_limit, sphere fold with min_radius and fixed radius 1)",
        // Below |scale| 1.05 the estimator's convergence breaks down; above 8 it leaves f32 range.
        arg: FractalArg {
            name: "scale",
            what: "mandelbox scale",
            shape: FractalArgShape::Number,
            rule: FractalRule::AbsBetween(1.05, 8.0),
        },
        iterations: Iterations { default: 12, min: 1, max: MAX_ITERATIONS },
        settings: &[(Setting::MinRadius, 0.5), (Setting::FoldLimit, 1.0)],
        call: |f| {
            let scale = f.number().cloned().unwrap_or(Expr::Lit(2.0));
            let args = vec![num(scale), count(f), num(f.min_radius_or_default()), num(f.fold_limit_or_default())];
            Some((Leaf::DeMandelbox, args))
        },
        step_factor: |_| 0.75,
        bound: |f| {
            let scale = range(f.number()?);
            let fold = range(&f.fold_limit_or_default()).max_abs();
            let e = mandelbox_half_extent(scale, fold)?;
            // Measured far-field ratio of estimate to box distance: (s − 1)/(s + 1) for s > 1, 1 for s < −1.
            let ratio = if scale.lo > 1.0 { (scale.lo - 1.0) / (scale.lo + 1.0) } else { 1.0 };
            Some(PrimBound { aabb: Aabb::cube(e), reach: 0.95 * ratio * f.step_factor_or_default() })
        },
        membership: Membership {
            leaves: &[(Leaf::DeMandelbox, Leaf::InMandelbox)],
            approaches_limit: true,
            signed: &[],
        },
    };

    pub static JULIABULB: FractalDecl = FractalDecl {
        name: "juliabulb",
        doc: "the Julia set of the Mandelbulb's map, z ← z^power + c from z = p (`.power(p)`, default 8; may animate)",
        arg: FractalArg {
            name: "c",
            what: "juliabulb constant c",
            shape: FractalArgShape::Vec3,
            rule: FractalRule::Finite,
        },
        iterations: Iterations { default: 8, min: 1, max: MAX_ITERATIONS },
        settings: &[(Setting::Bailout, 2.0), (Setting::Power, 8.0)],
        call: |f| {
            let mut args: Vec<CallArg> = f.arg_exprs().iter().cloned().map(num).collect();
            args.extend([num(f.setting_or_default(Setting::Power)), count(f), num(f.bailout_or_default())]);
            Some((Leaf::DeJuliabulb, args))
        },
        step_factor: |f| juliabulb_step_factor(range(&f.setting_or_default(Setting::Power)).lo),
        bound: |f| {
            let norm = f.arg_exprs().iter().map(|e| range(e).max_abs().powi(2)).sum::<f64>().sqrt();
            escape_time_bound(f, juliabulb_radius(range(&f.setting_or_default(Setting::Power)).lo, norm), PLAIN_OUTSIDE)
        },
        membership: Membership {
            leaves: &[(Leaf::DeJuliabulb, Leaf::InJuliabulb)],
            approaches_limit: true,
            signed: &[(Leaf::DeJuliabulb, Leaf::DeJuliabulbSigned)],
        },
    };

    /// The scale of a KIFS: below 1.1 the copies barely shrink (the detail needs ever more iterations), above 4 they
    /// are dust.
    const KIFS_SCALE: FractalRule = FractalRule::Between(1.1, 4.0);
    /// scale^24 at scale 4 is 2^48: past it the detail is below f32 resolution anyway.
    const KIFS_ITERATIONS: Iterations = Iterations { default: 10, min: 1, max: 24 };

    /// The leaf arguments of a KIFS: scale, angle, iterations.
    fn kifs_args(f: &Fractal) -> Vec<CallArg> {
        let scale = f.number().cloned().unwrap_or(Expr::Lit(2.0));
        vec![num(scale), num(f.setting_or_default(Setting::Angle)), count(f)]
    }

    /// A kaleidoscopic IFS's set lies in the unit ball and its estimate is a true lower bound (`kifs_orbit` in
    /// `formula/estimate.rs`): the step factor is 1, and outside the box the estimate is at least |p| − 1, at least the
    /// distance to the box.
    fn kifs_bound(_: &Fractal) -> Option<PrimBound> {
        Some(PrimBound { aabb: Aabb::cube(1.0), reach: 0.95 })
    }

    /// A KIFS family: every one takes a scale, an angle and its own estimator and membership leaves.
    const fn kifs(
        name: &'static str,
        doc: &'static str,
        what: &'static str,
        call: fn(&Fractal) -> Option<LeafCallOf>,
        leaves: &'static [(Leaf, Leaf)],
    ) -> FractalDecl {
        FractalDecl {
            name,
            doc,
            arg: FractalArg { name: "scale", what, shape: FractalArgShape::Number, rule: KIFS_SCALE },
            iterations: KIFS_ITERATIONS,
            settings: &[(Setting::Angle, 0.0)],
            call,
            step_factor: |_| 1.0,
            bound: kifs_bound,
            membership: Membership { leaves, approaches_limit: false, signed: &[] },
        }
    }

    pub static OCTAHEDRAL_KIFS: FractalDecl = kifs(
        "octahedral_kifs",
        "a kaleidoscopic IFS with octahedral folds, scaled by `scale` about (1, 0, 0) (at 2: the Sierpinski \
         octahedron), turned by `.angle(a)` about z each iteration",
        "octahedral_kifs scale",
        |f| Some((Leaf::DeOctahedralKifs, kifs_args(f))),
        &[(Leaf::DeOctahedralKifs, Leaf::InOctahedralKifs)],
    );

    pub static ICOSAHEDRAL_KIFS: FractalDecl = kifs(
        "icosahedral_kifs",
        "a kaleidoscopic IFS with icosahedral folds, scaled by `scale` about a vertex (at φ² ≈ 2.618: the \
         icosahedron flake), turned by `.angle(a)` about z each iteration",
        "icosahedral_kifs scale",
        |f| Some((Leaf::DeIcosahedralKifs, kifs_args(f))),
        &[(Leaf::DeIcosahedralKifs, Leaf::InIcosahedralKifs)],
    );

    /// The iteration counts of a formula written in the scene language.
    const FORMULA_ITERATIONS: Iterations = Iterations { default: 10, min: 1, max: MAX_ITERATIONS };

    /// The bailout a formula's set lies within: at least 1, so the escape-time estimate 0.5·r·ln r/|∇r| is positive
    /// past it; at most 10⁶.
    pub const FORMULA_BAILOUT: (f64, f64) = (1.0, 1e6);

    /// A formula's step factor: the scene's `.step_factor(k)` (measured by `fractal accuracy --estimators SCENE`),
    /// else a safe half.
    fn formula_step_factor(_: &Fractal) -> f64 {
        crate::formula::user::UNMEASURED_STEP_FACTOR
    }

    pub static ESCAPE_TIME: FractalDecl = FractalDecl {
        name: "escape_time",
        doc: "an escape-time fractal of a map written in the scene language, z ← map(z, c) from z = c = p while \
              |z| ≤ bailout; `hybrid(f, g, ..)` applies several maps in turn. The estimate 0.5·|z|·ln|z|/|∇|z|| takes \
              the gradient of the orbit's last length, derived by the compiler",
        arg: FractalArg {
            name: "map",
            what: "escape_time map",
            shape: FractalArgShape::Formula,
            rule: FractalRule::Finite,
        },
        iterations: FORMULA_ITERATIONS,
        settings: &[(Setting::Bailout, 2.0)],
        call: |_| None,
        step_factor: formula_step_factor,
        // The set lies within the bailout: a point past it escapes before the first step. There the estimate is
        // 0.5·|p|·ln|p|/√3 (J = I), over a quarter of the distance to the ball for a bailout of at least 1.
        bound: |f| {
            let b = range(&f.bailout_or_default()).hi;
            b.is_finite().then(|| PrimBound { aabb: Aabb::cube(b), reach: 0.25 * f.step_factor_or_default() })
        },
        membership: Membership { leaves: &[], approaches_limit: true, signed: &[] },
    };

    pub static FOLD: FractalDecl = FractalDecl {
        name: "fold",
        doc: "a folding fractal (Mandelbox, KIFS kind) of a map written in the scene language, z ← map(z, c) from \
              z = c = p for every iteration; the estimate is (|z| − bailout)/‖J‖, J the orbit's Jacobian, or the \
              product of the map's own scales where it returns (z, scale)",
        arg: FractalArg { name: "map", what: "fold map", shape: FractalArgShape::Formula, rule: FractalRule::Finite },
        iterations: FORMULA_ITERATIONS,
        settings: &[(Setting::Bailout, 1.0)],
        call: |_| None,
        step_factor: formula_step_factor,
        bound: |_| None,
        membership: Membership { leaves: &[], approaches_limit: false, signed: &[] },
    };

    /// The Juliabulb's step factor for its lowest power: at power 8 from the estimator study, below it from the
    /// Lipschitz tests (`docs/settings.md`, “Step factors of the fractal families”).
    fn juliabulb_step_factor(lowest: f64) -> f64 {
        if lowest >= 8.0 {
            1.4
        } else {
            0.2
        }
    }

    /// Whether the Mandelbulb's estimate takes the map's azimuthal stretch
    /// ([`crate::formula::de_mandelbulb_stretched`]): where its power stays below 4. The stretch divides the estimate
    /// by up to the power near the poles, so a power that can grow past it keeps the plain estimate, which keeps more
    /// of the distance to the bound (`docs/settings.md`, “Bounds of the fractal families”).
    fn stretched_bulb(f: &Fractal) -> bool {
        f.number().is_some() && bulb_powers(f).hi < 4.0
    }

    /// The powers the Mandelbulb's expression can take (8 when it has none).
    fn bulb_powers(f: &Fractal) -> Interval {
        f.number().map_or(Interval::point(8.0), range)
    }

    /// The plain Mandelbulb estimate's step factor for its lowest power, from the Lipschitz ratios by power
    /// (`docs/settings.md`, “Step factors of the fractal families”).
    fn bulb_step_factor(lowest: f64) -> f64 {
        if lowest >= 8.0 {
            0.75
        } else if lowest >= 4.0 {
            0.65
        } else {
            0.35
        }
    }
}

/// Mandelbulb of the given power (may animate; an integer 8 compiles to the trig-free polynomial form).
pub fn mandelbulb(power: impl Into<Expr>) -> Fractal {
    Fractal::new(&MANDELBULB, FractalArgValue::Num(power.into()))
}
pub fn menger(levels: u32) -> Fractal {
    Fractal { iterations: Some(levels), ..Fractal::new(&MENGER, FractalArgValue::Levels) }
}
pub fn sierpinski_tetrahedron(levels: u32) -> Fractal {
    Fractal { iterations: Some(levels), ..Fractal::new(&SIERPINSKI_TETRAHEDRON, FractalArgValue::Levels) }
}
/// Quaternion Julia set for the constant `c`.
pub fn julia(c: impl Into<Vec4Expr>) -> Fractal {
    Fractal::new(&JULIA, FractalArgValue::Vec4(c.into()))
}
pub fn mandelbox(scale: impl Into<Expr>) -> Fractal {
    Fractal::new(&MANDELBOX, FractalArgValue::Num(scale.into()))
}
/// The Julia set of the Mandelbulb's map for the constant `c` (power 8 unless `.power(p)`).
pub fn juliabulb(c: impl Into<Vec3Expr>) -> Fractal {
    Fractal::new(&JULIABULB, FractalArgValue::Vec3(c.into()))
}
/// Kaleidoscopic IFS with octahedral folds.
pub fn octahedral_kifs(scale: impl Into<Expr>) -> Fractal {
    Fractal::new(&OCTAHEDRAL_KIFS, FractalArgValue::Num(scale.into()))
}
/// An escape-time fractal of a formula ([`crate::ir::formula`]); a hybrid when it has several maps.
pub fn escape_time(formula: crate::ir::formula::Formula) -> Fractal {
    Fractal::new(&ESCAPE_TIME, FractalArgValue::Formula(Box::new(formula)))
}
/// A folding fractal of a formula ([`crate::ir::formula`]).
pub fn fold(formula: crate::ir::formula::Formula) -> Fractal {
    Fractal::new(&FOLD, FractalArgValue::Formula(Box::new(formula)))
}
/// Kaleidoscopic IFS with icosahedral folds.
pub fn icosahedral_kifs(scale: impl Into<Expr>) -> Fractal {
    Fractal::new(&ICOSAHEDRAL_KIFS, FractalArgValue::Num(scale.into()))
}
