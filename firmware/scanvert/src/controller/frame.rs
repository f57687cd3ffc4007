//! One frame pass over a stack of layers: the last stage before the
//! panel.
//!
//! A frame is drawn top to bottom, a band of rows at a time, into a buffer
//! of `rows × width` pixels, with no frame buffer (or into a whole frame,
//! as one band as high as the frame). Each band goes through every
//! [`Layer`] of the stack in painter's order, lowest first, and is then
//! shipped to a [`BandTarget`] (a panel's link, a DMA channel, the rows of
//! an image). The layers are what the application shows:
//!
//! | layer | what it draws |
//! |---|---|
//! | [`ListBands`](crate::controller::ListBands) | a display list: its 2D commands in painter's order, then its 3D layer (hidden surfaces) and labels |
//! | [`SceneBands`] | a retained 3D [`Scene`]: its visible faces, then its labels |
//! | [`DrawableLayer`] | any embedded-graphics `Drawable`: text in any font, circles, rounded rectangles, images |
//!
//! [`FramePass`] is the one driver: it checks each band (rows, buffer,
//! order), lets the layers step over the rows it skips, draws only the
//! runs of changed rows when asked ([`FramePass::draw_marked`]), and ships.
//! [`Controller::render_bands`](crate::controller::Controller::render_bands),
//! [`Scene::draw_bands`](crate::scene::Scene::draw_bands) and
//! [`Scene::draw_marked`](crate::scene::Scene::draw_marked) are that
//! driver over one layer.
//!
//! # The background
//!
//! A band's buffer holds the last band's pixels. The lowest layer is told
//! the frame's background and covers every pixel of the band: with its own
//! runs where it can (the 3D sweep writes the background as runs between
//! faces, each pixel once), else by a fill first. The layers above draw
//! only what they cover.
//!
//! # Changed rows
//!
//! [`DirtyRows`] marks the rows to draw again. A [`DrawableLayer`] layer marks
//! the rows of what changed in it (what was there and what is there now,
//! by bounding box); [`Scene::update_marking`](crate::scene::Scene::update_marking)
//! marks the rows whose content a scene update changed; the pass marks
//! every row on its first frame and when its background changes
//! ([`FramePass::set_background`]).
//! [`FramePass::draw_marked`] asks every layer for its marks, then draws
//! and ships only the marked rows. A panel that keeps its pixels then
//! shows the whole frame.
//!
//! # Two buffers
//!
//! With a target that ships by DMA ([`AsyncBandTarget`], such as
//! [`AsyncPanel`](crate::port::panel::AsyncPanel) over
//! `embedded-hal-async`), [`FramePass::draw_async`] and
//! [`FramePass::draw_marked_async`] draw each band while the one before
//! it is on its way, alternating two buffers the caller lends.
//!
//! ```
//! use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
//! use embedded_graphics::prelude::*;
//! use embedded_graphics::primitives::{Circle, PrimitiveStyle};
//! use embedded_graphics::text::Text;
//! use scanvert::frame::{DrawableLayer, FramePass, Layer};
//! use scanvert::pixelcolor::Rgb565;
//! use scanvert::port::band::{BandTarget, DirtyRows};
//!
//! /// Stands for a panel: counts the rows it is sent.
//! struct Panel(u32);
//! impl BandTarget for Panel {
//!     type Color = Rgb565;
//!     type Error = core::convert::Infallible;
//!     fn ship(&mut self, _y: u16, rows: u16, _px: &[Rgb565]) -> Result<(), Self::Error> {
//!         self.0 += rows as u32;
//!         Ok(())
//!     }
//! }
//!
//! let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
//! let dot = |x| Circle::new(Point::new(x, 40), 9).into_styled(PrimitiveStyle::with_fill(Rgb565::RED));
//! let mut clock = DrawableLayer::new(Text::new("12:00", Point::new(2, 10), style));
//! let mut marker = DrawableLayer::new(dot(10));
//! let mut band = [Rgb565::BLACK; 8 * 64];
//! let mut panel = Panel(0);
//! // The pass is kept from frame to frame. The first frame: every row.
//! let mut pass = FramePass::new((64, 64), Rgb565::BLACK);
//! pass.draw(&mut [&mut clock, &mut marker], 8, &mut band, &mut panel)?;
//! assert_eq!(panel.0, 64);
//! // The dot moves: only the rows it was and is on are drawn and sent.
//! marker.set(dot(30));
//! let mut bits = [0u32; DirtyRows::words(64)];
//! let mut dirty = DirtyRows::new(&mut bits, 64).unwrap();
//! let sent = pass.draw_marked(&mut [&mut clock, &mut marker], &mut dirty, 8, &mut band, &mut panel)?;
//! assert_eq!(sent, 9);
//! // A new background may show on any row: all of them are sent.
//! pass.set_background(Rgb565::BLUE);
//! dirty.clear();
//! let sent = pass.draw_marked(&mut [&mut clock, &mut marker], &mut dirty, 8, &mut band, &mut panel)?;
//! assert_eq!(sent, 64);
//! # Ok::<(), scanvert::frame::FrameError<core::convert::Infallible>>(())
//! ```

use crate::color::ListColor;
use crate::port::band::{check_band, check_buffer, fill_background};
use crate::port::band::{AsyncBandTarget, Band, BandTarget, BandsError, DirtyRows};
use crate::port::Counts;
use crate::scene::{Frame, Scene, SceneBands, SceneBandsError};
use crate::visible::{Resolve, VisibleError};
use core::convert::Infallible;
use core::future::{poll_fn, Future};
use core::pin::pin;
use core::task::Poll;
use embedded_graphics::mono_font::MonoFont;
use embedded_graphics_core::pixelcolor::PixelColor;

mod drawable;
mod packed;

pub use drawable::DrawableLayer;
pub use packed::PackedLayer;

/// Why a frame pass could not draw or ship a band: the band (nothing was
/// drawn into it), a layer's visible-surface workspace, or the target.
pub type FrameError<E> = BandsError<VisibleError<Infallible>, E>;

/// One layer of a frame: what it draws on a band's rows.
///
/// Bands come from one top-to-bottom pass: each starts at or below the
/// end of the last one, and the rows between were skipped (a layer with
/// state by row, such as the 2D edge table or the 3D sweep, steps over
/// them).
pub trait Layer<C: PixelColor> {
    /// Draws the layer's part of rows `band.y()..band.end()` over what the
    /// layers below drew. With `background`, this is the lowest layer
    /// and the band holds stale pixels: the layer writes every pixel of
    /// the band, `background` where it has nothing (or its own
    /// background: a display list's last `clear`).
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>>;

    /// Marks in `dirty` the rows where the layer changed since the last
    /// pass, and forgets them; with `None` (a pass of the whole frame),
    /// only forgets them. Layers that are built anew for each frame (a
    /// display list's, a scene's pass) mark nothing here: their changes
    /// are found where they are made
    /// ([`Scene::update_marking`](crate::scene::Scene::update_marking)).
    fn take_changes(&mut self, dirty: Option<&mut DirtyRows<'_>>) {
        let _ = dirty;
    }
}

/// A stack of layers is a layer: each draws in turn, lowest first, the
/// lowest with the background (an empty stack fills the band with it).
impl<C: PixelColor> Layer<C> for [&mut dyn Layer<C>] {
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        let mut background = background;
        let mut counts = Counts::default();
        for layer in self.iter_mut() {
            counts += layer.draw(band, background.take())?;
        }
        fill_background(band, background);
        Ok(counts)
    }

    fn take_changes(&mut self, mut dirty: Option<&mut DirtyRows<'_>>) {
        for layer in self.iter_mut() {
            layer.take_changes(dirty.as_deref_mut());
        }
    }
}

impl<C: PixelColor, L: Layer<C> + ?Sized> Layer<C> for &mut L {
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        (**self).draw(band, background)
    }

    fn take_changes(&mut self, dirty: Option<&mut DirtyRows<'_>>) {
        (**self).take_changes(dirty)
    }
}

/// One top-to-bottom pass over a frame's layers (see the
/// [module](self) docs).
#[derive(Clone, Copy, Debug)]
pub struct FramePass<C> {
    size: (u16, u16),
    background: C,
    /// The background of the last frame shipped whole or by its marks;
    /// `None` before the first, when the panel's pixels are unknown.
    shown: Option<C>,
    next: u16,
    counts: Counts,
}

impl<C: PixelColor> FramePass<C> {
    /// A pass over a frame of `size` (width, height), whose pixels no
    /// layer covers are `background`.
    pub fn new(size: (u16, u16), background: C) -> Self {
        FramePass {
            size,
            background,
            shown: None,
            next: 0,
            counts: Counts::default(),
        }
    }

    /// The frame's background.
    pub fn background(&self) -> C {
        self.background
    }

    /// Changes the background. The next
    /// [`draw_marked`](Self::draw_marked) then draws every row, since the
    /// background may show anywhere.
    pub fn set_background(&mut self, background: C) {
        self.background = background;
    }

    /// Starts a frame: from the top row, with no spans counted.
    fn restart(&mut self) {
        self.next = 0;
        self.counts = Counts::default();
    }

    /// Marks every row in `dirty` when the panel may not show this pass's
    /// background: before the pass's first frame, or after
    /// [`set_background`](Self::set_background) changed it.
    fn mark_background(&self, dirty: &mut DirtyRows<'_>) {
        if self.shown != Some(self.background) {
            dirty.mark_all();
        }
    }

    /// The frame's width and height.
    pub fn size(&self) -> (u16, u16) {
        self.size
    }

    /// The first row the next band may start at.
    pub fn next_row(&self) -> u16 {
        self.next
    }

    /// Spans and pixels the layers wrote so far.
    pub fn counts(&self) -> Counts {
        self.counts
    }

    /// Draws rows `y..y + rows` (cut at the frame's last row) through
    /// every layer, lowest first, into `pixels` (row by row, the frame's
    /// width a row), and returns the rows drawn. Rows between the last
    /// band and `y` are skipped. Nothing is drawn when the band is
    /// refused.
    ///
    /// This is the pass one band at a time: with two buffers, one band
    /// is drawn while the other is on its way. A band at row 0 starts a
    /// new frame.
    pub fn draw_band(
        &mut self,
        layers: &mut [&mut dyn Layer<C>],
        y: u16,
        rows: u16,
        pixels: &mut [C],
    ) -> Result<u16, FrameError<Infallible>> {
        if y == 0 {
            self.restart();
        }
        self.band_of(layers, y, rows, pixels)
    }

    /// [`draw_band`](Self::draw_band) through a stack of layers or one:
    /// one layer's drawing is compiled into the pass, with what it can
    /// know of the background.
    fn band_of<L: Layer<C> + ?Sized>(
        &mut self,
        layers: &mut L,
        y: u16,
        rows: u16,
        pixels: &mut [C],
    ) -> Result<u16, FrameError<Infallible>> {
        check_band(y, rows, self.next, self.size.1)?;
        let mut band = Band::new(pixels, self.size, y, rows)?;
        self.counts += layers
            .draw(&mut band, Some(self.background))
            .map_err(BandsError::Render)?;
        self.next = band.end();
        Ok(band.rows())
    }

    /// Draws the whole frame band by band, `rows` rows at a time, through
    /// the caller's buffer `band` (at least `rows × width` pixels), each
    /// band handed to `target` before the next is drawn. The layers'
    /// changes are forgotten: every row is drawn.
    pub fn draw<P>(
        &mut self,
        layers: &mut [&mut dyn Layer<C>],
        rows: u16,
        band: &mut [C],
        target: &mut P,
    ) -> Result<Counts, FrameError<P::Error>>
    where
        P: BandTarget<Color = C> + ?Sized,
    {
        let h = self.size.1;
        layers.take_changes(None);
        let done = self.draw_runs(layers, core::iter::once((0, h)), rows, band, target);
        self.shown_after(done).map(|(counts, _)| counts)
    }

    /// Draws only the rows that changed: every layer marks its changes in
    /// `dirty` ([`Layer::take_changes`]) over what is marked there already
    /// (by [`Scene::update_marking`](crate::scene::Scene::update_marking),
    /// or by hand), then the marked rows are drawn in bands of at most
    /// `rows` rows and shipped, the rows between stepped over. Returns
    /// the rows shipped; `dirty` is left as it was marked.
    ///
    /// Keep the pass from frame to frame: it remembers the background it
    /// last shipped, and marks every row on its first frame and after
    /// the background changes. A pass made anew each frame draws every
    /// row each time.
    pub fn draw_marked<P>(
        &mut self,
        layers: &mut [&mut dyn Layer<C>],
        dirty: &mut DirtyRows<'_>,
        rows: u16,
        band: &mut [C],
        target: &mut P,
    ) -> Result<u32, FrameError<P::Error>>
    where
        P: BandTarget<Color = C> + ?Sized,
    {
        layers.take_changes(Some(dirty));
        self.mark_background(dirty);
        let done = self.draw_runs(layers, dirty.runs(), rows, band, target);
        self.shown_after(done).map(|(_, shipped)| shipped)
    }

    /// [`draw`](Self::draw) with shipping that overlaps drawing: bands go
    /// alternately into `buffers.0` and `buffers.1` (each at least
    /// `rows × width` pixels), and each band is drawn while the one
    /// before it is on its way to `target`.
    pub async fn draw_async<P>(
        &mut self,
        layers: &mut [&mut dyn Layer<C>],
        rows: u16,
        buffers: (&mut [C], &mut [C]),
        target: &mut P,
    ) -> Result<Counts, FrameError<P::Error>>
    where
        P: AsyncBandTarget<Color = C> + ?Sized,
    {
        let h = self.size.1;
        layers.take_changes(None);
        let done = self
            .ship_runs_async(layers, core::iter::once((0, h)), rows, buffers, target)
            .await;
        self.shown_after(done).map(|(counts, _)| counts)
    }

    /// [`draw_marked`](Self::draw_marked) with shipping that overlaps
    /// drawing, through two buffers as [`draw_async`](Self::draw_async).
    /// Returns the rows shipped. Like `draw_marked`, it marks every row on
    /// the pass's first frame and after the background changes.
    pub async fn draw_marked_async<P>(
        &mut self,
        layers: &mut [&mut dyn Layer<C>],
        dirty: &mut DirtyRows<'_>,
        rows: u16,
        buffers: (&mut [C], &mut [C]),
        target: &mut P,
    ) -> Result<u32, FrameError<P::Error>>
    where
        P: AsyncBandTarget<Color = C> + ?Sized,
    {
        layers.take_changes(Some(dirty));
        self.mark_background(dirty);
        let done = self
            .ship_runs_async(layers, dirty.runs(), rows, buffers, target)
            .await;
        self.shown_after(done).map(|(_, shipped)| shipped)
    }

    /// Draws the runs of rows `runs` into the two buffers in turn; each
    /// band's place is sent, its transfer started (the future polled
    /// once), the next band drawn, then the transfer awaited. A band that
    /// fails to draw is reported once the transfer before it is done.
    async fn ship_runs_async<L, P, R>(
        &mut self,
        layers: &mut L,
        runs: R,
        rows: u16,
        (a, b): (&mut [C], &mut [C]),
        target: &mut P,
    ) -> Result<(Counts, u32), FrameError<P::Error>>
    where
        L: Layer<C> + ?Sized,
        P: AsyncBandTarget<Color = C> + ?Sized,
        R: IntoIterator<Item = (u16, u16)>,
    {
        self.restart();
        check_buffer(rows, self.size, a.len())?;
        check_buffer(rows, self.size, b.len())?;
        let w = self.size.0 as usize;
        let mut bands = runs.into_iter().flat_map(move |(y0, y1)| {
            (y0..y1)
                .step_by(rows as usize)
                .map(move |y| (y, rows.min(y1 - y)))
        });
        let Some((mut y, first)) = bands.next() else {
            return Ok((self.counts, 0));
        };
        let (mut cur, mut next) = (a, b);
        let mut n = self.band_of(layers, y, first, cur).map_err(widen)?;
        let mut shipped = 0u32;
        loop {
            let following = bands.next();
            let mut drawn = None;
            let ship = |error| BandsError::Ship { y, error };
            target.begin(y, n, self.size.0).await.map_err(ship)?;
            {
                let mut send = pin!(target.send(&cur[..n as usize * w]));
                // The first poll starts the transfer.
                let started = poll_fn(|cx| Poll::Ready(send.as_mut().poll(cx))).await;
                if let Some((y2, n2)) = following {
                    drawn = Some((y2, self.band_of(layers, y2, n2, next)));
                }
                let sent = match started {
                    Poll::Ready(r) => r,
                    Poll::Pending => send.await,
                };
                sent.map_err(ship)?;
            }
            shipped += n as u32;
            let Some((y2, band)) = drawn else {
                return Ok((self.counts, shipped));
            };
            (y, n) = (y2, band.map_err(widen)?);
            core::mem::swap(&mut cur, &mut next);
        }
    }

    /// Draws and ships the runs of rows `runs` (top to bottom), in bands
    /// of at most `rows` rows; returns the counts and the rows shipped.
    pub(crate) fn draw_runs<L, P, R>(
        &mut self,
        layers: &mut L,
        runs: R,
        rows: u16,
        band: &mut [C],
        target: &mut P,
    ) -> Result<(Counts, u32), FrameError<P::Error>>
    where
        L: Layer<C> + ?Sized,
        P: BandTarget<Color = C> + ?Sized,
        R: IntoIterator<Item = (u16, u16)>,
    {
        self.restart();
        check_buffer(rows, self.size, band.len())?;
        let w = self.size.0 as usize;
        self.each_band(runs, rows, |pass, y, n| {
            let n = pass.band_of(layers, y, n, band).map_err(widen)?;
            target
                .ship(y, n, &band[..n as usize * w])
                .map_err(|error| BandsError::Ship { y, error })?;
            Ok(n)
        })
    }

    /// The driver's loop, whatever the band is made of: `band(pass, y,
    /// n)` draws and ships rows `y..y + n` and returns the rows it drew,
    /// for each band of at most `rows` rows of the runs of rows `runs`,
    /// top to bottom. Returns the counts and the rows shipped.
    pub(crate) fn each_band<E, R>(
        &mut self,
        runs: R,
        rows: u16,
        mut band: impl FnMut(&mut Self, u16, u16) -> Result<u16, FrameError<E>>,
    ) -> Result<(Counts, u32), FrameError<E>>
    where
        R: IntoIterator<Item = (u16, u16)>,
    {
        let mut shipped = 0u32;
        for (y0, y1) in runs {
            let mut y = y0;
            while y < y1 {
                let n = band(self, y, rows.min(y1 - y))?;
                shipped += n as u32;
                y += n;
            }
        }
        Ok((self.counts, shipped))
    }

    /// `done`, a frame's result, remembered: after a frame shipped whole
    /// or by its marks, the panel shows this pass's background; after a
    /// failed one, nothing is known of it.
    pub(crate) fn shown_after<T, E>(&mut self, done: Result<T, E>) -> Result<T, E> {
        self.shown = done.is_ok().then_some(self.background);
        done
    }
}

/// A band's error, as one of a target's.
pub(crate) fn widen<R, E>(e: BandsError<R, Infallible>) -> BandsError<R, E> {
    match e {
        BandsError::Band(b) => BandsError::Band(b),
        BandsError::Render(r) => BandsError::Render(r),
        BandsError::Ship { error, .. } => match error {},
    }
}

/// A scene's pass as a layer: its visible faces, then its labels. As the
/// lowest layer it writes the background between the faces itself.
impl<C: ListColor> Layer<C> for SceneBands<'_, '_, '_, C> {
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        self.draw_band(band, background)
    }
}

/// A scene through the frame pass as its one layer.
impl<const DEPTH: usize, const N: usize> Scene<'_, DEPTH, N> {
    /// Draws the scene band by band, `rows` rows at a time, through the
    /// caller's buffer `band` (at least `rows × width` pixels), each band
    /// handed to `target` to ship before the next is drawn: the pixels
    /// [`draw`](Scene::draw) writes with `Some(background)`.
    pub fn draw_bands<P>(
        &mut self,
        resolve: Resolve,
        background: P::Color,
        font: &MonoFont<'_>,
        rows: u16,
        band: &mut [P::Color],
        target: &mut P,
    ) -> Result<Frame, SceneBandsError<P::Error>>
    where
        P: BandTarget + ?Sized,
        P::Color: ListColor,
    {
        let all = core::iter::once((0, self.store().height()));
        self.draw_runs(resolve, background, font, all, rows, band, target)
            .map(|(frame, _)| frame)
    }

    /// Draws only the rows marked in `dirty`, in bands of at most `rows`
    /// rows through the caller's buffer `band`, each shipped to `target`
    /// as [`draw_bands`](Self::draw_bands) ships them: one top-to-bottom
    /// pass, the rows between stepped over. A panel that keeps its pixels
    /// then shows the whole frame. Returns what was drawn and the rows
    /// shipped.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_marked<P>(
        &mut self,
        resolve: Resolve,
        background: P::Color,
        font: &MonoFont<'_>,
        dirty: &DirtyRows<'_>,
        rows: u16,
        band: &mut [P::Color],
        target: &mut P,
    ) -> Result<(Frame, u32), SceneBandsError<P::Error>>
    where
        P: BandTarget + ?Sized,
        P::Color: ListColor,
    {
        self.draw_runs(resolve, background, font, dirty.runs(), rows, band, target)
    }

    /// The scene's rows `runs` through a frame pass of its one layer.
    #[allow(clippy::too_many_arguments)]
    fn draw_runs<P, R>(
        &mut self,
        resolve: Resolve,
        background: P::Color,
        font: &MonoFont<'_>,
        runs: R,
        rows: u16,
        band: &mut [P::Color],
        target: &mut P,
    ) -> Result<(Frame, u32), SceneBandsError<P::Error>>
    where
        P: BandTarget + ?Sized,
        P::Color: ListColor,
        R: IntoIterator<Item = (u16, u16)>,
    {
        let size = (self.store().width(), self.store().height());
        check_buffer(rows, size, band.len())?;
        let mut pass = self
            .bands(resolve, background, font)
            .map_err(BandsError::Render)?;
        let (_, shipped) =
            FramePass::new(size, background).draw_runs(&mut pass, runs, rows, band, target)?;
        Ok((pass.frame(), shipped))
    }
}
