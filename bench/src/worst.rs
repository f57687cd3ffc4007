//! The visible-surface sweep's worst case, timed in one process: the
//! staggered faces of `testkit::staggered` (1,000 to 38,835 of them, each
//! nearer than the last, the same listed last to first, each farther),
//! written as display lists (a colour and a `poly3` a face) and rendered through the controller into a 1024 × 1024 RGB565
//! frame. `--only worst` rewrites the section between [`BEGIN`] and
//! [`END`] of `docs/performance.md` and `docs/worst-case.png`.

use crate::numbers::thousands;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::{Coord, Vertex3};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert_sim::memory::ListMemory;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};
use testkit::reference3d::Poly3;
use testkit::staggered::{staggered, Order, H, W};

/// Face counts timed (the last makes a list of 970,895 bytes).
pub const SIZES: [usize; 6] = [1_000, 2_000, 4_000, 8_000, 16_000, 38_835];

/// The orders, and their names in the table.
pub const ORDERS: [(Order, &str); 3] = [
    (Order::Nearer, "nearer"),
    (Order::Reversed, "reversed"),
    (Order::Farther, "farther"),
];

/// Markers of the section `--only worst` rewrites.
pub const BEGIN: &str = "<!-- worst-curve:begin -->";
/// End marker.
pub const END: &str = "<!-- worst-curve:end -->";

/// One list's time.
pub struct WorstRow {
    pub faces: usize,
    /// Index into [`ORDERS`].
    pub order: usize,
    /// Best time of a render, seconds.
    pub seconds: f64,
    /// Bytes of the list.
    pub bytes: usize,
}

/// The display list of `faces`: a black clear, then each face's colour
/// and the face (25 bytes a face).
fn list(faces: &[Poly3]) -> Vec<u8> {
    let size = 20 + faces.iter().map(|p| 7 + 6 * p.poly.len()).sum::<usize>();
    let mut buf = vec![0u8; size];
    let mut w = Writer::new(&mut buf, W, H).expect("frame size");
    w.clear(Rgb888::BLACK).expect("sized");
    let v = |(x, y, z): (i32, i32, i32)| Vertex3 {
        x: Coord::from_bits(x as i16),
        y: Coord::from_bits(y as i16),
        z: Coord::from_bits(z as i16),
    };
    for (k, p) in faces.iter().enumerate() {
        w.color(Rgb888::new(k as u8, (k >> 8) as u8, 0xff))
            .expect("sized");
        w.poly3(p.poly.iter().copied().map(v)).expect("3 vertices");
    }
    w.finish().to_vec()
}

/// `--write-worst DIR`: writes the lists timed here into `dir`, as
/// `nearer-N.dl`, `reversed-N.dl` and `farther-N.dl` for each of
/// [`SIZES`], for timing `scanvert render` on them.
pub fn write_lists(dir: &std::path::Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for &n in &SIZES {
        for (order, name) in ORDERS {
            std::fs::write(
                dir.join(format!("{name}-{n}.dl")),
                list(&staggered(n, order)),
            )?;
        }
    }
    Ok(())
}

/// Renders each list until at least `budget` has passed (at least once,
/// at most 5 times) and keeps the best time.
pub fn measure(budget: Duration) -> Vec<WorstRow> {
    let mut rows = Vec::new();
    let mut fb = vec![Rgb565::BLACK; W as usize * H as usize];
    for &faces in &SIZES {
        for (order, (o, name)) in ORDERS.iter().enumerate() {
            let bytes = list(&staggered(faces, *o));
            let list = DisplayList::new_checked(&bytes).expect("list");
            let mut mem = ListMemory::for_list(&list).expect("the 3D layer runs");
            let (mut best, start) = (f64::INFINITY, Instant::now());
            for _ in 0..5 {
                let t = Instant::now();
                let mut f = FrameBuffer::new(&mut fb, W, H).expect("frame");
                mem.controller()
                    .render(black_box(&list), &mut f)
                    .expect("renders");
                best = best.min(t.elapsed().as_secs_f64());
                if start.elapsed() >= budget {
                    break;
                }
            }
            eprintln!("worst {name:>8} {faces:>6} faces: {best:.3} s");
            rows.push(WorstRow {
                faces,
                order,
                seconds: best,
                bytes: bytes.len(),
            });
        }
    }
    rows
}

/// The section: how it is measured, the table, the plot, and the growth
/// between the two largest sizes.
pub fn section(rows: &[WorstRow], machine: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{BEGIN}\n### The scaling curve\n\n\
         ![worst cases: time against faces](worst-case.png)\n\n\
         Written by `cargo run --release -p scanvert-bench -- --only worst` ({machine}); the\n\
         full run keeps it. The same lists as above, written in the benchmark's process and\n\
         rendered by `Controller::render` into a 1024 × 1024 RGB565 frame: the list checked,\n\
         the faces cut, resolved and written (its memory sized beforehand, no program start,\n\
         no PNG), best of up to 5 renders within 0.3 s, in seconds:\n"
    );
    let _ = writeln!(s, "| faces | list (bytes) | nearer | reversed | farther |");
    let _ = writeln!(s, "|--:|--:|--:|--:|--:|");
    for &faces in &SIZES {
        let of = |order: usize| rows.iter().find(|r| r.faces == faces && r.order == order);
        let Some(first) = of(0) else { continue };
        let _ = write!(
            s,
            "| {} | {} |",
            thousands(faces as f64),
            thousands(first.bytes as f64)
        );
        for order in 0..ORDERS.len() {
            let _ = write!(
                s,
                " {} |",
                of(order).map_or("n/a".into(), |r| secs(r.seconds))
            );
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
    // The exponent of n between the two largest sizes, per order.
    let (a, b) = (SIZES[SIZES.len() - 2], SIZES[SIZES.len() - 1]);
    let mut growth = Vec::new();
    for (order, (_, name)) in ORDERS.iter().enumerate() {
        let t = |n: usize| {
            rows.iter()
                .find(|r| r.faces == n && r.order == order)
                .map(|r| r.seconds)
        };
        if let (Some(ta), Some(tb)) = (t(a), t(b)) {
            let k = (tb / ta).ln() / (b as f64 / a as f64).ln();
            growth.push(format!("{name} `n^{k:.2}`"));
        }
    }
    let _ = writeln!(
        s,
        "From {} to {} faces the time grows as: {} (an exponent near 1 is linear, near 2\n\
         quadratic; the smallest lists take milliseconds, where the noise of a shared host\n\
         shows).\n\n{END}\n",
        thousands(a as f64),
        thousands(b as f64),
        growth.join(", ")
    );
    s
}

/// Seconds to three significant places or milliseconds.
fn secs(v: f64) -> String {
    if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}
