//! The 512 × 256 `poly3` scenes of about 170 faces that the
//! visible-surface stages are measured on, on the host
//! (`host_tests/examples/visible_modes.rs`) and on target (the firmware
//! image's `poly3-layered` and `poly3-tilted`, from
//! `host_tests/tests/on_target_scenes.rs`).
//!
//! Each generator draws from the same [`Rng`]; [`all`] makes them in the
//! order the measurements use, so the scenes are the same everywhere.

use crate::reference3d::{drawn, Poly3};
use crate::rng::Rng;
use crate::scenes3d::{add, V3};

/// Frame width of the scenes.
pub const W: u16 = 512;
/// Frame height of the scenes.
pub const H: u16 = 256;

fn scale(a: V3, k: i32) -> V3 {
    (a.0 * k, a.1 * k, a.2 * k)
}

fn front(mut p: Vec<V3>) -> Poly3 {
    if !drawn(&p) {
        p.reverse();
    }
    Poly3 {
        poly: p,
        clip: None,
    }
}

/// 170 faces parallel to the screen, each at a depth of its own.
pub fn flat(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|k| {
            let (x, y) = (
                rng.range(-400, W as i32 * 16),
                rng.range(-400, H as i32 * 16),
            );
            let (w, h) = (rng.range(160, 1400), rng.range(160, 1000));
            let z = rng.range(-30000, 30000) / 170 * 170 + k;
            if k % 2 == 0 {
                front(vec![
                    (x, y, z),
                    (x, y + h, z),
                    (x + w, y + h, z),
                    (x + w, y, z),
                ])
            } else {
                front(vec![
                    (x, y, z),
                    (x - w / 2, y + h, z),
                    (x + w, y + h / 2, z),
                ])
            }
        })
        .collect()
}

/// 170 tilted triangles and parallelograms whose depths overlap.
pub fn tilted(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|k| {
            let o = (
                rng.range(-400, W as i32 * 16),
                rng.range(-400, H as i32 * 16),
                rng.range(-8000, 8000),
            );
            let u = (
                rng.range(-1200, 1200),
                rng.range(-800, 800),
                rng.range(-6000, 6000),
            );
            let v = (
                rng.range(-1200, 1200),
                rng.range(-800, 800),
                rng.range(-6000, 6000),
            );
            if k % 2 == 0 {
                front(vec![o, add(o, u), add(o, v)])
            } else {
                front(vec![o, add(o, u), add(add(o, u), v), add(o, v)])
            }
        })
        .collect()
}

/// 170 large triangles through each other: many intersecting spans.
pub fn dense(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|_| {
            let p = |rng: &mut Rng| {
                (
                    rng.range(-1600, W as i32 * 16 + 1600),
                    rng.range(-800, H as i32 * 16 + 800),
                    rng.range(-30000, 30000),
                )
            };
            front(vec![p(rng), p(rng), p(rng)])
        })
        .collect()
}

/// Bars over a map, in an oblique parallel projection: a 10 × 7 grid of
/// tiles and 20 bars (boxes, three faces culled each), about 190 `poly3`s.
pub fn bars(rng: &mut Rng) -> Vec<Poly3> {
    // Screen-space images of the world axes (x east, y north, z up), in
    // units; depth grows to the north and to the west and falls upwards.
    let ex = (640, 96, -900);
    let ey = (-288, -224, 1600);
    let ez = (0, -480, -400);
    let origin = (1100, 3000, 2000);
    let at =
        |x: i32, y: i32, z: i32| add(add(add(origin, scale(ex, x)), scale(ey, y)), scale(ez, z));
    let mut out = Vec::new();
    for gy in 0..7 {
        for gx in 0..10 {
            // Corners in eighths of a cell, so that the tiles are planar.
            let c = |x: i32, y: i32| {
                let p = add(add(scale(ex, x), scale(ey, y)), scale(origin, 8));
                (p.0 / 8, p.1 / 8, p.2 / 8)
            };
            let (x, y) = (gx * 8, gy * 8);
            out.push(front(vec![
                c(x, y),
                c(x + 8, y),
                c(x + 8, y + 8),
                c(x, y + 8),
            ]));
        }
    }
    for _ in 0..20 {
        let (gx, gy) = (rng.range(0, 10), rng.range(0, 7));
        let h = rng.range(1, 4);
        let o = at(gx, gy, 0);
        let (u, v, w) = (scale(ex, 1), scale(ey, 1), scale(ez, h));
        // Outward windings; the culling rule drops the back three.
        let face = |c: V3, e1: V3, e2: V3| vec![c, add(c, e1), add(add(c, e1), e2), add(c, e2)];
        for f in [
            face(o, v, u),
            face(add(o, w), u, v),
            face(o, w, v),
            face(add(o, u), v, w),
            face(o, u, w),
            face(add(o, v), w, u),
        ] {
            // Both windings are possible for a left-handed image of the
            // axes; keep the given winding and let culling decide.
            out.push(Poly3 {
                poly: f,
                clip: None,
            });
        }
    }
    out
}

/// The four scenes by name, `flat`, `tilted`, `bars` and `dense`, made
/// in that order from one seed.
pub fn all() -> [(&'static str, Vec<Poly3>); 4] {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    [
        ("flat", flat(&mut rng)),
        ("tilted", tilted(&mut rng)),
        ("bars", bars(&mut rng)),
        ("dense", dense(&mut rng)),
    ]
}
