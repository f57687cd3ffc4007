//! The 3D geometry stage against an independent double-precision reference:
//! sines, transform composition, projection and depth, the near plane and
//! the space behind the eye, edge-on faces, culling of a cube, lighting,
//! points and lines at the window's edges, the window clip, and the
//! corners of the fixed-point ranges. Property tests run random transforms
//! and polygons through the whole stage.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use proptest::prelude::*;
use scanvert::fixed::{Coord, Vertex, Vertex3};
use scanvert::geometry::{
    trig, Angle, Light, Matrix, Orthographic, Outcome, Perspective, Pipeline, PipelineError,
    PipelineStats, Point3, PolygonSink, Projection, TransformError, View, Viewport, Q16, Z_FAR,
    Z_NEAR,
};
use std::convert::Infallible;
use std::f64::consts::PI;

// ---------------------------------------------------------------------
// The reference, in f64.

type M = [[f64; 4]; 3];
type V3 = [f64; 3];

const ID: M = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
];

fn rad(a: Angle) -> f64 {
    a.to_bits() as f64 * 2.0 * PI / 65536.0
}

fn mul(a: &M, b: &M) -> M {
    let mut o = [[0.0; 4]; 3];
    for r in 0..3 {
        for c in 0..4 {
            o[r][c] =
                (0..3).map(|k| a[r][k] * b[k][c]).sum::<f64>() + if c == 3 { a[r][3] } else { 0.0 };
        }
    }
    o
}

fn apply(m: &M, p: V3) -> V3 {
    let mut o = [0.0; 3];
    for r in 0..3 {
        o[r] = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
    }
    o
}

fn rot_x(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0, 0.0], [0.0, c, -s, 0.0], [0.0, s, c, 0.0]]
}
fn rot_y(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s, 0.0], [0.0, 1.0, 0.0, 0.0], [-s, 0.0, c, 0.0]]
}
fn rot_z(a: f64) -> M {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0, 0.0], [s, c, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]
}
fn trans(t: V3) -> M {
    [
        [1.0, 0.0, 0.0, t[0]],
        [0.0, 1.0, 0.0, t[1]],
        [0.0, 0.0, 1.0, t[2]],
    ]
}
fn scal(s: V3) -> M {
    [
        [s[0], 0.0, 0.0, 0.0],
        [0.0, s[1], 0.0, 0.0],
        [0.0, 0.0, s[2], 0.0],
    ]
}

fn view_ref(eye: V3, yaw: Angle, pitch: Angle) -> M {
    let flip = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, -1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 0.0],
    ];
    let m = mul(&flip, &rot_x(-rad(pitch)));
    let m = mul(&m, &rot_y(-rad(yaw)));
    mul(&m, &trans([-eye[0], -eye[1], -eye[2]]))
}

/// The reference camera: screen x, y in px, depth in Q12.4 units.
#[derive(Clone, Copy, Debug)]
struct Cam {
    persp: bool,
    /// Focal length (px) or scale (px per unit).
    k: f64,
    near: f64,
    far: f64,
    w: f64,
    h: f64,
    cx: f64,
    cy: f64,
}

impl Cam {
    /// The camera as the pipeline holds it: parameters in Q16.16.
    fn quantised(mut self) -> Cam {
        let r = |v: f64| (v * 65536.0).round() / 65536.0;
        self.k = r(self.k);
        self.near = r(self.near);
        self.far = r(self.far);
        self.cx = (self.cx * 16.0).round() / 16.0;
        self.cy = (self.cy * 16.0).round() / 16.0;
        self
    }

    /// The screen depth at pixel position `(sx, sy)` of the plane through
    /// the view-space points `a`, `b`, `c`.
    fn depth_at(&self, [a, b, c]: [V3; 3], sx: f64, sy: f64) -> f64 {
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let off = n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
        let d = if self.persp {
            // The ray d · ((sx − cx)/k, (sy − cy)/k, 1) meets the plane.
            off / (n[0] * (sx - self.cx) / self.k + n[1] * (sy - self.cy) / self.k + n[2])
        } else {
            (off - n[0] * (sx - self.cx) / self.k - n[1] * (sy - self.cy) / self.k) / n[2]
        };
        let p = self.project([0.0, 0.0, d]);
        p[2]
    }

    fn project(&self, v: V3) -> V3 {
        let (zn, zf) = (Z_NEAR.units() as f64, Z_FAR.units() as f64);
        if self.persp {
            let t = (1.0 / self.near - 1.0 / v[2]) / (1.0 / self.near - 1.0 / self.far);
            [
                self.cx + self.k * v[0] / v[2],
                self.cy + self.k * v[1] / v[2],
                zn + (zf - zn) * t,
            ]
        } else {
            let t = (v[2] - self.near) / (self.far - self.near);
            [
                self.cx + self.k * v[0],
                self.cy + self.k * v[1],
                zn + (zf - zn) * t,
            ]
        }
    }

    fn pipeline(&self) -> Pipeline<8, 32> {
        assert_eq!(self.k, self.quantised().k, "quantise the camera first");
        let proj: Projection = if self.persp {
            Perspective::new(q(self.k), q(self.near), q(self.far))
                .unwrap()
                .into()
        } else {
            Orthographic::new(q(self.k), q(self.near), q(self.far))
                .unwrap()
                .into()
        };
        let c = Vertex::from_bits(
            (self.cx * 16.0).round() as i16,
            (self.cy * 16.0).round() as i16,
        );
        Pipeline::new(
            proj,
            Viewport::new(self.w as u16, self.h as u16, c).unwrap(),
        )
    }
}

/// Sutherland–Hodgman against `keep(v) ≥ 0`, in f64.
fn clip_ref(poly: &[V3], keep: impl Fn(&V3) -> f64) -> Vec<V3> {
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (s, e) = (poly[(i + poly.len() - 1) % poly.len()], poly[i]);
        let (ds, de) = (keep(&s), keep(&e));
        if (ds >= 0.0) != (de >= 0.0) {
            let t = ds / (ds - de);
            out.push([0, 1, 2].map(|k| s[k] + (e[k] - s[k]) * t));
        }
        if de >= 0.0 {
            out.push(e);
        }
    }
    out
}

/// The whole stage in f64 for a face given in view space (no cull, no
/// light): near/far clip, project, window clip.
fn stage_ref(cam: &Cam, face: &[V3]) -> Vec<V3> {
    let p = clip_ref(face, |v| v[2] - cam.near);
    let p = clip_ref(&p, |v| cam.far - v[2]);
    let p: Vec<V3> = p.iter().map(|&v| cam.project(v)).collect();
    let p = clip_ref(&p, |v| v[0]);
    let p = clip_ref(&p, |v| cam.w - v[0]);
    let p = clip_ref(&p, |v| v[1]);
    clip_ref(&p, |v| cam.h - v[1])
}

fn area(p: &[V3]) -> f64 {
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

// ---------------------------------------------------------------------
// Helpers.

/// How far a vertex may lie from the exact one, in px: rounding to 1/16 px
/// in x and y (√2/32), plus the projection and the clip's 1/256.
const ROUNDING: f64 = std::f64::consts::SQRT_2 / 32.0 + 1.0 / 256.0;

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn pt(v: V3) -> Point3 {
    Point3::new(q(v[0]), q(v[1]), q(v[2]))
}

fn fl(v: &Vertex3) -> V3 {
    [
        v.x.units() as f64 / 16.0,
        v.y.units() as f64 / 16.0,
        v.z.units() as f64,
    ]
}

#[derive(Default)]
struct Collect(Vec<(Vec<Vertex3>, Rgb888, bool)>);

impl PolygonSink for Collect {
    type Error = Infallible;
    fn polygon(&mut self, v: &[Vertex3], c: Rgb888, two: bool) -> Result<(), Infallible> {
        self.0.push((v.to_vec(), c, two));
        Ok(())
    }
}

/// Every vertex inside the window, at least three, not all on one line.
#[track_caller]
fn assert_in_window(poly: &[Vertex3], w: u16, h: u16) {
    assert!(poly.len() >= 3, "{poly:?}");
    for v in poly {
        assert!((0..=w as i32 * 16).contains(&v.x.units()), "{poly:?}");
        assert!((0..=h as i32 * 16).contains(&v.y.units()), "{poly:?}");
    }
    let d = |v: &Vertex3| {
        (
            v.x.units() as i64 - poly[0].x.units() as i64,
            v.y.units() as i64 - poly[0].y.units() as i64,
        )
    };
    let spread = poly
        .iter()
        .any(|a| poly.iter().any(|b| d(a).0 * d(b).1 - d(a).1 * d(b).0 != 0));
    assert!(spread, "no area: {poly:?}");
}

/// Distance from `p` to the convex polygon `poly` (zero inside), in x, y.
fn distance(p: &V3, poly: &[V3]) -> f64 {
    let n = poly.len();
    let cross = |a: &V3, b: &V3| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    let signs: Vec<f64> = (0..n)
        .map(|i| cross(&poly[i], &poly[(i + 1) % n]))
        .collect();
    if n >= 3 && (signs.iter().all(|&c| c >= 0.0) || signs.iter().all(|&c| c <= 0.0)) {
        return 0.0;
    }
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let len2 = dx * dx + dy * dy;
            let t = if len2 == 0.0 {
                0.0
            } else {
                (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
            };
            (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

/// The convex polygons `a` and `b` have the same shape within `tol` px:
/// each vertex of one lies within `tol / sin(θ/2)` of the other, `θ` its
/// interior angle. Vertices are not matched one to one: where two edges
/// meet at a small angle `θ`, moving the edges by `tol` moves the corner by
/// up to `tol / sin(θ/2)` (a clip meeting an edge at a grazing angle).
#[track_caller]
fn assert_close(a: &[V3], b: &[V3], tol: f64) {
    let check = |a: &[V3], b: &[V3]| {
        let n = a.len();
        for i in 0..n {
            let (p, prev, next) = (a[i], a[(i + n - 1) % n], a[(i + 1) % n]);
            let (u, v) = (
                [prev[0] - p[0], prev[1] - p[1]],
                [next[0] - p[0], next[1] - p[1]],
            );
            let theta = (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(u[0] * v[0] + u[1] * v[1]);
            let allow = tol / (theta / 2.0).sin().max(1e-3);
            assert!(
                distance(&p, b) <= allow,
                "{p:?} is {} from {b:?}, angle {theta}",
                distance(&p, b)
            );
        }
    };
    check(a, b);
    check(b, a);
}

/// The depth of each vertex is that of the face's plane at its screen
/// position: within half a step of rounding and 1/16 of the mapping, plus
/// what the vertex's position error is worth on the plane's slope (√2/32 px
/// of rounding, 1/256 of projection, 1/256 of two clip passes, and `extra`).
#[track_caller]
fn assert_depths(cam: &Cam, face: [V3; 3], poly: &[V3], extra: f64) {
    for v in poly {
        let want = cam.depth_at(face, v[0], v[1]);
        let h = 1.0 / 64.0;
        let slope = (cam.depth_at(face, v[0] + h, v[1]) - want)
            .hypot(cam.depth_at(face, v[0], v[1] + h) - want)
            / h;
        let tol = 0.5 + 1.0 / 16.0 + slope * (ROUNDING + 2.0 / 256.0 + extra) + 1e-6;
        assert!(
            (v[2] - want).abs() <= tol,
            "{v:?}: plane says {want}, slope {slope}"
        );
    }
}

fn cam_persp() -> Cam {
    Cam {
        persp: true,
        k: 300.0,
        near: 1.0,
        far: 200.0,
        w: 512.0,
        h: 256.0,
        cx: 256.0,
        cy: 128.0,
    }
    .quantised()
}

// ---------------------------------------------------------------------
// Sines.

#[test]
fn sine_and_cosine_of_every_angle() {
    let mut worst: f64 = 0.0;
    for b in 0..=u16::MAX {
        let a = Angle::from_bits(b);
        let s = trig::sin(a) as f64 / 65536.0;
        let c = trig::cos(a) as f64 / 65536.0;
        worst = worst
            .max((s - rad(a).sin()).abs())
            .max((c - rad(a).cos()).abs());
    }
    eprintln!("sin/cos worst error: {worst:.3e}");
    assert!(worst < 1.3e-5, "{worst}");
}

#[test]
fn arctangent_of_many_vectors() {
    let mut worst = 0i32;
    let mut gen = testkit::rng::Rng(0x9e37_79b9_7f4a_7c15);
    for i in 0..100_000 {
        let rng = gen.next_u64();
        let bits = 1 + (i % 62) as u32;
        let x = (rng as i64) >> (63 - bits);
        let y = ((rng >> 17) as i64 ^ (rng << 40) as i64) >> (63 - bits);
        if x == 0 && y == 0 {
            continue;
        }
        let got = trig::atan2(y, x).to_bits();
        let want = ((y as f64).atan2(x as f64) / (2.0 * PI) * 65536.0)
            .round()
            .rem_euclid(65536.0) as u16;
        let d = (got.wrapping_sub(want) as i16) as i32;
        // Small vectors have coarse directions: allow their own step too.
        let coarse = if bits < 16 {
            (65536.0 / (2.0 * PI * x.unsigned_abs().max(y.unsigned_abs()) as f64)) as i32
        } else {
            0
        };
        assert!(d.abs() <= 2 + coarse, "{y} {x}: {got} vs {want}");
        if bits >= 16 {
            worst = worst.max(d.abs());
        }
    }
    eprintln!("atan2 worst error: {worst} binary units");
    assert!(worst <= 2);
}

#[test]
fn look_at_points_the_view_axis_at_the_target() {
    let mut pipe = cam_persp().pipeline();
    for (eye, target) in [
        ([0.0, 30.0, 40.0], [0.0, 0.0, 0.0]),
        ([-12.5, 3.0, 7.0], [4.0, -1.0, -20.0]),
        ([5.0, -9.0, 0.0], [5.0, 9.0, 0.1]),
    ] {
        pipe.set_view(&View::look_at(pt(eye), pt(target)).unwrap())
            .unwrap();
        let a = pipe.project_point(pt(target)).unwrap();
        assert!(a.in_front && a.inside);
        assert!(
            (a.x - 256 * 16).abs() <= 1 && (a.y - 128 * 16).abs() <= 1,
            "{a:?}"
        );
    }
}

#[test]
fn integer_square_root() {
    for v in (0..u32::MAX).step_by(9_973).chain([u32::MAX]) {
        assert_eq!(
            trig::isqrt(v) as u64,
            (v as f64).sqrt().floor() as u64,
            "{v}"
        );
    }
}

// ---------------------------------------------------------------------
// Transforms.

#[derive(Clone, Copy, Debug)]
enum Op {
    T(V3),
    Rx(u16),
    Ry(u16),
    Rz(u16),
    S(V3),
    Push,
    Pop,
}

fn run_ops(ops: &[Op]) -> (Option<Matrix>, M) {
    let mut stack = scanvert::geometry::TransformStack::<4>::new();
    let mut refs = vec![ID];
    let mut saved: Vec<M> = Vec::new();
    let mut ok = true;
    for op in ops {
        let cur = *refs.last().unwrap();
        let r = match *op {
            Op::T(t) => {
                refs.push(mul(&cur, &trans(t)));
                stack.translate(q(t[0]), q(t[1]), q(t[2]))
            }
            Op::Rx(a) => {
                refs.push(mul(&cur, &rot_x(rad(Angle::from_bits(a)))));
                stack.rotate_x(Angle::from_bits(a))
            }
            Op::Ry(a) => {
                refs.push(mul(&cur, &rot_y(rad(Angle::from_bits(a)))));
                stack.rotate_y(Angle::from_bits(a))
            }
            Op::Rz(a) => {
                refs.push(mul(&cur, &rot_z(rad(Angle::from_bits(a)))));
                stack.rotate_z(Angle::from_bits(a))
            }
            Op::S(s) => {
                refs.push(mul(&cur, &scal(s)));
                stack.scale(q(s[0]), q(s[1]), q(s[2]))
            }
            Op::Push => {
                saved.push(cur);
                let r = stack.push();
                if r.is_err() {
                    saved.pop();
                }
                r
            }
            Op::Pop => {
                if let Some(m) = saved.pop() {
                    refs.push(m);
                }
                stack.pop()
            }
        };
        match (op, r) {
            (_, Ok(())) => {}
            (Op::Push, Err(TransformError::StackOverflow { depth: 4 })) => {}
            (Op::Pop, Err(TransformError::StackUnderflow)) => {}
            (_, Err(_)) => ok = false,
        }
    }
    (ok.then(|| *stack.current()), *refs.last().unwrap())
}

#[test]
fn transforms_compose_in_call_order() {
    // translate, then rotate: the rotation acts on the model first.
    let ops = [
        Op::T([5.0, 0.0, 0.0]),
        Op::Rz(0x4000),
        Op::S([2.0, 1.0, 1.0]),
    ];
    let (m, r) = run_ops(&ops);
    let m = m.unwrap();
    let p = [1.0, 0.0, 0.0];
    let got = m
        .transform(pt(p))
        .unwrap()
        .to_bits()
        .map(|v| v as f64 / 65536.0);
    let want = apply(&r, p);
    assert_eq!(want.map(|v| v.round()), [5.0, 2.0, 0.0]);
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() < 1e-4, "{got:?} {want:?}");
    }
    // The other order gives another point.
    let (m2, _) = run_ops(&[
        Op::S([2.0, 1.0, 1.0]),
        Op::Rz(0x4000),
        Op::T([5.0, 0.0, 0.0]),
    ]);
    assert_ne!(m2.unwrap().transform(pt(p)), m.transform(pt(p)));
}

fn op() -> impl Strategy<Value = Op> {
    let t = -50.0..50.0f64;
    let s = prop_oneof![0.1..4.0f64, -4.0..-0.1f64];
    prop_oneof![
        3 => (t.clone(), t.clone(), t).prop_map(|(x, y, z)| Op::T([x, y, z])),
        2 => any::<u16>().prop_map(Op::Rx),
        2 => any::<u16>().prop_map(Op::Ry),
        2 => any::<u16>().prop_map(Op::Rz),
        1 => (s.clone(), s.clone(), s).prop_map(|(x, y, z)| Op::S([x, y, z])),
        1 => Just(Op::Push),
        1 => Just(Op::Pop),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random sequences of translate, rotate, scale, push and pop agree
    /// with the reference matrices.
    #[test]
    fn random_transform_chains_match_the_reference(ops in prop::collection::vec(op(), 1..10),
                                                   p in prop::array::uniform3(-20.0..20.0f64)) {
        let (m, r) = run_ops(&ops);
        let want = apply(&r, p);
        if let (Some(m), true) = (m, want.iter().all(|v| v.abs() < 16000.0)) {
            // Error grows with the matrix entries: 2⁻¹⁶ per entry per step.
            let size: f64 = r.iter().flatten().map(|v| v.abs()).sum::<f64>() + 1.0;
            let tol = 1e-4 * size * ops.len() as f64;
            let got = m.transform(pt(p)).unwrap().to_bits().map(|v| v as f64 / 65536.0);
            for k in 0..3 {
                prop_assert!((got[k] - want[k]).abs() < tol, "{:?} {:?} tol {}", got, want, tol);
            }
        }
    }
}

#[test]
fn the_view_matrix_matches_the_reference() {
    for (eye, yaw, pitch) in [
        ([0.0, 0.0, 10.0], 0, 0),
        ([3.0, 4.0, -5.0], 0x2000, 0x0800),
        ([-100.0, 20.0, 7.5], 0xC123, 0xF000),
    ] {
        let v = View {
            eye: pt(eye),
            yaw: Angle::from_bits(yaw),
            pitch: Angle::from_bits(pitch),
        };
        let m = v.matrix().unwrap();
        let r = view_ref(eye, Angle::from_bits(yaw), Angle::from_bits(pitch));
        for p in [[0.0, 0.0, 0.0], [1.0, 2.0, 3.0], [-40.0, 5.0, 60.0]] {
            let got = m
                .transform(pt(p))
                .unwrap()
                .to_bits()
                .map(|v| v as f64 / 65536.0);
            let want = apply(&r, p);
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 2e-3, "{got:?} {want:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------
// Projection.

/// The documented bounds: x, y within 1/32 + 1/256 px, depth within half
/// a Q12.4 step plus 1/16.
#[test]
fn projection_is_within_its_documented_error() {
    let cams = [
        cam_persp(),
        Cam {
            persp: true,
            k: 2000.0,
            near: 0.01,
            far: 16000.0,
            w: 2047.0,
            h: 2047.0,
            cx: 1023.5,
            cy: 1000.0,
        },
        Cam {
            persp: true,
            k: 50.0,
            near: 100.0,
            far: 110.0,
            w: 64.0,
            h: 48.0,
            cx: 32.0,
            cy: 24.0,
        },
        Cam {
            persp: false,
            k: 3.5,
            near: -50.0,
            far: 50.0,
            w: 512.0,
            h: 256.0,
            cx: 256.0,
            cy: 128.0,
        },
    ];
    let mut rng = testkit::rng::Rng(0x1234_5678_9abc_def0);
    let mut next = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let (mut worst_xy, mut worst_z) = (0.0f64, 0.0f64);
    for cam in cams {
        let cam = cam.quantised();
        let pipe = cam.pipeline();
        for _ in 0..20_000 {
            let d = cam.near + (cam.far - cam.near) * next();
            let span = if cam.persp { d / cam.k } else { 1.0 / cam.k };
            let x = (next() * 1.4 - 0.2) * cam.w * span - cam.cx * span;
            let y = (next() * 1.4 - 0.2) * cam.h * span - cam.cy * span;
            let p = pt([x, y, d]);
            let v = p.to_bits().map(|c| c as f64 / 65536.0);
            let a = pipe.project_point(p).unwrap();
            assert!(a.in_front);
            let want = cam.project(v);
            let ex = (a.x as f64 / 16.0 - want[0])
                .abs()
                .max((a.y as f64 / 16.0 - want[1]).abs());
            let ez = (a.z.units() as f64 - want[2]).abs();
            worst_xy = worst_xy.max(ex);
            worst_z = worst_z.max(ez);
            let inside = (0.0..cam.w).contains(&(a.x as f64 / 16.0))
                && (0.0..cam.h).contains(&(a.y as f64 / 16.0));
            assert_eq!(a.inside, inside);
        }
    }
    eprintln!("projection worst error: {worst_xy:.4} px, depth {worst_z:.4} Q12.4 steps");
    assert!(worst_xy <= 1.0 / 32.0 + 1.0 / 256.0, "{worst_xy}");
    assert!(worst_z <= 0.5 + 1.0 / 16.0, "{worst_z}");
}

/// Over a planar face, depth is affine in screen x and y.
#[test]
fn depth_is_affine_in_screen_space() {
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    // A large slanted quad, counter-clockwise as displayed, reaching the
    // window's sides so that the clip makes new vertices.
    let face = [
        [30.0, -5.0, 2.0],
        [30.0, -5.0, 150.0],
        [-30.0, 8.0, 150.0],
        [-30.0, 8.0, 2.0],
    ];
    let mut sink = Collect::default();
    let out = pipe
        .polygon(&face.map(pt), Rgb888::WHITE, &mut sink)
        .unwrap();
    assert_eq!(out, Outcome::Emitted);
    let poly: Vec<V3> = sink.0[0].0.iter().map(fl).collect();
    assert!(poly.len() >= 5, "{poly:?}");
    assert_depths(&cam, [face[0], face[1], face[2]], &poly, 0.0);
    let r = stage_ref(&cam, &face);
    assert_close(&poly, &r, ROUNDING);
}

// ---------------------------------------------------------------------
// The near plane and the space behind the eye.

#[test]
fn faces_crossing_the_near_plane_and_behind_the_eye() {
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    // Counter-clockwise as displayed, for faces in front: a floor under the
    // eye, running from behind it to far ahead.
    let floor = [
        [5.0, 0.2, -20.0],
        [5.0, 0.2, 40.0],
        [-5.0, 0.2, 40.0],
        [-5.0, 0.2, -20.0],
    ];
    let mut sink = Collect::default();
    assert_eq!(
        pipe.polygon(&floor.map(pt), Rgb888::WHITE, &mut sink),
        Ok(Outcome::Emitted)
    );
    let got: Vec<V3> = sink.0[0].0.iter().map(fl).collect();
    let want = stage_ref(&cam, &floor);
    assert_close(&got, &want, ROUNDING + 300.0 / 131072.0);
    assert_depths(&cam, [floor[0], floor[1], floor[2]], &got, 300.0 / 131072.0);
    assert!(got.iter().any(|v| v[2] == Z_NEAR.units() as f64), "{got:?}");
    assert_in_window(&sink.0[0].0, 512, 256);

    // Wholly behind the eye, either winding: nothing, and no division.
    let behind = [
        [-5.0, 2.0, -20.0],
        [-5.0, 2.0, -1.0],
        [5.0, 2.0, -1.0],
        [5.0, 2.0, -20.0],
    ];
    let mut rev = behind;
    rev.reverse();
    let before = sink.0.len();
    let a = pipe
        .polygon(&behind.map(pt), Rgb888::WHITE, &mut sink)
        .unwrap();
    let b = pipe
        .polygon(&rev.map(pt), Rgb888::WHITE, &mut sink)
        .unwrap();
    assert_eq!(sink.0.len(), before);
    let mut both = [a, b];
    both.sort_by_key(|o| *o as u8);
    assert_eq!(both, [Outcome::Culled, Outcome::ClippedAway]);

    // A face through the eye itself, and one whose vertices are all at depth 0.
    let through = [[-1.0, -1.0, -1.0], [-1.0, 1.0, 1.0], [1.0, 1.0, 1.0]];
    let _ = pipe
        .polygon(&through.map(pt), Rgb888::WHITE, &mut sink)
        .unwrap();
    let at_eye = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
    assert_eq!(
        pipe.polygon(&at_eye.map(pt), Rgb888::WHITE, &mut sink),
        Ok(Outcome::Culled)
    );
    for (p, _, _) in &sink.0 {
        assert_in_window(p, 512, 256);
    }
    // Lines from behind the eye to in front.
    let line = [pt([0.0, 0.1, -10.0]), pt([0.5, 0.1, 10.0])];
    assert_eq!(
        pipe.polygon(&line, Rgb888::WHITE, &mut sink),
        Ok(Outcome::Emitted)
    );
    let last = &sink.0.last().unwrap().0;
    assert!(last.iter().any(|v| v.z == Z_NEAR));
    let s = pipe.stats();
    assert_eq!(
        s.faces_in,
        s.culled + s.clipped_away + s.emitted + s.rejected
    );
}

/// Two faces sharing an edge that crosses the near plane and the window's
/// side get the very same crossing points.
#[test]
fn shared_edges_are_clipped_alike() {
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    let (a, b, c, d) = (
        [-40.0, 3.0, -5.0],
        [10.0, 3.0, 30.0],
        [30.0, 3.0, -5.0],
        [-40.0, 3.0, 60.0],
    );
    let mut sink = Collect::default();
    // a–b is the diagonal of the quad a, c, b, d, split into two triangles;
    // both are counter-clockwise as displayed (the floor seen from above).
    pipe.polygon(&[a, b, d].map(pt), Rgb888::RED, &mut sink)
        .unwrap();
    pipe.polygon(&[a, c, b].map(pt), Rgb888::GREEN, &mut sink)
        .unwrap();
    assert_eq!(sink.0.len(), 2, "{:?}", pipe.stats());
    let shared: Vec<_> = sink.0[0]
        .0
        .iter()
        .filter(|v| sink.0[1].0.contains(v))
        .collect();
    // b, and where the diagonal leaves the window after the near clip.
    assert!(shared.len() >= 2, "{:?}", sink.0);
    assert!(
        shared
            .iter()
            .any(|v| v.x.units() == 0 || v.y.units() == 256 * 16),
        "{shared:?}"
    );
}

// ---------------------------------------------------------------------
// Culling.

/// The unit cube's faces, counter-clockwise seen from outside.
fn cube(h: f64) -> [[V3; 4]; 6] {
    let p = |x: f64, y: f64, z: f64| [x * h, y * h, z * h];
    [
        [
            p(-1., -1., 1.),
            p(1., -1., 1.),
            p(1., 1., 1.),
            p(-1., 1., 1.),
        ], // +z
        [
            p(1., -1., -1.),
            p(-1., -1., -1.),
            p(-1., 1., -1.),
            p(1., 1., -1.),
        ], // −z
        [
            p(1., -1., 1.),
            p(1., -1., -1.),
            p(1., 1., -1.),
            p(1., 1., 1.),
        ], // +x
        [
            p(-1., -1., -1.),
            p(-1., -1., 1.),
            p(-1., 1., 1.),
            p(-1., 1., -1.),
        ], // −x
        [
            p(-1., 1., 1.),
            p(1., 1., 1.),
            p(1., 1., -1.),
            p(-1., 1., -1.),
        ], // +y
        [
            p(-1., -1., -1.),
            p(1., -1., -1.),
            p(1., -1., 1.),
            p(-1., -1., 1.),
        ], // −y
    ]
}

const NORMALS: [V3; 6] = [
    [0., 0., 1.],
    [0., 0., -1.],
    [1., 0., 0.],
    [-1., 0., 0.],
    [0., 1., 0.],
    [0., -1., 0.],
];

fn face_colour(i: usize) -> Rgb888 {
    Rgb888::new(40 * i as u8 + 10, 0, 0)
}

/// A view from `eye` toward the origin.
fn looking_at_origin(eye: V3) -> View {
    let r = (eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]).sqrt();
    let pitch = (-eye[1] / r).asin();
    let yaw = eye[0].atan2(eye[2]);
    let ang = |a: f64| {
        Angle::from_bits(((a / (2.0 * PI) * 65536.0).round() as i64).rem_euclid(65536) as u16)
    };
    View {
        eye: pt(eye),
        yaw: ang(yaw),
        pitch: ang(pitch),
    }
}

#[test]
fn a_cube_shows_only_its_front_faces() {
    let cam = cam_persp();
    let mut checked = 0;
    for i in 0..400 {
        let t = i as f64 * 0.61;
        let eye = [
            6.0 * t.cos() * (t * 0.37).cos(),
            6.0 * (t * 0.37).sin(),
            6.0 * t.sin() * (t * 0.37).cos(),
        ];
        let front: Vec<usize> = (0..6)
            .filter(|&f| {
                let c = NORMALS[f];
                let to_eye = [eye[0] - c[0], eye[1] - c[1], eye[2] - c[2]];
                to_eye[0] * c[0] + to_eye[1] * c[1] + to_eye[2] * c[2] > 0.0
            })
            .collect();
        let margin = (0..6).all(|f| {
            let c = NORMALS[f];
            let d = (eye[0] - c[0]) * c[0] + (eye[1] - c[1]) * c[1] + (eye[2] - c[2]) * c[2];
            d.abs() > 0.05
        });
        if !margin {
            continue;
        }
        let mut pipe = cam.pipeline();
        pipe.set_view(&looking_at_origin(eye)).unwrap();
        let mut sink = Collect::default();
        for (f, face) in cube(1.0).iter().enumerate() {
            pipe.polygon(&face.map(pt), face_colour(f), &mut sink)
                .unwrap();
        }
        let mut got: Vec<Rgb888> = sink.0.iter().map(|p| p.1).collect();
        let mut want: Vec<Rgb888> = front.iter().map(|&f| face_colour(f)).collect();
        got.sort_by_key(|c| c.r());
        want.sort_by_key(|c| c.r());
        assert_eq!(got, want, "eye {eye:?}");
        let s = pipe.stats();
        assert_eq!(
            (s.faces_in, s.culled, s.emitted),
            (6, 6 - want.len() as u32, want.len() as u32)
        );
        for (p, _, two) in &sink.0 {
            assert!(!two);
            assert_in_window(p, 512, 256);
        }
        checked += 1;
    }
    assert!(checked > 300);
}

#[test]
fn edge_on_faces_are_culled() {
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    // The eye at the height of the cube's top face, looking straight at it:
    // the top (+y) and bottom faces are edge-on or turned away.
    pipe.set_view(&View {
        eye: pt([0.0, 1.0, 8.0]),
        yaw: Angle::ZERO,
        pitch: Angle::ZERO,
    })
    .unwrap();
    let mut sink = Collect::default();
    let mut outcomes = Vec::new();
    for (f, face) in cube(1.0).iter().enumerate() {
        outcomes.push(
            pipe.polygon(&face.map(pt), face_colour(f), &mut sink)
                .unwrap(),
        );
    }
    assert_eq!(outcomes[4], Outcome::Culled, "{outcomes:?}");
    assert_eq!(outcomes[0], Outcome::Emitted);
    assert_eq!(sink.0.len(), 1);
    // A face through the eye along the view axis: edge-on in both windings.
    let side = [[0.0, -1.0, 2.0], [0.0, 1.0, 2.0], [0.0, 1.0, 5.0]];
    pipe.set_view(&View::default()).unwrap();
    let mut rev = side;
    rev.reverse();
    let flip = |v: V3| [v[0], v[1], -v[2]];
    assert_eq!(
        pipe.polygon(&side.map(flip).map(pt), Rgb888::RED, &mut sink),
        Ok(Outcome::Culled)
    );
    assert_eq!(
        pipe.polygon(&rev.map(flip).map(pt), Rgb888::RED, &mut sink),
        Ok(Outcome::Culled)
    );
    // First three vertices in a line: the whole polygon decides, so one
    // winding is drawn and the other culled.
    let line = [
        [0.0, 0.0, -5.0],
        [1.0, 1.0, -5.0],
        [2.0, 2.0, -5.0],
        [0.0, 3.0, -5.0],
    ];
    let mut rev = line;
    rev.reverse();
    let both = [line, rev].map(|l| pipe.polygon(&l.map(pt), Rgb888::RED, &mut sink));
    assert!(
        both.contains(&Ok(Outcome::Culled)) && both.contains(&Ok(Outcome::Emitted)),
        "{both:?}"
    );
    // All of them in a line: no area, culled.
    let flat = [
        [0.0, 0.0, -5.0],
        [1.0, 1.0, -5.0],
        [2.0, 2.0, -5.0],
        [3.0, 3.0, -5.0],
    ];
    assert_eq!(
        pipe.polygon(&flat.map(pt), Rgb888::RED, &mut sink),
        Ok(Outcome::Culled)
    );
    // Nearly edge-on after rotation: either culled or delivered with an area.
    for a in 0..64u16 {
        let mut p = cam.pipeline();
        p.set_view(&View {
            eye: pt([0.0, 1.0, 8.0]),
            yaw: Angle::from_bits(a * 1000),
            pitch: Angle::ZERO,
        })
        .unwrap();
        let mut s = Collect::default();
        for face in cube(1.0) {
            p.polygon(&face.map(pt), Rgb888::RED, &mut s).unwrap();
        }
        for (poly, _, _) in &s.0 {
            assert_in_window(poly, 512, 256);
            let f: Vec<V3> = poly.iter().map(fl).collect();
            assert!(area(&f).abs() > 0.0);
        }
    }
}

// ---------------------------------------------------------------------
// Lighting.

#[test]
fn lighting_follows_lambert() {
    let cam = cam_persp();
    let colour = Rgb888::new(250, 128, 7);
    for (dir, pct) in [
        ([0, 1, 0], 70u8),
        ([1, 2, 3], 50),
        ([-3, 1, 0], 100),
        ([0, 0, 1], 0),
        ([5, -5, 1], 85),
    ] {
        let mut pipe = cam.pipeline();
        pipe.set_light(Light::new(dir, pct).unwrap());
        pipe.set_view(&looking_at_origin([4.0, 5.0, 6.0])).unwrap();
        let mut sink = Collect::default();
        let mut expect = Vec::new();
        for (f, face) in cube(1.0).iter().enumerate() {
            if pipe.polygon(&face.map(pt), colour, &mut sink).unwrap() == Outcome::Emitted {
                let l = [dir[0] as f64, dir[1] as f64, dir[2] as f64];
                let len = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
                let n = NORMALS[f];
                let cos = ((n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len).max(0.0);
                let i = (100.0 - pct as f64) / 100.0 + pct as f64 / 100.0 * cos;
                expect.push([colour.r(), colour.g(), colour.b()].map(|c| c as f64 * i));
            }
        }
        assert_eq!(sink.0.len(), 3);
        for ((_, got, _), want) in sink.0.iter().zip(&expect) {
            let got = [got.r(), got.g(), got.b()];
            for k in 0..3 {
                assert!(
                    (got[k] as f64 - want[k]).abs() <= 1.0,
                    "{dir:?} {pct}: {got:?} vs {want:?}"
                );
            }
        }
    }
    // Points and lines keep their colour.
    let mut pipe = cam.pipeline();
    pipe.set_light(Light::new([0, 0, -1], 100).unwrap());
    let mut sink = Collect::default();
    pipe.polygon(&[pt([0.0, 0.0, 10.0])], colour, &mut sink)
        .unwrap();
    pipe.polygon(
        &[pt([0.0, 0.0, 10.0]), pt([1.0, 0.0, 10.0])],
        colour,
        &mut sink,
    )
    .unwrap();
    assert!(sink.0.iter().all(|(_, c, two)| *c == colour && *two));
}

// ---------------------------------------------------------------------
// Points and lines at the window's edges.

fn ortho_cam() -> Cam {
    // One pixel per unit, origin at the window's top-left corner.
    Cam {
        persp: false,
        k: 1.0,
        near: -10.0,
        far: 10.0,
        w: 64.0,
        h: 48.0,
        cx: 0.0,
        cy: 0.0,
    }
    .quantised()
}

fn one(pipe: &mut Pipeline<8, 32>, pts: &[V3]) -> Option<Vec<V3>> {
    let mut sink = Collect::default();
    let pts: Vec<Point3> = pts.iter().map(|&p| pt(p)).collect();
    match pipe.polygon(&pts, Rgb888::BLUE, &mut sink).unwrap() {
        Outcome::Emitted => {
            let (p, c, two) = &sink.0[0];
            assert!(*two && *c == Rgb888::BLUE);
            assert_in_window(p, 64, 48);
            Some(p.iter().map(fl).collect())
        }
        _ => None,
    }
}

#[test]
fn points_and_lines_at_the_windows_edges() {
    let mut pipe = ortho_cam().pipeline();
    pipe.set_thickness(Coord::from_int(4).unwrap());
    // A point on the top-left corner: a quarter of its square.
    let p = one(&mut pipe, &[[0.0, 0.0, 0.0]]).unwrap();
    assert_eq!(area(&p), -4.0);
    // On the bottom-right corner, in the middle of the right side, and
    // 1 px outside the left side.
    assert_eq!(area(&one(&mut pipe, &[[64.0, 48.0, 0.0]]).unwrap()), -4.0);
    assert_eq!(area(&one(&mut pipe, &[[64.0, 20.0, 0.0]]).unwrap()), -8.0);
    assert_eq!(area(&one(&mut pipe, &[[-1.0, 20.0, 0.0]]).unwrap()), -4.0);
    // 2 px outside: it touches the side only; 3 px: nothing.
    assert_eq!(one(&mut pipe, &[[-2.0, 20.0, 0.0]]), None);
    assert_eq!(one(&mut pipe, &[[-3.0, 20.0, 0.0]]), None);
    // A point's depth is its own.
    let d = one(&mut pipe, &[[10.0, 10.0, 5.0]]).unwrap();
    assert!(d
        .iter()
        .all(|v| v[2] == ortho_cam().project([0.0, 0.0, 5.0])[2].round()));

    // A line along the top side: the half inside.
    let l = one(&mut pipe, &[[10.0, 0.0, 0.0], [30.0, 0.0, 0.0]]).unwrap();
    assert_eq!(area(&l).abs(), 40.0);
    // Along the left side, from corner to corner, and across the whole window.
    assert_eq!(
        area(&one(&mut pipe, &[[0.0, 0.0, 0.0], [0.0, 48.0, 0.0]]).unwrap()).abs(),
        96.0
    );
    let diag = one(&mut pipe, &[[-100.0, -75.0, -9.0], [164.0, 123.0, 9.0]]).unwrap();
    // The reference: the same quad (offset 2 px across the 264:198 line),
    // clipped in f64.
    let (ox, oy) = (-198.0 / 330.0 * 2.0, 264.0 / 330.0 * 2.0);
    let quad = [
        [-100.0 + ox, -75.0 + oy, 0.0],
        [164.0 + ox, 123.0 + oy, 0.0],
        [164.0 - ox, 123.0 - oy, 0.0],
        [-100.0 - ox, -75.0 - oy, 0.0],
    ];
    let cam = ortho_cam();
    let q = clip_ref(&quad, |v| v[0]);
    let q = clip_ref(&q, |v| cam.w - v[0]);
    let q = clip_ref(&q, |v| v[1]);
    let q = clip_ref(&q, |v| cam.h - v[1]);
    // Every vertex rounds to 1/16 px: the area moves by at most about the
    // perimeter times 1/32.
    assert!(
        (area(&diag) - area(&q)).abs() < 170.0 / 32.0,
        "{diag:?} {q:?}"
    );
    assert_close(&diag, &q, ROUNDING);
    // Depth along the line is affine, and constant across it.
    let (za, zb) = (
        cam.project([0.0, 0.0, -9.0])[2],
        cam.project([0.0, 0.0, 9.0])[2],
    );
    for v in &diag {
        let t = ((v[0] + 100.0) * 264.0 + (v[1] + 75.0) * 198.0) / (264.0 * 264.0 + 198.0 * 198.0);
        let want = za + (zb - za) * t;
        // Half a step, plus 1/32 px along a slope of 65535 / 330 per px.
        assert!((v[2] - want).abs() < 0.5 + 200.0 / 32.0, "{v:?} {want}");
    }
    // Outside, parallel to a side, and end-on (a square).
    assert_eq!(one(&mut pipe, &[[-5.0, 0.0, 0.0], [-5.0, 48.0, 0.0]]), None);
    assert_eq!(
        area(&one(&mut pipe, &[[8.0, 8.0, -3.0], [8.0, 8.0, 3.0]]).unwrap()),
        -16.0
    );
    // Lines in perspective, beyond the far plane and crossing it.
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    assert_eq!(
        one_wide(&mut pipe, &[[0.0, 0.0, 300.0], [1.0, 0.0, 300.0]]),
        None
    );
    let crossing = one_wide(&mut pipe, &[[0.0, 0.0, 100.0], [10.0, 0.0, 300.0]]).unwrap();
    assert!(crossing.iter().any(|v| v[2] == Z_FAR.units() as f64));
}

fn one_wide(pipe: &mut Pipeline<8, 32>, pts: &[V3]) -> Option<Vec<V3>> {
    let mut sink = Collect::default();
    let pts: Vec<Point3> = pts.iter().map(|&p| pt(p)).collect();
    match pipe.polygon(&pts, Rgb888::BLUE, &mut sink).unwrap() {
        Outcome::Emitted => {
            assert_in_window(&sink.0[0].0, 512, 256);
            Some(sink.0[0].0.iter().map(fl).collect())
        }
        _ => None,
    }
}

// ---------------------------------------------------------------------
// Labels.

#[test]
fn label_anchors() {
    let cam = cam_persp();
    let mut pipe = cam.pipeline();
    pipe.set_view(&View {
        eye: pt([0.0, 0.0, 10.0]),
        yaw: Angle::ZERO,
        pitch: Angle::ZERO,
    })
    .unwrap();
    let a = pipe.project_point(pt([1.0, 1.0, 0.0])).unwrap();
    assert!(a.in_front && a.inside);
    // World y up is screen y down: 30 px right of and 30 px above centre.
    assert_eq!((a.x, a.y), ((256 + 30) * 16, (128 - 30) * 16));
    let behind = pipe.project_point(pt([0.0, 0.0, 20.0])).unwrap();
    assert!(!behind.in_front && !behind.inside);
    let off = pipe.project_point(pt([100.0, 0.0, 0.0])).unwrap();
    assert!(off.in_front && !off.inside && off.x > 512 * 16);
    // Under a model transform too.
    pipe.stack_mut()
        .translate(Q16::from_int(-1), Q16::from_int(-1), Q16::ZERO)
        .unwrap();
    assert_eq!(pipe.project_point(pt([1.0, 1.0, 0.0])).unwrap().x, 256 * 16);
    assert_eq!(
        pipe.project_point(Point3::new(Q16::MAX, Q16::ZERO, Q16::ZERO)),
        Err(TransformError::Range)
    );
}

// ---------------------------------------------------------------------
// Range edges (overflow checks are on in this build).

#[test]
fn range_edges() {
    let e = (1i32 << 30) - 1;
    let ep = |x: i32, y: i32, z: i32| Point3::from_bits(x, y, z);
    // The smallest near plane, the largest far plane and focal length.
    let persp = Perspective::new(
        Q16::MAX,
        scanvert::geometry::project::NEAR_MIN,
        Q16::from_bits(e),
    )
    .unwrap();
    let mut pipe = Pipeline::<2, 16>::new(persp, Viewport::centred(2047, 2047).unwrap());
    let mut sink = Collect::default();
    let corners = [
        [ep(-e, -e, e), ep(-e, e, e), ep(e, e, e)],
        [ep(-e, -e, 256), ep(-e, e, 256), ep(e, e, e)],
        [ep(-e, -e, -e), ep(-e, e, e), ep(e, e, -e)],
        [ep(e, e, 256), ep(e, e, 257), ep(e, -e, 300)],
        [ep(0, 0, 256), ep(0, 1, 256), ep(1, 1, 256)],
    ];
    for tri in &corners {
        for w in [tri.to_vec(), tri.iter().rev().copied().collect()] {
            let _ = pipe.polygon(&w, Rgb888::WHITE, &mut sink).unwrap();
        }
        let _ = pipe.polygon(&tri[..1], Rgb888::WHITE, &mut sink).unwrap();
        let _ = pipe.polygon(&tri[..2], Rgb888::WHITE, &mut sink).unwrap();
    }
    for (p, _, _) in &sink.0 {
        assert_in_window(p, 2047, 2047);
    }
    assert!(!sink.0.is_empty());
    // Just beyond view space: an error, nothing drawn.
    let out = [ep(1 << 30, 0, 300), ep(0, 1, 300), ep(1, 1, 300)];
    assert_eq!(
        pipe.polygon(&out, Rgb888::WHITE, &mut sink),
        Err(PipelineError::Range)
    );
    let out = [Point3::new(Q16::MIN, Q16::MIN, Q16::MIN); 3];
    assert_eq!(
        pipe.polygon(&out, Rgb888::WHITE, &mut sink),
        Err(PipelineError::Range)
    );
    // Matrices at their limits.
    let s = pipe.stack_mut();
    s.scale(
        Q16::from_int(16384),
        Q16::from_int(-16384),
        Q16::from_int(16384),
    )
    .unwrap();
    assert_eq!(
        s.scale(Q16::from_int(2), Q16::ONE, Q16::ONE),
        Err(TransformError::Range)
    );
    s.push().unwrap();
    s.push().unwrap();
    assert_eq!(s.push(), Err(TransformError::StackOverflow { depth: 2 }));
    let tiny = Q16::from_bits(1);
    s.scale(tiny, tiny, tiny).unwrap();
    let _ = pipe.polygon(
        &[ep(e, e, e), ep(-e, e, e), ep(e, -e, e)],
        Rgb888::WHITE,
        &mut sink,
    );
    let st = pipe.stats();
    assert_eq!(
        st.faces_in,
        st.culled + st.clipped_away + st.emitted + st.rejected
    );
    // The orthographic extremes.
    let o = Orthographic::new(Q16::MAX, Q16::from_bits(-e), Q16::from_bits(e)).unwrap();
    let mut pipe = Pipeline::<2, 16>::new(
        o,
        Viewport::new(1, 1, Vertex::from_bits(i16::MIN, i16::MAX)).unwrap(),
    );
    for tri in &corners {
        let _ = pipe.polygon(tri, Rgb888::WHITE, &mut sink).unwrap();
    }
    for (p, _, _) in &sink.0 {
        assert_in_window(p, 2047, 2047);
    }
}

#[test]
fn capacity_is_an_error() {
    let cam = cam_persp();
    let proj = Perspective::new(q(cam.k), q(cam.near), q(cam.far)).unwrap();
    let mut pipe = Pipeline::<2, 4>::new(proj, Viewport::centred(512, 256).unwrap());
    let mut sink = Collect::default();
    // Both fit as given, but the near clip adds a vertex.
    let tri = [[0.0, 0.1, -5.0], [1.0, 0.1, 5.0], [-1.0, 0.1, 5.0]].map(pt);
    let quad = [
        [0.0, 0.1, -5.0],
        [1.0, 0.1, 5.0],
        [0.0, 0.1, 9.0],
        [-1.0, 0.1, 5.0],
    ]
    .map(pt);
    assert_eq!(
        pipe.polygon(&tri, Rgb888::WHITE, &mut sink),
        Ok(Outcome::Emitted)
    );
    assert_eq!(sink.0[0].0.len(), 4);
    assert_eq!(
        pipe.polygon(&quad, Rgb888::WHITE, &mut sink),
        Err(PipelineError::Capacity { capacity: 4 })
    );
    let five = [pt([0.0, 0.0, 5.0]); 5];
    assert_eq!(
        pipe.polygon(&five, Rgb888::WHITE, &mut sink),
        Err(PipelineError::Capacity { capacity: 4 })
    );
}

// ---------------------------------------------------------------------
// Random transforms and polygons: never a panic, always in the window.

fn coord() -> impl Strategy<Value = f64> {
    prop_oneof![
        30 => -30.0..30.0f64,
        6 => -3000.0..3000.0f64,
        1 => prop::sample::select(vec![0.0, 1.0, -1.0, 16383.99, -16383.99, 32767.0, -32768.0]),
    ]
}

/// A point in view space around `cam`'s view: `u`, `v` across the window
/// (±1 reaches a quarter window beyond each side), `t` in depth (negative
/// is behind the near plane, for perspective far behind the eye).
fn frustum_point(cam: &Cam, [u, v, t]: [f64; 3]) -> V3 {
    let lim = |x: f64| x.clamp(-16000.0, 16000.0);
    let z = lim(if cam.persp {
        cam.near * (1.0 + 30.0 * t)
    } else {
        cam.near + t * (cam.far - cam.near)
    });
    let s = if cam.persp {
        z.abs().max(cam.near) / cam.k
    } else {
        1.0 / cam.k
    };
    let sx = cam.w * (0.5 + 0.75 * u);
    let sy = cam.h * (0.5 + 0.75 * v);
    [lim((sx - cam.cx) * s), lim((sy - cam.cy) * s), z]
}

fn unit3() -> impl Strategy<Value = [f64; 3]> {
    prop::array::uniform3(-1.5..1.5f64)
}

fn camera() -> impl Strategy<Value = Cam> {
    prop_oneof![
        (
            1.0..4000.0f64,
            0.004..5.0f64,
            1.01..1000.0f64,
            1u16..=2047,
            1u16..=2047
        )
            .prop_map(|(k, n, r, w, h)| Cam {
                persp: true,
                k,
                near: n,
                far: (n * r).min(16000.0),
                w: w as f64,
                h: h as f64,
                cx: w as f64 / 2.0,
                cy: h as f64 / 3.0,
            }),
        (
            0.01..200.0f64,
            -100.0..100.0f64,
            0.1..1000.0f64,
            1u16..=512,
            1u16..=512
        )
            .prop_map(|(k, n, r, w, h)| Cam {
                persp: false,
                k,
                near: n,
                far: n + r,
                w: w as f64,
                h: h as f64,
                cx: 0.0,
                cy: h as f64,
            }),
    ]
    .prop_map(Cam::quantised)
}

/// Cameras whose near plane is at least `f/2048`, so that a view-space
/// step at the near plane is at most 1/32 px.
fn sane_camera() -> impl Strategy<Value = Cam> {
    camera().prop_map(|mut c| {
        if c.persp {
            c.near = c.near.max(c.k / 2048.0);
            c.far = c.far.max(c.near * 1.01);
        }
        c.quantised()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_scenes_never_panic_and_stay_in_the_window(
        cam in camera(),
        eye in prop::array::uniform3(-50.0..50.0f64),
        yaw in any::<u16>(),
        pitch in any::<u16>(),
        ops in prop::collection::vec(op(), 0..5),
        polys in prop::collection::vec(prop::collection::vec(prop::array::uniform3(coord()), 1..9), 1..6),
        framed in prop::collection::vec(prop::collection::vec(unit3(), 1..9), 0..6),
        thickness in 0i16..200,
        light in (prop::array::uniform3(-5i32..5), 0u8..=120),
    ) {
        let mut pipe = cam.pipeline();
        pipe.set_thickness(Coord::from_bits(thickness));
        if let Ok(l) = Light::new(light.0, light.1) {
            pipe.set_light(l);
        }
        // Polygons around the view first, in view space; then the others
        // under a random view and model transform.
        let mut sink = Collect::default();
        let mut two_sided = Vec::new();
        for poly in &framed {
            let pts: Vec<Point3> = poly.iter().map(|&u| pt(frustum_point(&cam, u))).collect();
            let out = pipe.polygon(&pts, Rgb888::CYAN, &mut sink);
            prop_assert!(out.is_ok());
            if out == Ok(Outcome::Emitted) {
                two_sided.push(pts.len() < 3);
            }
        }
        let _ = pipe.set_view(&View { eye: pt(eye), yaw: Angle::from_bits(yaw), pitch: Angle::from_bits(pitch) });
        for op in &ops {
            let s = pipe.stack_mut();
            let _ = match *op {
                Op::T(t) => s.translate(q(t[0]), q(t[1]), q(t[2])),
                Op::Rx(a) => s.rotate_x(Angle::from_bits(a)),
                Op::Ry(a) => s.rotate_y(Angle::from_bits(a)),
                Op::Rz(a) => s.rotate_z(Angle::from_bits(a)),
                Op::S(v) => s.scale(q(v[0]), q(v[1]), q(v[2])),
                Op::Push => s.push(),
                Op::Pop => s.pop(),
            };
        }
        for poly in &polys {
            let pts: Vec<Point3> = poly.iter().map(|&p| pt(p)).collect();
            match pipe.polygon(&pts, Rgb888::CYAN, &mut sink) {
                Ok(Outcome::Emitted) => two_sided.push(pts.len() < 3),
                Err(PipelineError::Sink(e)) => match e {},
                Ok(_) | Err(_) => {}
            }
            let _ = pipe.project_point(pts[0]);
        }
        for ((p, _, two), want) in sink.0.iter().zip(&two_sided) {
            prop_assert!(p.len() >= 3);
            prop_assert_eq!(two, want);
            for v in p {
                prop_assert!((0..=cam.w as i32 * 16).contains(&v.x.units()), "{:?}", p);
                prop_assert!((0..=cam.h as i32 * 16).contains(&v.y.units()), "{:?}", p);
            }
        }
        let s: PipelineStats = pipe.stats();
        prop_assert_eq!(s.faces_in as usize, polys.len() + framed.len());
        prop_assert_eq!(s.faces_in, s.culled + s.clipped_away + s.emitted + s.rejected);
        prop_assert_eq!(s.emitted as usize, sink.0.len());
    }

    /// Faces in view space against the reference stage: same vertices,
    /// where the reference has a clear area.
    #[test]
    fn random_faces_match_the_reference(
        cam in sane_camera(),
        face in prop::array::uniform3(unit3()),
    ) {
        let mut pipe = cam.pipeline();
        // The reference sees the same Q16.16 points.
        let f: Vec<V3> = face.iter().map(|&u| pt(frustum_point(&cam, u)).to_bits().map(|c| c as f64 / 65536.0)).collect();
        let face_pts = f.clone();
        // The reference's facing, away from ties.
        let n = {
            let (a, b, c) = (f[0], f[1], f[2]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        };
        let det = if cam.persp { f[0][0] * n[0] + f[0][1] * n[1] + f[0][2] * n[2] } else { n[2] };
        let scale = if cam.persp { 1e3 } else { 1.0 };
        prop_assume!(det.abs() > 1e-3 * scale);
        let mut sink = Collect::default();
        let out = pipe.polygon(&face_pts.iter().map(|&p| pt(p)).collect::<Vec<_>>(), Rgb888::WHITE, &mut sink).unwrap();
        if det > 0.0 {
            prop_assert_eq!(out, Outcome::Culled);
            return Ok(());
        }
        let want = stage_ref(&cam, &face_pts);
        // Only cases with a clear answer: a clear area and not a sliver (one
        // that rounding could flatten), or nothing at all.
        let perimeter: f64 = (0..want.len())
            .map(|i| {
                let (a, b) = (want[i], want[(i + 1) % want.len()]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .sum();
        if want.len() >= 3 && area(&want).abs() > 2.0 && area(&want).abs() > perimeter * 0.1 {
            prop_assert_eq!(out, Outcome::Emitted);
            let got: Vec<V3> = sink.0[0].0.iter().map(fl).collect();
            // Positions within 1/32 px of rounding, plus the projection's
            // 1/100 px, plus half a view-space step where the near clip made
            // the vertex (f·2⁻¹⁷/near px).
            let step = if cam.persp { cam.k / cam.near } else { cam.k } / 131072.0;
            let tol = ROUNDING + step + 1e-9;
            assert_close(&got, &want, tol);
            assert_depths(&cam, [f[0], f[1], f[2]], &got, step);
        } else if want.is_empty() {
            prop_assert_ne!(out, Outcome::Emitted);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Constructors and set-up functions take any input without a panic.
    #[test]
    fn set_up_never_panics(
        a in any::<[i32; 3]>(),
        b in any::<[i32; 3]>(),
        x in any::<i64>(),
        y in any::<i64>(),
        fov in any::<u16>(),
        width in any::<u16>(),
        height in any::<u16>(),
        near in any::<i32>(),
        far in any::<i32>(),
        k in any::<i32>(),
        pct in any::<u8>(),
        c in any::<(i16, i16)>(),
    ) {
        let p = |v: [i32; 3]| Point3::from_bits(v[0], v[1], v[2]);
        if let Ok(v) = View::look_at(p(a), p(b)) {
            let _ = v.matrix();
        }
        let _ = trig::atan2(y, x);
        let _ = Light::new(a, pct);
        let _ = Q16::from_ratio(a[0], a[1]);
        let _ = Angle::from_turns(a[0], a[1]);
        let _ = Angle::from_degrees(a[2]);
        let (n, f, kk) = (Q16::from_bits(near), Q16::from_bits(far), Q16::from_bits(k));
        let _ = Perspective::from_fov(Angle::from_bits(fov), width, n, f);
        let _ = Perspective::new(kk, n, f);
        let _ = Orthographic::new(kk, n, f);
        let _ = Viewport::new(width, height, Vertex::from_bits(c.0, c.1));
        let _ = Viewport::centred(width, height);
        let m = Matrix::from_rows([[a[0], a[1], a[2], b[0]], [b[1], b[2], a[0], a[1]], [a[2], b[0], b[1], b[2]]]);
        if let Some(m) = m {
            let _ = m.transform(p(b));
            let _ = m.checked_mul(&m);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    /// Facing is the whole polygon's orientation as projected: for random
    /// star-shaped faces, convex or concave (reflex corners anywhere, the
    /// first three vertices included), tilted and in either winding, a
    /// face is culled exactly when the f64 shoelace sum of its projection
    /// is not negative.
    #[test]
    fn facing_is_the_projected_orientation_of_the_whole_polygon(
        spokes in prop::collection::vec((0.0..1.0f64, 0.3..3.0f64), 4..12),
        start in 0usize..12,
        reverse in any::<bool>(),
        (tx, ty) in (-1.2..1.2f64, -1.2..1.2f64),
        centre in (-4.0..4.0f64, -3.0..3.0f64, 6.0..60.0f64),
    ) {
        // Angles spread over the turn, each in its own sector: a simple
        // star-shaped polygon around the origin.
        let n = spokes.len();
        let mut face: Vec<V3> = spokes
            .iter()
            .enumerate()
            .map(|(k, &(a, r))| {
                let t = std::f64::consts::TAU * (k as f64 + 0.1 + 0.8 * a) / n as f64;
                [r * t.cos(), r * t.sin(), 0.0]
            })
            .collect();
        face.rotate_left(start % n);
        if reverse {
            face.reverse();
        }
        let m = mul(&trans([centre.0, centre.1, centre.2]), &mul(&rot_y(tx), &rot_x(ty)));
        let view: Vec<V3> = face.iter().map(|&p| apply(&m, p)).collect();
        let cam = cam_persp();
        let projected: Vec<V3> = view.iter().map(|&v| cam.project(v)).collect();
        let a = area(&projected);
        prop_assume!(a.abs() > 1.0);
        let mut pipe = cam.pipeline();
        let mut sink = Collect::default();
        let pts: Vec<Point3> = view.iter().map(|&v| pt(v)).collect();
        let got = pipe.polygon(&pts, Rgb888::RED, &mut sink).unwrap();
        prop_assert_eq!(got != Outcome::Culled, a < 0.0, "area {} {:?}", a, got);
    }
}
