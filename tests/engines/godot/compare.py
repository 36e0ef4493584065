#!/usr/bin/env python3
"""Compares the Godot shots in DIR (godot_*.png) with the project's render REF.png; prints the figures as text
and writes DIR/figures.json. Usage: compare.py DIR REF.png. Exit 1 if a check fails (limits below)."""
import json, sys
import numpy as np
from PIL import Image

HOLES_MAX = 0.2      # % of the fractal's pixels that one image has and the other has not (each way)
MEAN_MAX = 4.0       # mean |Godot - reference| per channel on pixels both call fractal (0-255)
P95_MAX = 16.0       # its 95th percentile, per channel
OCCLUSION_MIN = 99.8 # % of the cube/fractal overlap that shows the right colour in (b) and (c)
MAGENTA, GREEN = np.array([255, 0, 255]), np.array([0, 255, 0])

d, ref_path = sys.argv[1], sys.argv[2]
img = lambda n: np.asarray(Image.open(f'{d}/godot_{n}.png').convert('RGB')).astype(int)
near = lambda a, c, tol=2: (np.abs(a - c).max(axis=2) <= tol)
a, b, c = img('a'), img('b'), img('c')
ref = np.asarray(Image.open(ref_path).convert('RGB')).astype(int)
if ref.shape != a.shape:
    sys.exit(f'size differs: Godot {a.shape} reference {ref.shape}')
probe = img('probe')[a.shape[0] // 2, a.shape[1] // 2]

# The reference's fractal pixels: where its depth AOV (REF.depth.exr, beside REF.png) is finite.
try:
    import OpenEXR
except ImportError:
    sys.exit('compare.py: needs the OpenEXR package (pip install OpenEXR) to read the reference\'s depth AOV')
with OpenEXR.File(ref_path[:-len('.png')] + '.depth.exr') as exr:
    ref_m = np.isfinite(np.asarray(exr.channels()['Z'].pixels, dtype=np.float32)).reshape(ref.shape[:2])
bg = ref[~ref_m].mean(axis=0).round() if (~ref_m).any() else np.zeros(3)
god_m = ~near(a, MAGENTA)
n = max(int(ref_m.sum()), 1)
both = ref_m & god_m
holes = 100.0 * (ref_m & ~god_m).sum() / n
extra = 100.0 * (god_m & ~ref_m).sum() / n
diff = np.abs(a[both] - ref[both])
f = {
    'pixels': int(a.shape[0] * a.shape[1]), 'fractal_pixels_ref': n, 'fractal_pixels_godot': int(god_m.sum()),
    'reference_background': bg.tolist(), 'probe_albedo_0.5_0.2_0.8_on_canvas': probe.tolist(),
    'holes_pct': round(holes, 3), 'extra_pct': round(extra, 3),
    'mean_abs_diff_rgb': np.round(diff.mean(axis=0), 2).tolist() if both.any() else None,
    'p95_abs_diff_rgb': np.percentile(diff, 95, axis=0).tolist() if both.any() else None,
    'mean_rgb_godot': np.round(a[both].mean(axis=0), 1).tolist() if both.any() else None,
    'mean_rgb_reference': np.round(ref[both].mean(axis=0), 1).tolist() if both.any() else None,
}
# Occlusion: the cube alone gives its footprint; where it overlaps the fractal, (b) must show the cube
# (green) and (c) the fractal as in (a).
for shot, img_, cube_shot in (('b', b, 'cube_front'), ('c', c, 'cube_back')):
    over = near(img(cube_shot), GREEN) & god_m
    ok = near(img_, GREEN) if shot == 'b' else near(img_, a)
    f[f'overlap_pixels_{shot}'] = int(over.sum())
    f[f'occlusion_ok_pct_{shot}'] = round(100.0 * (ok & over).sum() / max(int(over.sum()), 1), 2)
checks = {
    'holes': holes <= HOLES_MAX and extra <= HOLES_MAX,
    'colour': both.any() and max(f['mean_abs_diff_rgb']) <= MEAN_MAX and max(f['p95_abs_diff_rgb']) <= P95_MAX,
    'cube in front hides the fractal (b)': f['overlap_pixels_b'] > 0 and f['occlusion_ok_pct_b'] >= OCCLUSION_MIN,
    'cube behind is hidden by the fractal (c)': f['overlap_pixels_c'] > 0 and f['occlusion_ok_pct_c'] >= OCCLUSION_MIN,
}
f['checks'] = {k: bool(v) for k, v in checks.items()}
json.dump(f, open(f'{d}/figures.json', 'w'), indent=1)
print(f"  fractal pixels: reference {n}, Godot {f['fractal_pixels_godot']} (reference's mean background {bg.tolist()})")
print(f"  holes (reference fractal, Godot background): {f['holes_pct']} %   extra (the other way): {f['extra_pct']} %"
      f"   [limit {HOLES_MAX} % each]")
print(f"  colour on {int(both.sum())} shared pixels: mean |diff| {f['mean_abs_diff_rgb']}, p95 {f['p95_abs_diff_rgb']}"
      f"   [limits {MEAN_MAX} / {P95_MAX}]")
print(f"  mean RGB: Godot {f['mean_rgb_godot']}, reference {f['mean_rgb_reference']}")
print(f"  occlusion: (b) cube in front shows on {f['occlusion_ok_pct_b']} % of {f['overlap_pixels_b']} overlap pixels;"
      f" (c) fractal over the cube behind on {f['occlusion_ok_pct_c']} % of {f['overlap_pixels_c']} [need {OCCLUSION_MIN} %]")
print(f"  probe: unshaded ALBEDO (0.5, 0.2, 0.8) reaches the canvas as {probe.tolist()}")
for k, v in checks.items():
    print(f"  {'PASS' if v else 'FAIL'}: {k}")
sys.exit(0 if all(checks.values()) else 1)
