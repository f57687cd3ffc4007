//! `port::Panel` through a recording SPI mock: command order, the address
//! window of every band, and every pixel byte against a full render.

use std::cell::RefCell;
use std::convert::Infallible;
use std::rc::Rc;

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal::spi::{ErrorType, Operation, SpiDevice};
use scanvert::frame::{DrawableLayer, FramePass, Layer};
use scanvert::port::band::{BandTarget, DirtyRows};
use scanvert::port::{Panel, PanelError};

const W: u16 = 240;
const H: u16 = 240;

/// An address window: first and last column, first and last row.
type Window = (u16, u16, u16, u16);

#[derive(Default)]
struct Log {
    dc: bool,
    /// (dc level, bytes) per write.
    writes: Vec<(bool, Vec<u8>)>,
    transactions: usize,
}

struct Spi(Rc<RefCell<Log>>);
struct Dc(Rc<RefCell<Log>>);

impl ErrorType for Spi {
    type Error = Infallible;
}
impl SpiDevice for Spi {
    fn transaction(&mut self, ops: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        let mut l = self.0.borrow_mut();
        l.transactions += 1;
        for op in ops {
            match op {
                Operation::Write(b) => {
                    let dc = l.dc;
                    l.writes.push((dc, b.to_vec()));
                }
                _ => panic!("only writes expected"),
            }
        }
        Ok(())
    }
}
impl PinErrorType for Dc {
    type Error = Infallible;
}
impl OutputPin for Dc {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc = false;
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc = true;
        Ok(())
    }
}

/// Replays the log into a panel memory; returns the windows (x0, x1, y0, y1).
fn replay(log: &Log, mem: &mut [u16], xo: u16, yo: u16) -> Vec<Window> {
    let (mut cmd, mut params) = (0u8, Vec::new());
    let mut win = Vec::new();
    let (mut cx, mut cy) = ((0, 0), (0, 0));
    let mut pos = 0usize;
    let mut pending: Option<u8> = None;
    for (dc, bytes) in &log.writes {
        if !dc {
            assert_eq!(bytes.len(), 1);
            cmd = bytes[0];
            params.clear();
            pending = None;
            if cmd == 0x2c {
                win.push((cx.0, cx.1, cy.0, cy.1));
                pos = 0;
            }
            continue;
        }
        match cmd {
            0x2a | 0x2b => {
                params.extend_from_slice(bytes);
                if params.len() == 4 {
                    let a = u16::from_be_bytes([params[0], params[1]]);
                    let b = u16::from_be_bytes([params[2], params[3]]);
                    if cmd == 0x2a {
                        cx = (a, b)
                    } else {
                        cy = (a, b)
                    }
                }
            }
            0x2c => {
                let w = usize::from(cx.1 - cx.0 + 1);
                for &byte in bytes {
                    match pending.take() {
                        None => pending = Some(byte),
                        Some(hi) => {
                            let x = usize::from(cx.0 - xo) + pos % w;
                            let y = usize::from(cy.0 - yo) + pos / w;
                            mem[y * usize::from(W) + x] = u16::from_be_bytes([hi, byte]);
                            pos += 1;
                        }
                    }
                }
            }
            c => panic!("unexpected command {c:#x}"),
        }
    }
    win
}

fn shapes<D: DrawTarget<Color = Rgb565>>(d: &mut D) {
    let _ = Circle::new(Point::new(30, 40), 150)
        .into_styled(PrimitiveStyle::with_fill(Rgb565::RED))
        .draw(d);
    let _ = Rectangle::new(Point::new(100, 5), Size::new(90, 200))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::GREEN, 3))
        .draw(d);
}

/// A frame memory drawn by embedded-graphics directly.
struct Full(Vec<u16>);
impl OriginDimensions for Full {
    fn size(&self) -> Size {
        Size::new(W.into(), H.into())
    }
}
impl DrawTarget for Full {
    type Color = Rgb565;
    type Error = Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in it {
            if p.x >= 0 && p.y >= 0 && p.x < W.into() && p.y < H.into() {
                self.0[p.y as usize * usize::from(W) + p.x as usize] = RawU16::from(c).into_inner();
            }
        }
        Ok(())
    }
}

fn reference() -> Vec<u16> {
    let mut f = Full(vec![
        RawU16::from(Rgb565::BLUE).into_inner();
        usize::from(W) * usize::from(H)
    ]);
    shapes(&mut f);
    f.0
}

fn run(
    rows: u16,
    marked: Option<(i32, i32)>,
    chunk: usize,
) -> (Vec<u16>, Vec<Window>, Rc<RefCell<Log>>) {
    let log = Rc::new(RefCell::new(Log::default()));
    let mut buf = vec![0u8; chunk];
    let mut panel = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut buf);
    let mut a = DrawableLayer::new(
        Circle::new(Point::new(30, 40), 150).into_styled(PrimitiveStyle::with_fill(Rgb565::RED)),
    );
    let mut b = DrawableLayer::new(
        Rectangle::new(Point::new(100, 5), Size::new(90, 200))
            .into_styled(PrimitiveStyle::with_stroke(Rgb565::GREEN, 3)),
    );
    let mut layers: [&mut dyn Layer<Rgb565>; 2] = [&mut a, &mut b];
    let mut band = vec![Rgb565::BLACK; usize::from(rows) * usize::from(W)];
    let mut pass = FramePass::new((W, H), Rgb565::BLUE);
    match marked {
        None => {
            pass.draw(&mut layers, rows, &mut band, &mut panel).unwrap();
        }
        Some((y0, y1)) => {
            let mut bits = vec![0u32; DirtyRows::words(H)];
            let mut dirty = DirtyRows::new(&mut bits, H).unwrap();
            dirty.mark(y0, y1);
            pass.draw_marked(&mut layers, &mut dirty, rows, &mut band, &mut panel)
                .unwrap();
        }
    }
    let mut mem = vec![0u16; usize::from(W) * usize::from(H)];
    let win = replay(&log.borrow(), &mut mem, 0, 0);
    (mem, win, log)
}

#[test]
fn full_pass_bytes_equal_a_full_render() {
    let want = reference();
    for rows in [1u16, 7, 16] {
        let (mem, win, log) = run(rows, None, 64);
        assert_eq!(mem, want, "rows {rows}");
        let mut y = 0;
        for &(x0, x1, y0, y1) in &win {
            assert_eq!((x0, x1, y0), (0, W - 1, y));
            y = y1 + 1;
        }
        assert_eq!(y, H);
        let l = log.borrow();
        let bytes: usize = l.writes.iter().map(|w| w.1.len()).sum();
        println!(
            "rows {rows}: {} bands, {} transactions, {} bytes",
            win.len(),
            l.transactions,
            bytes
        );
        // Per band: 3 command bytes, 8 parameter bytes.
        assert_eq!(bytes, usize::from(W) * usize::from(H) * 2 + win.len() * 11);
    }
}

#[test]
fn marked_pass_ships_marked_rows_equal_a_full_render() {
    let want = reference();
    for rows in [1u16, 7, 16] {
        let (mem, win, _) = run(rows, Some((50, 61)), 100);
        for &(_, _, y0, y1) in &win {
            for y in y0..=y1 {
                let r = usize::from(y) * usize::from(W)..usize::from(y + 1) * usize::from(W);
                assert_eq!(mem[r.clone()], want[r], "row {y}");
            }
        }
        // The marked rows are all shipped (the layers, new, may add their own).
        for y in 50..=61u16 {
            assert!(
                win.iter().any(|w| w.2 <= y && y <= w.3),
                "row {y} not shipped"
            );
        }
        for w in &win {
            assert_eq!((w.0, w.1), (0, W - 1));
        }
    }
}

/// A panel whose visible area starts at an offset in its memory (the
/// 240×135 Pico Display at 40, 53): every window is moved by it, and the
/// pixels land where they would with none.
#[test]
fn an_offset_moves_every_window() {
    let (xo, yo) = (40u16, 53u16);
    let log = Rc::new(RefCell::new(Log::default()));
    let mut buf = vec![0u8; 256];
    let mut panel = Panel::with_offset(Spi(log.clone()), Dc(log.clone()), &mut buf, xo, yo);
    let mut a = DrawableLayer::new(
        Circle::new(Point::new(30, 40), 150).into_styled(PrimitiveStyle::with_fill(Rgb565::RED)),
    );
    let mut b = DrawableLayer::new(
        Rectangle::new(Point::new(100, 5), Size::new(90, 200))
            .into_styled(PrimitiveStyle::with_stroke(Rgb565::GREEN, 3)),
    );
    let mut layers: [&mut dyn Layer<Rgb565>; 2] = [&mut a, &mut b];
    let mut band = vec![Rgb565::BLACK; 16 * usize::from(W)];
    FramePass::new((W, H), Rgb565::BLUE)
        .draw(&mut layers, 16, &mut band, &mut panel)
        .unwrap();
    let mut mem = vec![0u16; usize::from(W) * usize::from(H)];
    let win = replay(&log.borrow(), &mut mem, xo, yo);
    assert_eq!(mem, reference());
    for (k, &(x0, x1, y0, y1)) in win.iter().enumerate() {
        let y = k as u16 * 16;
        assert_eq!((x0, x1, y0, y1), (xo, xo + W - 1, yo + y, yo + y + 15));
    }
    // An offset that would carry an address past 65,535 is refused.
    let mut far = Panel::with_offset(
        Spi(log.clone()),
        Dc(log.clone()),
        &mut buf,
        u16::MAX - 10,
        0,
    );
    let e = far.ship(0, 1, &[Rgb565::RED; 240]).unwrap_err();
    assert!(matches!(e, PanelError::Shape), "{e:?}");
}

/// What the panel refuses, before sending anything, and the errors of
/// its link.
#[test]
fn errors_are_typed() {
    let log = Rc::new(RefCell::new(Log::default()));
    // A byte buffer of fewer than two bytes, a band that is not whole rows.
    let mut tiny = [0u8; 1];
    let mut p = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut tiny);
    assert!(matches!(
        p.ship(0, 1, &[Rgb565::RED; 4]),
        Err(PanelError::Shape)
    ));
    let mut buf = [0u8; 64];
    let mut p = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut buf);
    assert!(matches!(
        p.ship(0, 3, &[Rgb565::RED; 10]),
        Err(PanelError::Shape)
    ));
    assert!(matches!(p.ship(0, 0, &[]), Err(PanelError::Shape)));
    assert!(log.borrow().writes.is_empty(), "nothing is sent");
    // A pin that fails, and a bus that fails: each as its own variant.
    struct BadPin;
    impl PinErrorType for BadPin {
        type Error = embedded_hal::digital::ErrorKind;
    }
    impl OutputPin for BadPin {
        fn set_low(&mut self) -> Result<(), Self::Error> {
            Err(embedded_hal::digital::ErrorKind::Other)
        }
        fn set_high(&mut self) -> Result<(), Self::Error> {
            Err(embedded_hal::digital::ErrorKind::Other)
        }
    }
    let mut p = Panel::new(Spi(log.clone()), BadPin, &mut buf);
    assert!(matches!(
        p.ship(0, 1, &[Rgb565::RED; 8]),
        Err(PanelError::Pin(embedded_hal::digital::ErrorKind::Other))
    ));
    struct BadSpi;
    impl ErrorType for BadSpi {
        type Error = embedded_hal::spi::ErrorKind;
    }
    impl SpiDevice for BadSpi {
        fn transaction(&mut self, _: &mut [Operation<'_, u8>]) -> Result<(), Self::Error> {
            Err(embedded_hal::spi::ErrorKind::Other)
        }
    }
    let mut p = Panel::new(BadSpi, Dc(log.clone()), &mut buf);
    let e = p.ship(0, 1, &[Rgb565::RED; 8]).unwrap_err();
    assert!(matches!(
        e,
        PanelError::Spi(embedded_hal::spi::ErrorKind::Other)
    ));
    assert!(!e.to_string().is_empty());
}

/// The same layers through the frame pass into a band of words
/// (`PackedBand`), shipped by the panel as the words' bytes: the panel's
/// memory equals the full render, byte for byte, with the same windows
/// and bytes as bands of pixels, for chunks of whole and part words.
#[test]
fn bands_of_words_ship_the_bytes_of_bands_of_pixels() {
    use scanvert::frame::PackedLayer;
    let want = reference();
    for rows in [1u16, 7, 16] {
        for chunk in [4usize, 63, 64, 4096] {
            let log = Rc::new(RefCell::new(Log::default()));
            let mut buf = vec![0u8; chunk];
            let mut panel = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut buf);
            let mut a = DrawableLayer::new(
                Circle::new(Point::new(30, 40), 150)
                    .into_styled(PrimitiveStyle::with_fill(Rgb565::RED)),
            );
            let mut b = DrawableLayer::new(
                Rectangle::new(Point::new(100, 5), Size::new(90, 200))
                    .into_styled(PrimitiveStyle::with_stroke(Rgb565::GREEN, 3)),
            );
            let mut layers: [&mut dyn PackedLayer<Rgb565>; 2] = [&mut a, &mut b];
            let mut words = vec![0u32; (usize::from(rows) * usize::from(W)).div_ceil(2)];
            let mut pass = FramePass::new((W, H), Rgb565::BLUE);
            pass.draw_packed(&mut layers, rows, &mut words, &mut panel)
                .unwrap();
            let mut mem = vec![0u16; usize::from(W) * usize::from(H)];
            let win = replay(&log.borrow(), &mut mem, 0, 0);
            assert_eq!(mem, want, "rows {rows}, chunk {chunk}");
            let (_, pixel_win, _) = run(rows, None, 64);
            assert_eq!(win, pixel_win, "rows {rows}, chunk {chunk}");
            let bytes: usize = log.borrow().writes.iter().map(|w| w.1.len()).sum();
            assert_eq!(bytes, usize::from(W) * usize::from(H) * 2 + win.len() * 11);
        }
    }
}

/// A band of an odd number of pixels sends its pixels' bytes and not the
/// padding half; a buffer under one word or too few words are refused.
#[test]
fn bands_of_words_send_no_padding_and_refuse_bad_shapes() {
    use scanvert::port::PackedBandTarget;
    let log = Rc::new(RefCell::new(Log::default()));
    let mut buf = vec![0u8; 8];
    let mut panel = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut buf);
    // 3 × 1: pixels 0x1234, 0x5678, 0x9abc, wire order, and a padding half.
    let words = [0x7856_3412u32, 0xdead_bc9a];
    panel.ship_words(2, 1, 3, &words).unwrap();
    let l = log.borrow();
    let data: Vec<u8> = l.writes.iter().skip(5).flat_map(|w| w.1.clone()).collect();
    assert_eq!(data, [0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc]);
    drop(l);
    assert!(matches!(
        panel.ship_words(0, 1, 5, &words),
        Err(PanelError::Shape)
    ));
    assert!(matches!(
        panel.ship_words(0, 0, 3, &words),
        Err(PanelError::Shape)
    ));
    let mut small = [0u8; 3];
    let mut panel = Panel::new(Spi(log.clone()), Dc(log.clone()), &mut small);
    assert!(matches!(
        panel.ship_words(0, 1, 3, &words),
        Err(PanelError::Shape)
    ));
}
