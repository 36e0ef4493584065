#!/usr/bin/env python3
"""Builds the fragment shaders Chromium renders, and render.mjs's job list, from exported packages.

Usage: prepare.py OUTDIR WIDTH HEIGHT SCENE...
Reads OUTDIR/SCENE/shadertoy/SCENE.glsl and OUTDIR/SCENE/glsl/{SCENE.glsl,README.md}; writes, per scene and target,
OUTDIR/SCENE/TARGET.frag (the colour image) and TARGET.mask.frag (white where sdf_raymarch hits, black where it
misses), and OUTDIR/jobs.json.

- shadertoy: the exported body between Shadertoy's own image-pass header and footer (shadertoy_header.glsl,
  shadertoy_footer.glsl), unchanged. Its mask variant replaces the one line writing the colour.
- glsl: `#version 300 es`, precision, the library, and a main() that builds the camera ray from the numbers the
  Shadertoy file's mainImage starts from (pivot, offset, tan_half) and writes sdf_display(hit.rgb). The uniforms are
  set to the defaults the README's parameter table lists, sdf_time to 0.
"""
import json
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
COLOUR_LINE = "fragColor = vec4(sdf_display(hit.rgb), 1.0);"
MASK_LINE = "fragColor = vec4(vec3(hit.w < 0.0 ? 0.0 : 1.0), 1.0);"


def number(text):
    return float(text.strip().rstrip("f"))


def camera_of(shadertoy):
    """The pivot, offset and tan_half literals of the Shadertoy mainImage (GLSL text, copied verbatim)."""
    found = {}
    for name, pattern in [("pivot", r"vec3 pivot = (vec3\([^;]*\));"), ("offset", r"vec3 offset = (vec3\([^;]*\));"),
                          ("tan_half", r"float tan_half = ([^;]*);")]:
        m = re.search(pattern, shadertoy)
        if not m:
            sys.exit(f"prepare.py: the Shadertoy file has no `{name}` (did mainImage change?)")
        found[name] = m.group(1)
    return found


def defaults_of(readme, library):
    """{uniform: default} from the README's parameter table; cross-checked against the library's uniforms."""
    uniforms = re.findall(r"^uniform float (\w+);", library, re.M)
    table = {}
    for line in readme.splitlines():
        cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
        if len(cells) < 2 or not line.lstrip().startswith("|"):
            continue
        for i, cell in enumerate(cells):
            if cell in uniforms and cell != "sdf_time":
                # The first number after the uniform's cell is its default.
                for rest in cells[i + 1:]:
                    try:
                        table[cell] = number(rest)
                        break
                    except ValueError:
                        continue
    # The library's own comment (`// `NAME`: default X, range A … B`) as a cross-check.
    comments = {m.group(1): number(m.group(2)) for m in
                re.finditer(r"^uniform float (\w+); // `[^`]*`: default ([-+0-9.eE]+)", library, re.M)}
    for u in uniforms:
        if u == "sdf_time":
            continue
        if u not in table:
            if u in comments:
                print(f"prepare.py: {u} is not in the README's table; using the library's comment", file=sys.stderr)
                table[u] = comments[u]
            else:
                sys.exit(f"prepare.py: no default for uniform {u}")
        elif u in comments and abs(comments[u] - table[u]) > 1e-9 * max(1.0, abs(table[u])):
            sys.exit(f"prepare.py: {u}: the README says {table[u]}, the library's comment {comments[u]}")
    table["sdf_time"] = 0.0
    return table


def glsl_page(library, cam, mask):
    write = ("frag_colour = vec4(vec3(hit.w < 0.0 ? 0.0 : 1.0), 1.0);" if mask
             else "frag_colour = vec4(sdf_display(hit.rgb), 1.0);")
    return f"""#version 300 es
precision highp float;
precision highp int;
{library}
// The harness: the Shadertoy package's camera at t = 0 (its numbers), no mouse.
uniform vec2 u_resolution;
out vec4 frag_colour;
void main() {{
    vec3 pivot = {cam['pivot']};
    vec3 offset = {cam['offset']};
    vec3 eye = pivot + offset;
    vec3 forward = normalize(pivot - eye);
    vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), forward));
    vec3 up = cross(forward, right);
    float tan_half = {cam['tan_half']};
    vec2 uv = (2.0 * gl_FragCoord.xy - u_resolution) / u_resolution.y;
    vec3 rd = normalize(forward + tan_half * (uv.x * right + uv.y * up));
    vec4 hit = sdf_raymarch(eye, rd, 2.0 * tan_half / u_resolution.y);
    {write}
}}
"""


def main():
    out, width, height, scenes = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
    header = (HERE / "shadertoy_header.glsl").read_text()
    footer = (HERE / "shadertoy_footer.glsl").read_text()
    jobs = []
    for scene in scenes:
        d = out / scene
        body = (d / "shadertoy" / f"{scene}.glsl").read_text()
        if body.count(COLOUR_LINE) != 1:
            sys.exit(f"prepare.py: {scene}: mainImage's colour line `{COLOUR_LINE}` not found once")
        (d / "shadertoy.frag").write_text(header + body + footer)
        (d / "shadertoy.mask.frag").write_text(header + body.replace(COLOUR_LINE, MASK_LINE) + footer)
        shadertoy_uniforms = {"iResolution": [width, height, 1.0], "iTime": 0.0, "iTimeDelta": 0.0,
                              "iFrameRate": 60.0, "iMouse": [0.0, 0.0, 0.0, 0.0], "iDate": [2026.0, 0.0, 1.0, 0.0],
                              "iSampleRate": 44100.0}
        for target in ["shadertoy"]:
            for variant in ["", ".mask"]:
                jobs.append({"frag": str(d / f"{target}{variant}.frag"), "out": str(d / f"{target}{variant}.png"),
                             "width": width, "height": height, "uniforms": shadertoy_uniforms, "ints": {"iFrame": 0}})

        library = (d / "glsl" / f"{scene}.glsl").read_text()
        readme = (d / "glsl" / "README.md").read_text()
        cam = camera_of(body)
        uniforms = defaults_of(readme, library)
        (d / "glsl.uniforms.json").write_text(json.dumps(uniforms, indent=2) + "\n")
        uniforms = dict(uniforms, u_resolution=[width, height])
        for variant, mask in [("", False), (".mask", True)]:
            (d / f"glsl{variant}.frag").write_text(glsl_page(library, cam, mask))
            jobs.append({"frag": str(d / f"glsl{variant}.frag"), "out": str(d / f"glsl{variant}.png"),
                         "width": width, "height": height, "uniforms": uniforms})
    (out / "jobs.json").write_text(json.dumps({"info": str(out / "webgl_renderer.json"), "jobs": jobs}, indent=1) + "\n")


if __name__ == "__main__":
    main()
