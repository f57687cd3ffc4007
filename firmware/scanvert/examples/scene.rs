//! A retained 3D scene: two segments, one of which moves between two
//! frames, so that only it is rebuilt.
//!
//! Each segment is described by a procedure of the application (here a
//! closure). `Scene::update` rebuilds the stale segments alone and counts
//! the work; `Scene::draw` resolves the visible surfaces row by row,
//! without a z-buffer, and draws the labels last.
//!
//! ```sh
//! cargo run -p scanvert --example scene
//! ```

use scanvert::port::checksum::frame_checksum;
use scanvert::prelude::*;
use scanvert::scene::SceneStorage;
use scanvert::scene::DEFAULT_FONT;
use scanvert::{Angle, Builder, Perspective, Pipeline, Point3, Resolve, Scene, SceneError};
use scanvert::{View, Viewport, Q16};

const W: u16 = 48;
const H: u16 = 20;

/// A square of side 4 at the builder's current transform.
fn square(b: &mut Builder<'_, '_, 4, 16>, c: Rgb888) -> Result<(), SceneError> {
    let corners = [(-2, -2), (2, -2), (2, 2), (-2, 2)].map(|(x, y)| Point3::from_int(x, y, 0));
    b.face(&corners, c).map(|_| ())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // All the scene's memory in one value, its capacities as const
    // generics: 64 trapezoids, 8 faces, 2 segments, H rows of the index,
    // 16 edge slots, 16 active trapezoids a row, W runs a row, 2 labels and
    // 16 bytes of label text. It could as well be a `static`.
    let mut storage =
        SceneStorage::<64, 8, 2, { H as usize }, 16, 16, { W as usize }, 2, 16>::new();
    let persp = Perspective::from_fov(
        Angle::from_degrees(60),
        W,
        Q16::from_int(1),
        Q16::from_int(100),
    )?;
    let mut scene = Scene::new(
        storage.as_memory(),
        Pipeline::<4, 16>::new(persp, Viewport::centred(W, H)?),
    )?;
    scene.set_view(&View {
        eye: Point3::from_int(0, 0, 10),
        yaw: Angle::ZERO,
        pitch: Angle::ZERO,
    })?;

    let mut pixels = [Rgb565::BLACK; W as usize * H as usize];

    // Segment 0 stands still; segment 1, a square behind it with a label,
    // moves right between the frames.
    let mut still = |b: &mut Builder<'_, '_, 4, 16>| square(b, Rgb888::RED);
    for (frame, x) in [-3, 2].into_iter().enumerate() {
        let mut moving = |b: &mut Builder<'_, '_, 4, 16>| {
            b.translate(Q16::from_int(x), Q16::from_int(1), Q16::from_int(-4))?;
            square(b, Rgb888::BLUE)?;
            b.label(Point3::from_int(-2, -2, 0), "B", Rgb888::WHITE)
                .map(|_| ())
        };
        if frame > 0 {
            scene.invalidate(1)?; // the application says segment 1 changed
        }
        let u = scene.update(&mut [&mut still, &mut moving])?;
        let mut fb = FrameBuffer::new(&mut pixels, W, H).ok_or("frame size")?;
        let f = scene.draw(
            Resolve::Crossing,
            Some(Rgb565::BLACK),
            DEFAULT_FONT,
            &mut fb,
        )?;

        for y in 0..H {
            let glyph = |c: &Rgb565| match *c {
                Rgb565::RED => 'r',
                Rgb565::BLUE => 'b',
                Rgb565::WHITE => '#',
                _ => '.',
            };
            println!(
                "{}",
                fb.row(y)
                    .ok_or("row")?
                    .iter()
                    .map(glyph)
                    .collect::<String>()
            );
        }
        println!(
            "frame {frame}: segments rebuilt {}, trapezoids cut {}, spans {}, labels {}; checksum {:08x}\n",
            u.regenerated, u.trapezoids, f.decoded.spans, f.labels.drawn, frame_checksum(fb.pixels())
        );
    }
    let clears = |s| scene.store().segment(s).map_or(0, |g| g.counters().clears);
    println!("builds: segment 0 {}, segment 1 {}", clears(0), clears(1));
    Ok(())
}
