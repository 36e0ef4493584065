#!/usr/bin/env python3
"""Splits a scene's normal error between the render and the truth, for an escape-time map.

Reads the CSV `fractal accuracy SCENE --default-only --normals-csv FILE` writes (every pixel whose normal was
measured) and, from an f64 transcription of the scene's map (below; not the project's evaluator), recomputes at each
pixel:

- the render's own normal: the tetrahedral gradient of 0.5·|z|·ln|z| / |∇|z|| with taps one hit epsilon apart, as the
  ray program takes it (its angle to the CSV's render normal checks the transcription: near 0), and the same with
  every tap iterated as often as the hit's own orbit (the estimate's gradient without its jumps between bands);
- the gradient of the potential, Jᵀz (∇|zₙ|), at the render's hit and at the truth's, against the true normal.

With --out, writes the potential's gradient at each render hit as x,y,nx,ny,nz, which
`fractal accuracy SCENE --default-only --judge-normals FILE` judges as the budget judges a render's normals (its
cone-consistent p99 included, which this script cannot compute).

Usage: benches/normal_split.py FILE.csv MAP [--iterations N] [--bailout B] [--pixel-epsilon E] [--out FILE]
MAP: makin (Makin3D-2, scenes/fractal/makin_bulb.fractal), lkmitch (scenes/formulas/lkmitch_bulb.fractal), julia
(the quaternion Julia set in the slice w = 0, scenes/fractal/julia.fractal at t = 0: --constant -0.2,0.8,0
--iterations 16 --pixel-epsilon 0.05).
Needs numpy.
"""
import argparse
import csv

import numpy as np


def makin(z, c):
    x, y, w = z
    return np.array([x * x + 2 * y * w, -y * y - 2 * x * w, -w * w + 2 * x * y]) + c


def makin_jacobian(z):
    x, y, w = z
    return np.array([[2 * x, 2 * w, 2 * y], [-2 * w, -2 * y, -2 * x], [2 * y, 2 * x, -2 * w]])


def lkmitch(z, c):
    x, y, w = z
    return np.array([x * x - 2 * y * w, w * w + 2 * x * y, y * y - 2 * x * w]) + c


def lkmitch_jacobian(z):
    x, y, w = z
    return np.array([[2 * x, -2 * w, -2 * y], [2 * y, 2 * x, 2 * w], [-2 * w, 2 * y, -2 * x]])


def julia(z, c):
    # The quaternion square in the slice w = 0 (its w stays 0 for a constant with w = 0).
    x, y, w = z
    return np.array([x * x - y * y - w * w, 2 * x * y, 2 * x * w]) + c


def julia_jacobian(z):
    x, y, w = z
    return np.array([[2 * x, -2 * y, -2 * w], [2 * y, 2 * x, 0], [2 * w, 0, 2 * x]])


# name: (map, its Jacobian, whether c is the point (a Mandelbrot-style set) or a constant (a Julia set))
MAPS = {"makin": (makin, makin_jacobian, True), "lkmitch": (lkmitch, lkmitch_jacobian, True),
        "julia": (julia, julia_jacobian, False)}
TETRAHEDRON = np.array([[1, -1, -1], [-1, -1, 1], [-1, 1, -1], [1, 1, 1]], float)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("map", choices=sorted(MAPS))
    ap.add_argument("--iterations", type=int, default=12)
    ap.add_argument("--bailout", type=float, default=4.0)
    ap.add_argument("--pixel-epsilon", type=float, default=0.1)
    ap.add_argument("--out", help="write the potential's gradient at the render's hits here, for --judge-normals")
    ap.add_argument("--constant", default="0,0,0", help="a Julia set's constant c, x,y,z")
    a = ap.parse_args()
    step, jacobian, mandelbrot = MAPS[a.map]
    constant = np.array([float(v) for v in a.constant.split(",")])

    def orbit(p, steps=None):
        # As the formula's orbit: stops once |z| passes the bailout or after the iterations; given `steps`, after
        # exactly that many.
        z, J, n = p.copy(), np.eye(3), 0
        while n < steps if steps else n < a.iterations and np.linalg.norm(z) <= a.bailout:
            J = jacobian(z) @ J + (np.eye(3) if mandelbrot else 0)
            z = step(z, p if mandelbrot else constant)
            n += 1
        return z, J, n

    def estimate(p, steps=None):
        z, J, _ = orbit(p, steps)
        r = np.linalg.norm(z)
        return 0.5 * r * np.log(r) / np.linalg.norm(J.T @ z / r)

    def tetrahedral(p, h, steps=None):
        g = sum(k * estimate(p + k * h, steps) for k in TETRAHEDRON)
        return g / np.linalg.norm(g)

    def potential(p):
        z, J, _ = orbit(p)
        g = J.T @ z
        return g / np.linalg.norm(g)

    def angle(u, v):
        return np.degrees(np.arccos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1)))

    def facing(n, d):
        return -n if n @ d > 0 else n

    rows = list(csv.DictReader(open(a.csv)))
    mixed, away = 0, 0
    potentials = []
    figures = {k: [] for k in ["render", "transcription", "estimate within the hit's band", "potential at the render's hit", "potential at the truth's hit"]}
    for r in rows:
        o = np.array([float(r[k]) for k in ("ox", "oy", "oz")])
        d = np.array([float(r[k]) for k in ("dx", "dy", "dz")])
        rn = np.array([float(r[k]) for k in ("rnx", "rny", "rnz")])
        tn = np.array([float(r[k]) for k in ("tnx", "tny", "tnz")])
        tr, tt = float(r["t_render"]), float(r["t_truth"])
        footprint = float(r["footprint"]) / tt
        hit = o + d * tr
        figures["render"].append(float(r["centre_deg"]))
        h = a.pixel_epsilon * footprint * tr
        figures["transcription"].append(angle(tetrahedral(hit, h), rn))
        # The taps at the hit's own iteration count: the estimate's gradient without the jumps between bands.
        band = orbit(hit)[2]
        mixed += any(orbit(hit + k * h)[2] != band for k in TETRAHEDRON)
        figures["estimate within the hit's band"].append(angle(facing(tetrahedral(hit, h, band), d), tn))
        at_hit = facing(potential(hit), d)
        figures["potential at the render's hit"].append(angle(at_hit, tn))
        potentials.append((r["x"], r["y"], at_hit))
        away += rn @ d > 0
        figures["potential at the truth's hit"].append(angle(facing(potential(o + d * tt), d), tn))
    print(f"{len(rows)} pixels, {away} of them with a render normal facing away from the camera; degrees against the true normal at the pixel's centre (transcription: against the render's)")
    if a.out:
        open(a.out, "w").write("".join(f"{x},{y},{n[0]},{n[1]},{n[2]}\n" for x, y, n in potentials))
    print(f"  {mixed} pixels' normal taps escape after different numbers of iterations")
    for name, v in figures.items():
        v = np.array(v)
        print(f"  {name:30s} median {np.median(v):6.2f}  p90 {np.percentile(v, 90):6.2f}  p99 {np.percentile(v, 99):6.2f}")


if __name__ == "__main__":
    main()
