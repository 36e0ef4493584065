//! Mesh files: binary glTF (`.glb`: positions, normals, vertex colours, indices), binary PLY (positions, normals,
//! 8-bit colours), binary STL (facet normals, no colour) and OBJ (positions with colours, normals). All are written in
//! glTF's right-handed frame: z mirrored, and triangle winding reversed with it so faces still point outwards.

use std::fmt::Write as _;
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

/// The bytes of `mesh` in `format`.
pub fn write_mesh(mesh: &Mesh, format: MeshFormat) -> Vec<u8> {
    let m = right_handed(mesh);
    match format {
        MeshFormat::Glb => glb(&m),
        MeshFormat::Ply => ply(&m),
        MeshFormat::Stl => stl(&m),
        MeshFormat::Obj => obj(&m).into_bytes(),
    }
}

/// z mirrored, winding reversed.
fn right_handed(mesh: &Mesh) -> Mesh {
    let mirror = |v: &[f32; 3]| [v[0], v[1], -v[2]];
    Mesh {
        positions: mesh.positions.iter().map(mirror).collect(),
        normals: mesh.normals.iter().map(mirror).collect(),
        colours: mesh.colours.clone(),
        triangles: mesh.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
    }
}

fn extend_f32s<'a>(bytes: &mut Vec<u8>, values: impl IntoIterator<Item = &'a [f32; 3]>) {
    for v in values {
        v.iter().for_each(|c| bytes.extend_from_slice(&c.to_le_bytes()));
    }
}

fn glb(m: &Mesh) -> Vec<u8> {
    let n = m.positions.len();
    let mut bin = Vec::with_capacity(n * 36 + m.triangles.len() * 12);
    extend_f32s(&mut bin, &m.positions);
    extend_f32s(&mut bin, &m.normals);
    extend_f32s(&mut bin, &m.colours);
    m.triangles.iter().flatten().for_each(|i| bin.extend_from_slice(&i.to_le_bytes()));
    let (lo, hi) = m.positions.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
        ([0, 1, 2].map(|a| lo[a].min(p[a])), [0, 1, 2].map(|a| hi[a].max(p[a])))
    });
    let (lo, hi) = if n == 0 { ([0.0; 3], [0.0; 3]) } else { (lo, hi) };
    let v = n * 12;
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
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": v, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": 2 * v, "byteLength": v, "target": 34962 },
            { "buffer": 0, "byteOffset": 3 * v, "byteLength": m.triangles.len() * 12, "target": 34963 },
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5126, "count": n, "type": "VEC3" },
            { "bufferView": 3, "componentType": 5125, "count": m.triangles.len() * 3, "type": "SCALAR" },
        ],
    });
    let mut json = serde_json::to_vec(&document).expect("a JSON value always serialises");
    // Chunks are 4-byte aligned: JSON padded with spaces, binary with zeros.
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

fn byte(c: f32) -> u8 {
    (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}

fn ply(m: &Mesh) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment fractal mesh, glTF frame (right-handed, y up)\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n\
         property float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        m.positions.len(),
        m.triangles.len()
    );
    let mut out = header.into_bytes();
    for ((p, n), c) in m.positions.iter().zip(&m.normals).zip(&m.colours) {
        extend_f32s(&mut out, [p, n]);
        out.extend(c.map(byte));
    }
    for t in &m.triangles {
        out.push(3);
        t.iter().for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
    }
    out
}

fn stl(m: &Mesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + m.triangles.len() * 50);
    let mut header = [b' '; 80];
    let text = b"fractal mesh, glTF frame (right-handed, y up)";
    header[..text.len()].copy_from_slice(text);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(m.triangles.len() as u32).to_le_bytes());
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let (u, v) = ([0, 1, 2].map(|k| b[k] - a[k]), [0, 1, 2].map(|k| c[k] - a[k]));
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let len = n.iter().map(|x| x * x).sum::<f32>().sqrt();
        let n = if len > 0.0 { n.map(|x| x / len) } else { [0.0; 3] };
        extend_f32s(&mut out, [&n, &a, &b, &c]);
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

fn obj(m: &Mesh) -> String {
    let mut out = String::from("# fractal mesh, glTF frame (right-handed, y up); vertex colours after positions\n");
    for (p, c) in m.positions.iter().zip(&m.colours) {
        let _ = writeln!(out, "v {} {} {} {} {} {}", p[0], p[1], p[2], c[0], c[1], c[2]);
    }
    for n in &m.normals {
        let _ = writeln!(out, "vn {} {} {}", n[0], n[1], n[2]);
    }
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    out
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

    #[test]
    fn every_format_writes_the_whole_mesh() {
        let m = tetrahedron();
        assert_eq!(m.unmatched_edges(), 0);
        let stl = write_mesh(&m, MeshFormat::Stl);
        assert_eq!(stl.len(), 84 + 4 * 50);
        let ply = write_mesh(&m, MeshFormat::Ply);
        assert!(ply.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
        let obj = String::from_utf8(write_mesh(&m, MeshFormat::Obj)).unwrap();
        assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 4);
        // Mirrored: the vertex at z = 1 is at z = −1, and the winding is reversed.
        assert!(obj.contains("v 0 0 -1 1 0.5 0\n") && obj.contains("f 1//1 2//2 3//3\n"), "{obj}");
        let glb = write_mesh(&m, MeshFormat::Glb);
        assert_eq!(&glb[..4], b"glTF");
        assert_eq!(u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize, glb.len());
    }
}
