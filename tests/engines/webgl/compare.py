#!/usr/bin/env python3
"""Compares Chromium's WebGL2 renders of the packages with `fractal render`'s image of the same view.

Usage: compare.py OUTDIR SCENE...  (tolerances: tolerances.json, a scene's tier there, or TOL_<LIMIT> variables)
Per scene, reads OUTDIR/SCENE/{reference.png, reference.depth.exr} and, per target (shadertoy, glsl),
TARGET.png (the colour) and TARGET.mask.png (white = sdf_raymarch hit). Writes TARGET.diff.png: |Δ| × 8 over pixels
both call fractal, magenta where only the reference hits, cyan where only the engine hits. Prints one row per scene
and target, writes OUTDIR/results.json, and exits 1 if a row fails a tolerance.

Figures:
  mask%   pixels where exactly one of the two images hits, as % of the reference's hit pixels
  mean    mean |Δ| per channel (R, G, B; 0..255) over pixels both images hit (checked: the worst channel)
  p95     95th percentile of |Δ| over those pixels and channels
  >8      % of those pixels whose largest channel |Δ| exceeds 8
  bias    the largest |mean signed Δ| of a channel over those pixels (a systematic shift: gamma, light, camera)
  bg      mean |Δ| over pixels both images miss (the background)
"""
import json
import os
import sys
from pathlib import Path

import numpy as np
from PIL import Image

LIMITS = ("mask_pct", "mean", "over8_pct", "bias", "bg_mean")


def tolerances():
    """{"default": {...}, "tiers": {...}, "scenes": {scene: tier}} from tolerances.json (or $WEBGL_TOLERANCES);
    TOL_<LIMIT> environment variables override every scene's value of that limit."""
    path = Path(os.environ.get("WEBGL_TOLERANCES", Path(__file__).resolve().parent / "tolerances.json"))
    spec = json.loads(path.read_text())
    return spec


def limits_for(spec, scene):
    tier = spec.get("scenes", {}).get(scene)
    limits = dict(spec["default"])
    if tier:
        limits.update(spec["tiers"][tier])
    for k in LIMITS:
        env = os.environ.get("TOL_" + k.upper())
        if env is not None:
            limits[k] = float(env)
    return tier or "default", limits


def rgb(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.int16)


def depth_mask(path):
    try:
        import OpenEXR
    except ImportError:
        sys.exit("compare.py: needs the OpenEXR package (pip install OpenEXR) to read the reference's depth AOV")
    with OpenEXR.File(str(path)) as f:
        channels = f.channels()
        z = np.asarray(channels["Z"].pixels, dtype=np.float32)
    return np.isfinite(z)


def compare(ref, ref_hit, eng, eng_hit):
    both = ref_hit & eng_hit
    neither = ~ref_hit & ~eng_hit
    diff = np.abs(ref - eng)
    n_ref = max(int(ref_hit.sum()), 1)
    row = {
        "ref_hit_px": int(ref_hit.sum()),
        "eng_hit_px": int(eng_hit.sum()),
        "only_ref_px": int((ref_hit & ~eng_hit).sum()),
        "only_eng_px": int((eng_hit & ~ref_hit).sum()),
    }
    row["mask_pct"] = 100.0 * (row["only_ref_px"] + row["only_eng_px"]) / n_ref
    d = diff[both]
    if d.size:
        row["mean_rgb"] = [float(x) for x in d.mean(axis=0)]
        row["mean"] = float(d.mean(axis=0).max())  # the worst channel's mean
        row["p95"] = float(np.percentile(d, 95))
        row["max"] = int(d.max())
        row["over8_pct"] = 100.0 * float((d.max(axis=1) > 8).mean())
        signed = (eng - ref)[both].mean(axis=0)
        row["bias_rgb"] = [float(x) for x in signed]
        row["bias"] = float(np.abs(signed).max())  # the worst channel's mean signed difference
    else:
        row.update(mean_rgb=[0.0] * 3, mean=0.0, p95=0.0, max=0, over8_pct=0.0, bias_rgb=[0.0] * 3, bias=0.0)
    row["bg_mean"] = float(diff[neither].mean()) if neither.any() else 0.0
    image = np.zeros(ref.shape, dtype=np.uint8)
    image[both] = np.clip(diff[both] * 8, 0, 255).astype(np.uint8)
    image[ref_hit & ~eng_hit] = [255, 0, 255]
    image[eng_hit & ~ref_hit] = [0, 255, 255]
    return row, image


def verdict(row, limits):
    return [k for k in LIMITS if row[k] > limits[k]]


def main():
    out, scenes = Path(sys.argv[1]), sys.argv[2:]
    spec = tolerances()
    results, failures = [], 0
    header = (f"{'scene':<22} {'target':<10} {'mask%':>6} {'meanR':>6} {'meanG':>6} {'meanB':>6} {'p95':>5} "
              f"{'>8 %':>6} {'bias':>5} {'bg':>5} {'hits(ref)':>9} {'tier':<8} verdict")
    print(header)
    print("-" * len(header))
    for scene in scenes:
        d = out / scene
        tier, limits = limits_for(spec, scene)
        try:
            ref = rgb(d / "reference.png")
            ref_hit = depth_mask(d / "reference.depth.exr")
        except Exception as e:  # a missing reference fails the scene
            print(f"{scene:<22} {'-':<10} no reference: {e}")
            failures += 1
            continue
        engines = {}
        for target in ("shadertoy", "glsl"):
            try:
                eng = rgb(d / f"{target}.png")
                eng_hit = rgb(d / f"{target}.mask.png")[..., 0] > 127
            except Exception as e:
                print(f"{scene:<22} {target:<10} no render: {e}")
                results.append({"scene": scene, "target": target, "error": str(e)})
                failures += 1
                continue
            if eng.shape != ref.shape:
                print(f"{scene:<22} {target:<10} size {eng.shape} != reference {ref.shape}")
                failures += 1
                continue
            engines[target] = (eng, eng_hit)
            row, image = compare(ref, ref_hit, eng, eng_hit)
            Image.fromarray(image).save(d / f"{target}.diff.png")
            failed = verdict(row, limits)
            failures += bool(failed)
            row.update(scene=scene, target=target, tier=tier, limits=limits, failed=failed)
            results.append(row)
            m = row["mean_rgb"]
            print(f"{scene:<22} {target:<10} {row['mask_pct']:6.2f} {m[0]:6.2f} {m[1]:6.2f} {m[2]:6.2f} "
                  f"{row['p95']:5.1f} {row['over8_pct']:6.2f} {row['bias']:5.2f} {row['bg_mean']:5.2f} "
                  f"{row['ref_hit_px']:9d} {tier:<8} {'FAIL ' + ','.join(failed) if failed else 'ok'}")
        if len(engines) == 2:  # the two packages share the library: they should agree with each other closely
            (a, ah), (b, bh) = engines["shadertoy"], engines["glsl"]
            row, _ = compare(a, ah, b, bh)
            row.update(scene=scene, target="st-vs-glsl", failed=[])
            results.append(row)
            m = row["mean_rgb"]
            print(f"{scene:<22} {'st~glsl':<10} {row['mask_pct']:6.2f} {m[0]:6.2f} {m[1]:6.2f} {m[2]:6.2f} "
                  f"{row['p95']:5.1f} {row['over8_pct']:6.2f} {row['bias']:5.2f} {row['bg_mean']:5.2f} "
                  f"{row['ref_hit_px']:9d} {'':<8} (info: the two engine images against each other)")
    (out / "results.json").write_text(json.dumps({"tolerances": spec, "rows": results}, indent=1) + "\n")
    print("\ntolerances (tolerances.json): mask% / mean |d| per channel (0..255) / % of hit pixels > 8 / |bias| per "
          "channel / background mean |d|")
    for name, lim in [("default", spec["default"])] + [(t, dict(spec["default"], **v)) for t, v in spec["tiers"].items()]:
        print(f"  {name:<8} " + "  ".join(f"{k} <= {lim[k]}" for k in LIMITS))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
