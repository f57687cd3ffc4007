//! `port::AsyncPanel` and `FramePass::draw_async` through a recording
//! async SPI mock whose every transfer stays in flight for one poll, as a
//! DMA transfer does: every byte and address window against a full render,
//! the changed rows only, the order (each band drawn while the one before
//! it is on its way), and errors.

use std::cell::RefCell;
use std::convert::Infallible;
use std::future::Future;
use std::pin::pin;
use std::rc::Rc;
use std::task::{Context, Poll, Waker};

use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::{ErrorType as PinErrorType, OutputPin};
use embedded_hal_async::spi::{ErrorType, Operation, SpiDevice};
use scanvert::frame::{DrawableLayer, FrameError, FramePass, Layer};
use scanvert::port::band::{Band, BandsError, DirtyRows};
use scanvert::port::panel::{CASET, RAMWR, RASET};
use scanvert::port::{AsyncPanel, Counts, PanelError};
use scanvert::visible::VisibleError;

const W: u16 = 96;
const H: u16 = 64;
const ROWS: u16 = 8;

#[derive(Clone, Debug, PartialEq, Eq)]
enum Event {
    /// A layer drew the band at this row.
    Draw(u16),
    /// A write of this many bytes started, and ended.
    Start(usize),
    End(usize),
}

#[derive(Default)]
struct Log {
    dc: bool,
    /// (dc level, bytes) per write.
    writes: Vec<(bool, Vec<u8>)>,
    events: Vec<Event>,
    /// Fail the write that would be this one (counting from 0).
    fail_at: Option<usize>,
}

/// A transfer in flight: pending on its first poll, done on the next.
struct InFlight(bool);
impl Future for InFlight {
    type Output = ();
    fn poll(mut self: std::pin::Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<()> {
        if self.0 {
            Poll::Ready(())
        } else {
            self.0 = true;
            cx.waker().wake_by_ref();
            Poll::Pending
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct SpiFault;
impl embedded_hal::spi::Error for SpiFault {
    fn kind(&self) -> embedded_hal::spi::ErrorKind {
        embedded_hal::spi::ErrorKind::Other
    }
}

struct Spi(Rc<RefCell<Log>>);
struct Dc(Rc<RefCell<Log>>);

impl ErrorType for Spi {
    type Error = SpiFault;
}
impl SpiDevice for Spi {
    async fn transaction(&mut self, ops: &mut [Operation<'_, u8>]) -> Result<(), SpiFault> {
        for op in ops {
            let Operation::Write(b) = op else {
                panic!("only writes expected")
            };
            {
                let mut l = self.0.borrow_mut();
                if l.fail_at == Some(l.writes.len()) {
                    return Err(SpiFault);
                }
                let dc = l.dc;
                l.writes.push((dc, b.to_vec()));
                l.events.push(Event::Start(b.len()));
            }
            InFlight(false).await;
            self.0.borrow_mut().events.push(Event::End(b.len()));
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

/// A layer that logs the bands it draws.
struct Logged<'l, L>(L, Rc<RefCell<Log>>, std::marker::PhantomData<&'l ()>);
impl<L: Layer<Rgb565>> Layer<Rgb565> for Logged<'_, L> {
    fn draw(
        &mut self,
        band: &mut Band<'_, Rgb565>,
        background: Option<Rgb565>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        self.1.borrow_mut().events.push(Event::Draw(band.y()));
        self.0.draw(band, background)
    }
    fn take_changes(&mut self, dirty: Option<&mut DirtyRows<'_>>) {
        self.0.take_changes(dirty)
    }
}

/// Runs `f` to completion, polling it again whenever it is pending.
fn block_on<F: Future>(f: F) -> F::Output {
    let mut f = pin!(f);
    let mut cx = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(v) = f.as_mut().poll(&mut cx) {
            return v;
        }
    }
}

/// Replays the writes into a panel memory; returns the address windows
/// (x0, x1, y0, y1) in order.
fn replay(log: &Log, mem: &mut [Rgb565]) -> Vec<(u16, u16, u16, u16)> {
    let (mut cmd, mut cols, mut rows) = (0u8, (0, 0), (0, 0));
    let (mut windows, mut at, mut half) = (Vec::new(), 0usize, None::<u8>);
    let be = |b: &[u8]| {
        (
            u16::from_be_bytes([b[0], b[1]]),
            u16::from_be_bytes([b[2], b[3]]),
        )
    };
    for (dc, bytes) in &log.writes {
        if !dc {
            assert_eq!(bytes.len(), 1, "a command is one byte");
            cmd = bytes[0];
            if cmd == RAMWR {
                windows.push((cols.0, cols.1, rows.0, rows.1));
                at = 0;
            }
            continue;
        }
        match cmd {
            CASET => cols = be(bytes),
            RASET => rows = be(bytes),
            RAMWR => {
                for &b in bytes {
                    let Some(hi) = half.take() else {
                        half = Some(b);
                        continue;
                    };
                    let w = (cols.1 - cols.0 + 1) as usize;
                    let (x, y) = (cols.0 as usize + at % w, rows.0 as usize + at / w);
                    mem[y * W as usize + x] =
                        Rgb565::from(RawU16::new(u16::from_be_bytes([hi, b])));
                    at += 1;
                }
            }
            other => panic!("unexpected command {other:#x}"),
        }
    }
    assert!(half.is_none(), "an odd byte of pixels");
    windows
}

fn dot(x: i32) -> embedded_graphics::primitives::Styled<Circle, PrimitiveStyle<Rgb565>> {
    Circle::new(Point::new(x, 20), 17).into_styled(PrimitiveStyle::with_fill(Rgb565::RED))
}

fn bar() -> embedded_graphics::primitives::Styled<Rectangle, PrimitiveStyle<Rgb565>> {
    Rectangle::new(Point::new(5, 45), Size::new(80, 12))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::BLUE))
}

/// The frame drawn whole by embedded-graphics.
fn full(x: i32) -> Vec<Rgb565> {
    let mut fb = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut t = scanvert::port::FrameBuffer::new(&mut fb, W, H).unwrap();
    bar().draw(&mut t).unwrap();
    dot(x).draw(&mut t).unwrap();
    fb
}

fn setup(fail_at: Option<usize>) -> (Rc<RefCell<Log>>, Spi, Dc) {
    let log = Rc::new(RefCell::new(Log {
        fail_at,
        ..Log::default()
    }));
    (log.clone(), Spi(log.clone()), Dc(log))
}

#[test]
fn every_byte_and_window_equals_a_full_render() {
    for buf_len in [2 * ROWS as usize * W as usize, 64, 3] {
        let (log, spi, dc) = setup(None);
        let mut buf = vec![0u8; buf_len];
        let mut panel = AsyncPanel::new(spi, dc, &mut buf);
        let (mut a, mut b) = (
            vec![Rgb565::BLACK; (ROWS * W) as usize],
            vec![Rgb565::BLACK; (ROWS * W) as usize],
        );
        let mut bar_layer = DrawableLayer::new(bar());
        let mut dot_layer = DrawableLayer::new(dot(10));
        let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bar_layer, &mut dot_layer];
        block_on(FramePass::new((W, H), Rgb565::BLACK).draw_async(
            layers,
            ROWS,
            (&mut a, &mut b),
            &mut panel,
        ))
        .expect("frame");
        let mut mem = vec![Rgb565::GREEN; W as usize * H as usize];
        let windows = replay(&log.borrow(), &mut mem);
        let want: Vec<_> = (0..H / ROWS)
            .map(|k| (0, W - 1, k * ROWS, k * ROWS + ROWS - 1))
            .collect();
        assert_eq!(windows, want, "buffer of {buf_len} bytes");
        assert!(mem == full(10), "buffer of {buf_len} bytes");
    }
}

#[test]
fn each_band_is_drawn_while_the_last_is_in_flight() {
    let (log, spi, dc) = setup(None);
    let mut buf = vec![0u8; 2 * ROWS as usize * W as usize];
    let mut panel = AsyncPanel::new(spi, dc, &mut buf);
    let (mut a, mut b) = (
        vec![Rgb565::BLACK; (ROWS * W) as usize],
        vec![Rgb565::BLACK; (ROWS * W) as usize],
    );
    let mut bars = Logged(DrawableLayer::new(bar()), log.clone(), Default::default());
    let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bars];
    block_on(FramePass::new((W, H), Rgb565::BLACK).draw_async(
        layers,
        ROWS,
        (&mut a, &mut b),
        &mut panel,
    ))
    .expect("frame");
    let band_bytes = 2 * (ROWS * W) as usize;
    let events = log.borrow().events.clone();
    for k in 1..H / ROWS {
        // Band k is drawn after band k − 1's pixels started, before they end.
        let started = events
            .iter()
            .enumerate()
            .filter(|(_, e)| **e == Event::Start(band_bytes))
            .nth(k as usize - 1)
            .map(|(i, _)| i)
            .unwrap();
        let ended = started
            + events[started..]
                .iter()
                .position(|e| *e == Event::End(band_bytes))
                .unwrap();
        let drawn = events
            .iter()
            .position(|e| *e == Event::Draw(k * ROWS))
            .unwrap();
        assert!(started < drawn && drawn < ended, "band {k}: {events:?}");
    }
}

#[test]
fn changed_rows_only() {
    let (log, spi, dc) = setup(None);
    let mut buf = vec![0u8; 2 * ROWS as usize * W as usize];
    let mut panel = AsyncPanel::new(spi, dc, &mut buf);
    let (mut a, mut b) = (
        vec![Rgb565::BLACK; (ROWS * W) as usize],
        vec![Rgb565::BLACK; (ROWS * W) as usize],
    );
    let mut bar_layer = DrawableLayer::new(bar());
    let mut dot_layer = DrawableLayer::new(dot(10));
    let mut pass = FramePass::new((W, H), Rgb565::BLACK);
    {
        let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bar_layer, &mut dot_layer];
        block_on(pass.draw_async(layers, ROWS, (&mut a, &mut b), &mut panel)).expect("first frame");
    }
    dot_layer.set(dot(50));
    let mut bits = [0u32; DirtyRows::words(H)];
    let mut dirty = DirtyRows::new(&mut bits, H).unwrap();
    let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bar_layer, &mut dot_layer];
    let sent =
        block_on(pass.draw_marked_async(layers, &mut dirty, ROWS, (&mut a, &mut b), &mut panel))
            .expect("second frame");
    // The dot's 17 rows, before and after: rows 20..37.
    assert_eq!(sent, 17);
    let mut mem = vec![Rgb565::GREEN; W as usize * H as usize];
    replay(&log.borrow(), &mut mem);
    assert!(mem == full(50));
}

#[test]
fn a_failed_transfer_names_its_band() {
    // Writes a band: CASET + 4, RASET + 4, RAMWR, pixels = 6 writes.
    let (_log, spi, dc) = setup(Some(6 + 5));
    let mut buf = vec![0u8; 2 * ROWS as usize * W as usize];
    let mut panel = AsyncPanel::new(spi, dc, &mut buf);
    let (mut a, mut b) = (
        vec![Rgb565::BLACK; (ROWS * W) as usize],
        vec![Rgb565::BLACK; (ROWS * W) as usize],
    );
    let mut bar_layer = DrawableLayer::new(bar());
    let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bar_layer];
    let e = block_on(FramePass::new((W, H), Rgb565::BLACK).draw_async(
        layers,
        ROWS,
        (&mut a, &mut b),
        &mut panel,
    ))
    .expect_err("the second band's pixels fail");
    assert!(
        matches!(
            e,
            BandsError::Ship {
                y: 8,
                error: PanelError::Spi(SpiFault)
            }
        ),
        "{e:?}"
    );
    // A buffer too short for a band is refused before anything is sent.
    let (log, spi, dc) = setup(None);
    let mut panel = AsyncPanel::new(spi, dc, &mut buf);
    let mut short = vec![Rgb565::BLACK; 10];
    let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut bar_layer];
    let e: FrameError<_> = block_on(FramePass::new((W, H), Rgb565::BLACK).draw_async(
        layers,
        ROWS,
        (&mut a, &mut short),
        &mut panel,
    ))
    .expect_err("short buffer");
    assert!(matches!(e, BandsError::Band(_)), "{e:?}");
    assert!(log.borrow().writes.is_empty());
}
