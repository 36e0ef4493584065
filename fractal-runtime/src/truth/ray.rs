//! The true first hit along one ray: march the scene's membership ([`super::member`]) with small steps and bisect the
//! first outside → inside crossing. No distance estimate is read: where a fractal is involved the membership value is
//! a sign only and the march takes fixed steps; where only exact primitives are, the value is their exact distance
//! (1-Lipschitz: `fractal-dsl/tests/lipschitz.rs`) and the march may step by it.

use fractal_dsl::eval::Env;

use super::member::{Member, SceneMembership};

/// Bisection halvings of a crossing's bracket: 2⁻⁴⁰ of a step is far below any pixel footprint.
const BISECTIONS: u32 = 40;
/// Share of an exact distance a step may take (a margin for the few bounds that are not exact, like the ellipsoid's).
const DISTANCE_SHARE: f64 = 0.9;

/// One ray through a scene's membership.
pub(crate) struct TruthRay<'a> {
    pub membership: &'a SceneMembership,
    pub env: &'a Env<'a, Member>,
    pub origin: [f64; 3],
    pub direction: [f64; 3],
}

impl TruthRay<'_> {
    pub fn point(&self, t: f64) -> [f64; 3] {
        [0, 1, 2].map(|i| self.origin[i] + self.direction[i] * t)
    }

    /// ≤ 0 where the ray is inside the scene at `t`.
    pub fn value(&self, t: f64) -> f64 {
        self.membership.value(self.point(t), self.env)
    }

    /// The first t in [start, end] where the ray enters the scene, stepping by `step(t)` (or by the exact distance
    /// where the value is one); `start` itself when the ray starts inside. Features thinner than the step along the
    /// ray can be stepped over.
    pub fn first_crossing(&self, start: f64, end: f64, step: impl Fn(f64) -> f64) -> Option<f64> {
        let mut t = start;
        let mut v = self.value(t);
        if v <= 0.0 {
            return Some(t);
        }
        while t < end {
            let next = (t + step(t).max(DISTANCE_SHARE * v)).min(end);
            let v_next = self.value(next);
            if v_next <= 0.0 {
                return Some(self.bisect(t, next));
            }
            (t, v) = (next, v_next);
        }
        None
    }

    /// The crossing between `outside` (value > 0) and `inside` (value ≤ 0), to 2⁻⁴⁰ of the bracket; the inside end,
    /// so the point returned is in the set.
    fn bisect(&self, mut outside: f64, mut inside: f64) -> f64 {
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (outside + inside);
            if self.value(mid) <= 0.0 {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        inside
    }
}
