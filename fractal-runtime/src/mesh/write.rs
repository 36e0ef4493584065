//! Mesh files: binary glTF (`.glb`: positions, normals, vertex colours, indices), binary PLY (positions, normals,
//! 8-bit colours), binary STL (facet normals, no colour) and OBJ (positions with colours, normals). All are written in
//! glTF's right-handed frame: z mirrored, and triangle winding reversed with it so faces still point outwards.

use std::io::{self, Write};
use std::path::Path;

use serde_json::json;

use super::Mesh;

/// A mesh file format, chosen by the output's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Glb,
    Ply,
    Stl,
    Obj,
}

impl MeshFormat {
    pub const EXTENSIONS: &'static str = ".glb, .ply, .stl or .obj";

    pub fn from_path(path: &Path) -> Option<MeshFormat> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "glb" => Some(MeshFormat::Glb),
            "ply" => Some(MeshFormat::Ply),
            "stl" => Some(MeshFormat::Stl),
            "obj" => Some(MeshFormat::Obj),
            _ => None,
        }
    }
}

/// Writes `mesh` in `format` to `out`, turning it into glTF's frame in place first (see the module documentation):
/// nothing but the mesh is held in memory, however large.
pub fn write_mesh(mut mesh: Mesh, format: MeshFormat, out: &mut dyn Write) -> io::Result<()> {
    to_right_handed(&mut mesh);
    match format {
        MeshFormat::Glb => glb(&mesh, out),
        MeshFormat::Ply => ply(&mesh, out),
        MeshFormat::Stl => stl(&mesh, out),
        MeshFormat::Obj => obj(&mesh, out),
    }
}

/// z mirrored, winding reversed.
fn to_right_handed(mesh: &mut Mesh) {
    mesh.positions.iter_mut().chain(mesh.normals.iter_mut()).for_each(|v| v[2] = -v[2]);
    mesh.triangles.iter_mut().for_each(|t| t.swap(1, 2));
}

fn write_f32s<'a>(out: &mut dyn Write, values: impl IntoIterator<Item = &'a [f32; 3]>) -> io::Result<()> {
    for v in values {
        for c in v {
            out.write_all(&c.to_le_bytes())?;
        }
    }
    Ok(())
}

fn glb(m: &Mesh, out: &mut dyn Write) -> io::Result<()> {
    let n = m.positions.len();
    let (lo, hi) = m.positions.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
        ([0, 1, 2].map(|a| lo[a].min(p[a])), [0, 1, 2].map(|a| hi[a].max(p[a])))
    });
    let (lo, hi) = if n == 0 { ([0.0; 3], [0.0; 3]) } else { (lo, hi) };
    let (v, t) = (n * 12, m.triangles.len() * 12);
    let bin_len = 3 * v + t;
    // 5126: FLOAT, 5125: UNSIGNED_INT; 34962 / 34963: vertex / index buffer targets.
    let document = json!({
        "asset": { "version": "2.0", "generator": concat!("fractal ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "name": "fractal", "mesh": 0 }],
        "meshes": [{ "primitives": [{
            "attributes": { "POSITION": 0, "NORMAL": 1, "COLOR_0": 2 },
            "indices": 3,
            "mode": 4,
        }]}],
        "buffers": [{ "byteLength": bin_len }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": v, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": 2 * v, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": 3 * v, "byteLength": t, "target": 34963 },
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5126, "count": n, "type": "VEC3" },
            { "bufferView": 3, "componentType": 5125, "count": m.triangles.len() * 3, "type": "SCALAR" },
        ],
    });
    let mut json = serde_json::to_vec(&document).map_err(io::Error::other)?;
    // Chunks are 4-byte aligned: JSON padded with spaces; the binary chunk (whole f32s and u32s) already is.
    json.resize(json.len().next_multiple_of(4), b' ');
    let total = 12 + 8 + json.len() + 8 + bin_len;
    let total =
        u32::try_from(total).map_err(|_| io::Error::other("a .glb file is limited to 4 GiB: lower the resolution"))?;
    out.write_all(b"glTF")?;
    out.write_all(&2u32.to_le_bytes())?;
    out.write_all(&total.to_le_bytes())?;
    out.write_all(&(json.len() as u32).to_le_bytes())?;
    out.write_all(b"JSON")?;
    out.write_all(&json)?;
    out.write_all(&(bin_len as u32).to_le_bytes())?;
    out.write_all(b"BIN\0")?;
    write_f32s(out, &m.positions)?;
    write_f32s(out, &m.normals)?;
    write_f32s(out, &m.colours)?;
    for i in m.triangles.iter().flatten() {
        out.write_all(&i.to_le_bytes())?;
    }
    Ok(())
}

fn byte(c: f32) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

fn ply(m: &Mesh, out: &mut dyn Write) -> io::Result<()> {
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\ncomment fractal mesh, glTF frame (right-handed, y up)\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n\
         property float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        m.positions.len(),
        m.triangles.len()
    )?;
    for ((p, n), c) in m.positions.iter().zip(&m.normals).zip(&m.colours) {
        write_f32s(out, [p, n])?;
        out.write_all(&c.map(byte))?;
    }
    for t in &m.triangles {
        out.write_all(&[3])?;
        for i in t {
            out.write_all(&i.to_le_bytes())?;
        }
    }
    Ok(())
}

fn stl(m: &Mesh, out: &mut dyn Write) -> io::Result<()> {
    let mut header = [b' '; 80];
    let text = b"fractal mesh, glTF frame (right-handed, y up)";
    header[..text.len()].copy_from_slice(text);
    out.write_all(&header)?;
    out.write_all(&(m.triangles.len() as u32).to_le_bytes())?;
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let (u, v) = ([0, 1, 2].map(|k| b[k] - a[k]), [0, 1, 2].map(|k| c[k] - a[k]));
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let len = n.iter().map(|x| x * x).sum::<f32>().sqrt();
        let n = if len > 0.0 { n.map(|x| x / len) } else { [0.0; 3] };
        write_f32s(out, [&n, &a, &b, &c])?;
        out.write_all(&0u16.to_le_bytes())?;
    }
    Ok(())
}

fn obj(m: &Mesh, out: &mut dyn Write) -> io::Result<()> {
    writeln!(out, "# fractal mesh, glTF frame (right-handed, y up); vertex colours after positions")?;
    for (p, c) in m.positions.iter().zip(&m.colours) {
        writeln!(out, "v {} {} {} {} {} {}", p[0], p[1], p[2], c[0], c[1], c[2])?;
    }
    for n in &m.normals {
        writeln!(out, "vn {} {} {}", n[0], n[1], n[2])?;
    }
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> Mesh {
        Mesh {
            positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            normals: vec![[0.0, 1.0, 0.0]; 4],
            colours: vec![[1.0, 0.5, 0.0]; 4],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    fn bytes(format: MeshFormat) -> Vec<u8> {
        let mut out = Vec::new();
        write_mesh(tetrahedron(), format, &mut out).unwrap();
        out
    }

    #[test]
    fn every_format_writes_the_whole_mesh() {
        assert_eq!(tetrahedron().unmatched_edges(), 0);
        let stl = bytes(MeshFormat::Stl);
        assert_eq!(stl.len(), 84 + 4 * 50);
        let ply = bytes(MeshFormat::Ply);
        assert!(ply.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
        let obj = String::from_utf8(bytes(MeshFormat::Obj)).unwrap();
        assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 4);
        // Mirrored: the vertex at z = 1 is at z = −1, and the winding is reversed.
        assert!(obj.contains("v 0 0 -1 1 0.5 0\n") && obj.contains("f 1//1 2//2 3//3\n"), "{obj}");
        let glb = bytes(MeshFormat::Glb);
        assert_eq!(&glb[..4], b"glTF");
        assert_eq!(u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize, glb.len());
    }
}
