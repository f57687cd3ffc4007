//! `scanvert import`: a Wavefront OBJ or STL model into a text display
//! list that shows the whole model.
//!
//! The model is read with `tobj` (OBJ: polygons of any size, `v/vt/vn`
//! indices, negative indices; materials ignored) or `stl_io` (ASCII and
//! binary STL). STL repeats each corner in every triangle through it: the
//! corners are welded into shared vertices by exact equality of their
//! `f32` coordinates, so one model as OBJ and as STL gives the same
//! vertices and faces, and the same picture.
//!
//! The list: the frame, a perspective and a view fitted to the model's
//! bounding box, a light, the colour, then one `v` a vertex and one `f` a
//! face, in the model's order and winding (counter-clockwise seen from
//! outside shows the outside, as both formats have it). The model is
//! moved so that its bounding box is centred on the origin and scaled so
//! that the box's half-diagonal is [`RADIUS`] world units: any model's
//! coordinates then fit the list's Q16.16 range with the same precision.

use crate::text::format_q16;
use scanvert::geometry::Q16;
use scanvert::pixelcolor::{Rgb888, RgbColor};
use std::fmt::Write;
use std::io::{BufReader, Cursor, Read, Seek};

/// The half-diagonal of the model's bounding box in the list, world units.
pub const RADIUS: f64 = 10.0;

/// The most vertices a list's table can name from one `f` (the binary
/// form's `u16` indices).
pub const MAX_VERTICES: usize = 1 << 16;

/// A polygon mesh: vertices and faces of 0-based indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Model {
    /// Vertex positions, as the file has them.
    pub vertices: Vec<[f32; 3]>,
    /// Faces, each at least 3 indices into `vertices`, in the file's
    /// winding.
    pub faces: Vec<Vec<u32>>,
}

/// The model formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// STL, ASCII or binary.
    Stl,
}

/// The format of a file named `name` holding `bytes`: by the extension
/// (`.obj`, `.stl`, any case), else STL when the bytes start with `solid`
/// or have a binary STL's size for their triangle count, else OBJ.
pub fn format_of(name: &str, bytes: &[u8]) -> Format {
    let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("obj") => Format::Obj,
        Some("stl") => Format::Stl,
        _ => {
            let binary = bytes.len() >= 84 && {
                let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
                bytes.len() as u64 == 84 + 50 * n as u64
            };
            if binary || bytes.trim_ascii_start().starts_with(b"solid") {
                Format::Stl
            } else {
                Format::Obj
            }
        }
    }
}

/// Reads a model of `format` from `bytes`. A file the reader refuses, one
/// with no face, a coordinate that is not finite, or an index past the
/// vertices is an error, with a message.
pub fn read(format: Format, bytes: &[u8]) -> Result<Model, String> {
    let model = match format {
        Format::Obj => read_obj(bytes)?,
        Format::Stl => read_stl(&mut Cursor::new(bytes))?,
    };
    if model.faces.is_empty() {
        return Err("the model has no face".into());
    }
    if model.vertices.iter().flatten().any(|c| !c.is_finite()) {
        return Err("the model has a coordinate that is not a finite number".into());
    }
    let n = model.vertices.len();
    if model.faces.iter().flatten().any(|&i| i as usize >= n) {
        return Err("a face names a vertex the model does not have".into());
    }
    if n > MAX_VERTICES {
        return Err(format!(
            "the model has {n} vertices; a display list names at most {MAX_VERTICES} from one segment"
        ));
    }
    Ok(model)
}

fn read_obj(bytes: &[u8]) -> Result<Model, String> {
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // Materials are ignored: a `mtllib` is not opened.
    let (models, _) = tobj::load_obj_buf(&mut BufReader::new(bytes), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| format!("not a Wavefront OBJ model: {e}"))?;
    let mut out = Model::default();
    for m in models {
        let mesh = m.mesh;
        let base = out.vertices.len() as u32;
        out.vertices
            .extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        let index = |i: &u32| base + i;
        if mesh.face_arities.is_empty() {
            // Only triangles.
            out.faces.extend(
                mesh.indices
                    .chunks_exact(3)
                    .map(|f| f.iter().map(index).collect()),
            );
        } else {
            let mut at = 0usize;
            for &n in &mesh.face_arities {
                let end = at + n as usize;
                let face = mesh
                    .indices
                    .get(at..end)
                    .ok_or("a face of the model is cut short")?;
                out.faces.push(face.iter().map(index).collect());
                at = end;
            }
        }
    }
    Ok(out)
}

fn read_stl<R: Read + Seek>(r: &mut R) -> Result<Model, String> {
    let mesh = stl_io::read_stl(r).map_err(|e| format!("not an STL model: {e}"))?;
    // Weld: one vertex for each distinct position (`+ 0.0` makes −0 the
    // same as 0, as `==` has them).
    let key = |p: [f32; 3]| p.map(|c| (c + 0.0).to_bits());
    let mut seen = std::collections::HashMap::new();
    let mut out = Model::default();
    let mut id = Vec::with_capacity(mesh.vertices.len());
    for v in &mesh.vertices {
        let p = v.0;
        let next = out.vertices.len() as u32;
        let i = *seen.entry(key(p)).or_insert_with(|| {
            out.vertices.push(p);
            next
        });
        id.push(i);
    }
    for f in &mesh.faces {
        let face = f
            .vertices
            .iter()
            .map(|&i| id.get(i).copied().ok_or("a triangle names no vertex"))
            .collect::<Result<Vec<_>, _>>()?;
        out.faces.push(face);
    }
    Ok(out)
}

/// The text list that shows `model` in a `width × height` frame, in
/// `color`.
pub fn list(model: &Model, width: u16, height: u16, color: Rgb888) -> String {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for v in &model.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k] as f64);
            hi[k] = hi[k].max(v[k] as f64);
        }
    }
    let centre: [f64; 3] = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
    let half = (0..3)
        .map(|k| (hi[k] - lo[k]) / 2.0)
        .map(|d| d * d)
        .sum::<f64>()
        .sqrt();
    let scale = if half > 0.0 { RADIUS / half } else { 1.0 };
    // The view: the bounding sphere inside both fields of view, from a
    // three-quarter view above and to the right.
    let fov = 45.0f64;
    let tan_h = (fov.to_radians() / 2.0).tan();
    let tan_v = tan_h * height as f64 / width as f64;
    let half_angle = tan_h.min(tan_v).atan();
    let distance = RADIUS / half_angle.sin() * 1.05;
    let dir = [0.55, 0.45, 0.7];
    let norm = dir.iter().map(|d| d * d).sum::<f64>().sqrt();
    let eye = dir.map(|d| d / norm * distance);
    let near = (distance - RADIUS * 1.1).max(0.5);
    let far = distance + RADIUS * 1.1;
    let q = |x: f64| format_q16(Q16::from_bits((x * 65536.0).round() as i32));
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# made by `scanvert import`: {} vertices, {} faces",
        model.vertices.len(),
        model.faces.len()
    );
    let _ = writeln!(
        s,
        "# the model's bounding box centred on the origin, its half-diagonal {RADIUS} units (scale {scale:e})"
    );
    let _ = writeln!(s, "frame {width} {height}");
    let _ = writeln!(s, "perspective {fov} {} {}", q(near), q(far));
    let _ = writeln!(s, "lookat {} {} {}  0 0 0", q(eye[0]), q(eye[1]), q(eye[2]));
    let _ = writeln!(s, "light 1 2 3 70");
    let _ = writeln!(
        s,
        "color #{:02x}{:02x}{:02x}",
        color.r(),
        color.g(),
        color.b()
    );
    for v in &model.vertices {
        let p: [f64; 3] = std::array::from_fn(|k| (v[k] as f64 - centre[k]) * scale);
        let _ = writeln!(s, "v {} {} {}", q(p[0]), q(p[1]), q(p[2]));
    }
    for f in &model.faces {
        s.push('f');
        for &i in f {
            let _ = write!(s, " {}", i + 1);
        }
        s.push('\n');
    }
    s
}
