//! Plain value types of geometry and ranges: [`Interval`] (a closed range of numbers, with conservative arithmetic)
//! and [`Aabb`] (an axis-aligned box). The analyses compute them; vocabulary declarations state bounds in them.

/// A closed range of values; infinite ends mean no limit is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// Multiplies two interval ends, reading 0 · ∞ as 0: an infinite end is a limit no finite value reaches, and any
/// finite value times 0 is 0.
fn mul_end(a: f64, b: f64) -> f64 {
    if a == 0.0 || b == 0.0 {
        0.0
    } else {
        a * b
    }
}

impl Interval {
    /// Every value (and the answer when nothing better is known).
    pub const ENTIRE: Interval = Interval { lo: f64::NEG_INFINITY, hi: f64::INFINITY };
    /// The range of `t`: scenes start at time 0 and run for as long as they are shown.
    pub const TIME: Interval = Interval { lo: 0.0, hi: f64::INFINITY };

    /// The interval between `a` and `b` in either order; a NaN end gives [`Interval::ENTIRE`].
    pub fn new(a: f64, b: f64) -> Interval {
        if a.is_nan() || b.is_nan() {
            Interval::ENTIRE
        } else {
            Interval { lo: a.min(b), hi: a.max(b) }
        }
    }
    pub fn point(v: f64) -> Interval {
        Interval::new(v, v)
    }
    pub fn is_point(self) -> bool {
        self.lo == self.hi
    }
    /// Both ends finite.
    pub fn is_finite(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
    pub fn contains(self, v: f64) -> bool {
        self.lo <= v && v <= self.hi
    }
    pub fn width(self) -> f64 {
        self.hi - self.lo
    }
    /// The largest magnitude of any value in the interval.
    pub fn max_abs(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
    /// The smallest magnitude of any value in the interval (0 when it contains 0).
    pub fn min_abs(self) -> f64 {
        if self.contains(0.0) {
            0.0
        } else {
            self.lo.abs().min(self.hi.abs())
        }
    }
    /// The smallest interval containing both.
    pub fn hull(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.max(o.hi))
    }

    pub fn abs(self) -> Interval {
        Interval::new(self.min_abs(), self.max_abs())
    }
    pub fn sqrt(self) -> Interval {
        if self.lo < 0.0 {
            // sqrt of a negative value is NaN, which no interval contains.
            return Interval::ENTIRE;
        }
        Interval::new(self.lo.sqrt(), self.hi.sqrt())
    }
    pub fn min(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.min(o.hi))
    }
    pub fn max(self, o: Interval) -> Interval {
        Interval::new(self.lo.max(o.lo), self.hi.max(o.hi))
    }
    /// `max(x, lo).min(hi)`, as [`crate::ir::Func::Clamp`] evaluates.
    pub fn clamp(self, lo: Interval, hi: Interval) -> Interval {
        self.max(lo).min(hi)
    }
    /// `a + (b − a)·t`, as [`crate::ir::Func::Mix`] evaluates.
    pub fn mix(self, b: Interval, t: Interval) -> Interval {
        self + (b - self) * t
    }
    pub fn sin(self) -> Interval {
        use std::f64::consts::FRAC_PI_2;
        self.periodic(f64::sin, FRAC_PI_2, -FRAC_PI_2)
    }
    pub fn cos(self) -> Interval {
        use std::f64::consts::PI;
        self.periodic(f64::cos, 0.0, PI)
    }
    /// A 2π-periodic function with its peaks at `peak` + 2kπ and troughs at `trough` + 2kπ, monotone in between.
    fn periodic(self, f: fn(f64) -> f64, peak: f64, trough: f64) -> Interval {
        use std::f64::consts::TAU;
        if !self.is_finite() || self.width() >= TAU {
            return Interval::new(-1.0, 1.0);
        }
        let has = |at: f64| at + ((self.lo - at) / TAU).ceil() * TAU <= self.hi;
        let (a, b) = (f(self.lo), f(self.hi));
        let hi = if has(peak) { 1.0 } else { a.max(b) };
        let lo = if has(trough) { -1.0 } else { a.min(b) };
        // The extremum test itself rounds: widen by a few ulps so a value computed at a point near a turn stays inside.
        Interval::new(lo - 4.0 * f64::EPSILON, hi + 4.0 * f64::EPSILON)
            .clamp(Interval::point(-1.0), Interval::point(1.0))
    }
    /// `powf(self, e)`. Exact cases: a constant integer exponent (any base), a constant exponent with a non-negative
    /// base, and a varying exponent with a positive base (through exp(e·ln x)); anything that can be NaN is
    /// [`Interval::ENTIRE`].
    pub fn pow(self, e: Interval) -> Interval {
        if e.is_point() {
            let n = e.lo;
            if n == 0.0 {
                return Interval::point(1.0);
            }
            if n.fract() == 0.0 && n.is_finite() {
                let even = (n / 2.0).fract() == 0.0;
                if n > 0.0 {
                    return if even {
                        Interval::new(self.min_abs().powf(n), self.max_abs().powf(n))
                    } else {
                        Interval::new(self.lo.powf(n), self.hi.powf(n))
                    };
                }
                if self.contains(0.0) {
                    return Interval::ENTIRE;
                }
                return if even {
                    Interval::new(self.max_abs().powf(n), self.min_abs().powf(n))
                } else {
                    Interval::new(self.hi.powf(n), self.lo.powf(n))
                };
            }
            if self.lo < 0.0 {
                return Interval::ENTIRE;
            }
            return Interval::new(self.lo.powf(n), self.hi.powf(n));
        }
        if self.lo < 0.0 {
            return Interval::ENTIRE;
        }
        let log = Interval::new(self.lo.ln(), self.hi.ln());
        let p = e * log;
        // exp(e·ln x) and powf(x, e) round differently: widen by a relative margin far above either's error.
        Interval::new(p.lo.exp() * (1.0 - 1e-12), p.hi.exp() * (1.0 + 1e-12))
    }
}

impl core::ops::Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl core::ops::Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::new(self.lo + o.lo, self.hi + o.hi)
    }
}

impl core::ops::Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        self + -o
    }
}

impl core::ops::Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let ends = [mul_end(self.lo, o.lo), mul_end(self.lo, o.hi), mul_end(self.hi, o.lo), mul_end(self.hi, o.hi)];
        Interval::new(
            ends.iter().copied().fold(f64::INFINITY, f64::min),
            ends.iter().copied().fold(-f64::INFINITY, f64::max),
        )
    }
}

impl core::ops::Div for Interval {
    type Output = Interval;
    /// Unbounded when the divisor's range contains 0.
    fn div(self, o: Interval) -> Interval {
        if o.contains(0.0) {
            return Interval::ENTIRE;
        }
        // Quotients of the ends directly (not times a reciprocal, which rounds twice): division rounds monotonically.
        let ends = [self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi];
        if ends.iter().any(|v| v.is_nan()) {
            return Interval::ENTIRE;
        }
        Interval::new(
            ends.iter().copied().fold(f64::INFINITY, f64::min),
            ends.iter().copied().fold(-f64::INFINITY, f64::max),
        )
    }
}

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Aabb {
        Aabb { min, max }
    }
    /// The box [−half, half] per axis.
    pub fn centered(half: [f64; 3]) -> Aabb {
        Aabb { min: half.map(|h| -h), max: half }
    }
    /// The cube [−half, half]³.
    pub fn cube(half: f64) -> Aabb {
        Aabb::centered([half; 3])
    }
    pub fn center(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| 0.5 * (self.min[i] + self.max[i]))
    }
    pub fn half_extents(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| 0.5 * (self.max[i] - self.min[i]))
    }
    pub fn is_finite(&self) -> bool {
        self.min.iter().chain(&self.max).all(|v| v.is_finite())
    }
    /// Whether `p` lies inside or on the box.
    pub fn contains(&self, p: [f64; 3]) -> bool {
        (0..3).all(|i| self.min[i] <= p[i] && p[i] <= self.max[i])
    }
    /// The smallest box containing both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb { min: [0, 1, 2].map(|i| self.min[i].min(o.min[i])), max: [0, 1, 2].map(|i| self.max[i].max(o.max[i])) }
    }
    /// The overlap of both. Disjoint boxes bound an empty shape; the result is then a flat box between them (any box
    /// bounds nothing), so the extents never go negative.
    pub fn intersection(&self, o: &Aabb) -> Aabb {
        let mut b = Aabb {
            min: [0, 1, 2].map(|i| self.min[i].max(o.min[i])),
            max: [0, 1, 2].map(|i| self.max[i].min(o.max[i])),
        };
        for i in 0..3 {
            if b.min[i] > b.max[i] {
                let mid = 0.5 * (b.min[i] + b.max[i]);
                b.min[i] = mid;
                b.max[i] = mid;
            }
        }
        b
    }
    /// Grown by `by[i]` on both sides of axis i.
    pub fn grow3(&self, by: [f64; 3]) -> Aabb {
        Aabb { min: [0, 1, 2].map(|i| self.min[i] - by[i]), max: [0, 1, 2].map(|i| self.max[i] + by[i]) }
    }
    /// Grown by `by` on every side.
    pub fn grow(&self, by: f64) -> Aabb {
        self.grow3([by; 3])
    }
    /// The box swept when moved by any offset whose components lie in `lo[i]..=hi[i]`.
    pub fn translate(&self, lo: [f64; 3], hi: [f64; 3]) -> Aabb {
        Aabb { min: [0, 1, 2].map(|i| self.min[i] + lo[i]), max: [0, 1, 2].map(|i| self.max[i] + hi[i]) }
    }
    /// The box scaled about the origin by a factor `s`.
    pub fn scale(&self, s: f64) -> Aabb {
        let a = self.min.map(|v| v * s);
        let b = self.max.map(|v| v * s);
        Aabb { min: [0, 1, 2].map(|i| a[i].min(b[i])), max: [0, 1, 2].map(|i| a[i].max(b[i])) }
    }
    pub fn corners(&self) -> [[f64; 3]; 8] {
        std::array::from_fn(|k| [0, 1, 2].map(|i| if k >> i & 1 == 0 { self.min[i] } else { self.max[i] }))
    }
    /// The box of a set of points (`None` for none).
    pub fn of_points(points: impl IntoIterator<Item = [f64; 3]>) -> Option<Aabb> {
        points.into_iter().map(|p| Aabb { min: p, max: p }).reduce(|a, b| a.union(&b))
    }
}

impl Aabb {
    /// The box of this box rotated by any angle in `angle` about the unit axis `k`.
    pub fn rotated(&self, k: [f64; 3], angle: Interval) -> Option<Aabb> {
        if angle.is_point() && angle.is_finite() {
            let (s, c) = angle.lo.sin_cos();
            return Aabb::of_points(self.corners().map(|p| rodrigues(p, k, s, c)));
        }
        // Any angle: the shape sweeps around the axis. For a coordinate axis the swept set is a cylinder; otherwise
        // a ball.
        let corners = self.corners();
        match k.iter().position(|&c| c.abs() == 1.0) {
            Some(i) => {
                let radius = corners
                    .iter()
                    .map(|p| ((0..3).filter(|&j| j != i).map(|j| p[j] * p[j]).sum::<f64>()).sqrt())
                    .fold(0.0, f64::max);
                let mut min = [-radius; 3];
                let mut max = [radius; 3];
                min[i] = self.min[i];
                max[i] = self.max[i];
                Some(Aabb { min, max })
            }
            None => {
                let radius =
                    corners.iter().map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).fold(0.0, f64::max);
                Some(Aabb::cube(radius))
            }
        }
    }
}

/// `p` rotated by the angle whose sine and cosine are `s`, `c` about the unit axis `k`.
fn rodrigues(p: [f64; 3], k: [f64; 3], s: f64, c: f64) -> [f64; 3] {
    let cross = [k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]];
    let dot = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
    [0, 1, 2].map(|i| p[i] * c + cross[i] * s + k[i] * dot * (1.0 - c))
}

/// A shape's bound and how its distance relates to it (see `analyse::bounds`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    /// The box the shape lies in; `None` when unbounded.
    pub aabb: Option<Aabb>,
    /// Outside the box, the node's distance is at least `reach` × the distance to the box (0 < reach ≤ 1; 0 when
    /// nothing is known). Growing operations divide by it.
    pub reach: f64,
    /// Whether the node's distance is at least the box's signed distance everywhere, inside the box too: then a union
    /// guard that skips the node never changes the union's value.
    pub exact_guard: bool,
}

impl Bound {
    pub const UNBOUNDED: Bound = Bound { aabb: None, reach: 0.0, exact_guard: false };

    /// The bound of an exact distance inside `aabb`.
    pub fn exact(aabb: Aabb) -> Bound {
        Bound { aabb: Some(aabb), reach: 1.0, exact_guard: true }.map(Some)
    }
    /// The box mapped by `f`, keeping the reach; unbounded when `f` or the result is not a finite box.
    pub fn map(self, f: impl FnOnce(Aabb) -> Option<Aabb>) -> Bound {
        match self.aabb.and_then(f) {
            Some(b) if b.is_finite() => Bound { aabb: Some(b), ..self },
            _ => Bound::UNBOUNDED,
        }
    }
    /// The bound of `{d − by ≤ 0}`: the box grown by `by`/reach.
    pub fn grown(self, by: f64) -> Bound {
        if by <= 0.0 {
            return self;
        }
        if self.reach <= 0.0 || !by.is_finite() {
            return Bound::UNBOUNDED;
        }
        let reach = self.reach;
        self.map(|b| Some(b.grow(by / reach)))
    }
    /// The bound of the union of shapes: the hull of their boxes (unbounded if any is).
    pub fn hull(all: &[Bound]) -> Bound {
        let mut out: Option<Bound> = None;
        for b in all {
            let Some(bx) = b.aabb else { return Bound::UNBOUNDED };
            out = Some(match out {
                None => *b,
                Some(o) => Bound {
                    aabb: o.aabb.map(|a| a.union(&bx)),
                    reach: o.reach.min(b.reach),
                    exact_guard: o.exact_guard && b.exact_guard,
                },
            });
        }
        out.unwrap_or(Bound::UNBOUNDED)
    }
    /// The bound of the intersection of shapes: the overlap of the bounded ones' boxes.
    pub fn overlap(all: &[Bound]) -> Bound {
        let boxes: Vec<(Aabb, f64)> = all.iter().filter_map(|b| b.aabb.map(|a| (a, b.reach))).collect();
        let Some(&(first, first_reach)) = boxes.first() else { return Bound::UNBOUNDED };
        let (mut aabb, mut reach) = (first, first_reach);
        for (b, r) in &boxes[1..] {
            aabb = aabb.intersection(b);
            reach = reach.min(*r);
        }
        // max(d_i) ≥ reach·max(dist to box_i), and the distance to the overlap of n axis-aligned boxes is at most √n
        // times the largest distance to one of them (per axis it is the largest of the per-axis gaps).
        let n = boxes.len() as f64;
        Bound { aabb: Some(aabb), reach: reach / n.sqrt(), exact_guard: false }
    }
}
