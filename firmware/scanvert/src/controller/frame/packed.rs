//! The frame pass into a band of words ([`PackedBand`]: two 16-bit pixels
//! a word, in a panel's wire order), shipped to a [`PackedBandTarget`].
//!
//! The same pass as into a band of pixels, over layers that can draw into
//! words ([`PackedLayer`]): every layer of this crate can, and a stack of
//! them is one.

use super::{widen, DrawableLayer, FrameError, FramePass, Layer};
use crate::color::ListColor;
use crate::port::band::{check_band, check_buffer, BandsError, DirtyRows};
use crate::port::packed_band::{PackedBand, PackedBandTarget};
use crate::port::runs::Rows;
use crate::port::Counts;
use crate::scene::SceneBands;
use crate::visible::VisibleError;
use core::convert::Infallible;
use embedded_graphics::prelude::{Dimensions, Drawable};
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::PixelColor;

/// A [`Layer`] that also draws into a band of words.
pub trait PackedLayer<C>: Layer<C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    /// Draws the layer's part of rows `band.y()..band.end()`, as
    /// [`Layer::draw`] draws it into a band of pixels: the same pixels.
    fn draw_packed(
        &mut self,
        band: &mut PackedBand<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>>;
}

/// A stack of layers that draw into words is a layer: each draws in
/// turn, lowest first, the lowest with the background.
impl<C> Layer<C> for [&mut dyn PackedLayer<C>]
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    fn draw(
        &mut self,
        band: &mut crate::port::band::Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        let mut background = background;
        let mut counts = Counts::default();
        for layer in self.iter_mut() {
            counts += layer.draw(band, background.take())?;
        }
        crate::port::band::fill_background(band, background);
        Ok(counts)
    }

    fn take_changes(&mut self, mut dirty: Option<&mut DirtyRows<'_>>) {
        for layer in self.iter_mut() {
            layer.take_changes(dirty.as_deref_mut());
        }
    }
}

impl<C> PackedLayer<C> for [&mut dyn PackedLayer<C>]
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    fn draw_packed(
        &mut self,
        band: &mut PackedBand<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        let mut background = background;
        let mut counts = Counts::default();
        for layer in self.iter_mut() {
            counts += layer.draw_packed(band, background.take())?;
        }
        band.background(background);
        Ok(counts)
    }
}

impl<C, L> PackedLayer<C> for &mut L
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
    L: PackedLayer<C> + ?Sized,
{
    fn draw_packed(
        &mut self,
        band: &mut PackedBand<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        (**self).draw_packed(band, background)
    }
}

/// A scene's pass into words: its visible faces, then its labels.
impl<C> PackedLayer<C> for SceneBands<'_, '_, '_, C>
where
    C: ListColor + Into<RawU16> + From<RawU16>,
{
    fn draw_packed(
        &mut self,
        band: &mut PackedBand<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        self.draw_band(band, background)
    }
}

/// An embedded-graphics drawable into words: drawn into the band, cut to
/// its rows, when its bounding box meets them.
impl<C, D> PackedLayer<C> for DrawableLayer<D>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
    D: Drawable<Color = C> + Dimensions,
{
    fn draw_packed(
        &mut self,
        band: &mut PackedBand<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        band.background(background);
        if !self.meets(band.y(), band.end()) {
            return Ok(Counts::default());
        }
        match self.item().draw(band) {
            Ok(_) => Ok(Counts::default()),
            Err(e) => match e {},
        }
    }
}

impl<C> FramePass<C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    /// [`draw_band`](Self::draw_band) into a band of words: rows `y..y +
    /// rows` through every layer into `words` (at least
    /// [`PackedBand::words_len`]`(width, rows)`); returns the rows drawn.
    pub fn draw_band_packed(
        &mut self,
        layers: &mut [&mut dyn PackedLayer<C>],
        y: u16,
        rows: u16,
        words: &mut [u32],
    ) -> Result<u16, FrameError<Infallible>> {
        if y == 0 {
            self.restart();
        }
        self.band_of_packed(layers, y, rows, words)
    }

    fn band_of_packed<L: PackedLayer<C> + ?Sized>(
        &mut self,
        layers: &mut L,
        y: u16,
        rows: u16,
        words: &mut [u32],
    ) -> Result<u16, FrameError<Infallible>> {
        check_band(y, rows, self.next, self.size.1)?;
        let mut band = PackedBand::new(words, self.size, y, rows)?;
        self.counts += layers
            .draw_packed(&mut band, Some(self.background))
            .map_err(BandsError::Render)?;
        self.next = band.end();
        Ok(band.rows())
    }

    /// [`draw`](Self::draw) into a band of words: the whole frame, `rows`
    /// rows at a time, through `words` (at least
    /// [`PackedBand::words_len`]`(width, rows)`), each band's words handed
    /// to `target` before the next is drawn.
    pub fn draw_packed<P>(
        &mut self,
        layers: &mut [&mut dyn PackedLayer<C>],
        rows: u16,
        words: &mut [u32],
        target: &mut P,
    ) -> Result<Counts, FrameError<P::Error>>
    where
        P: PackedBandTarget<Color = C> + ?Sized,
    {
        let h = self.size.1;
        layers.take_changes(None);
        let done = self.packed_runs(layers, core::iter::once((0, h)), rows, words, target);
        self.shown_after(done).map(|(counts, _)| counts)
    }

    /// [`draw_marked`](Self::draw_marked) into a band of words: only the
    /// marked rows (the layers' changes added to `dirty`), in bands of at
    /// most `rows` rows, each shipped to `target`. Returns the rows
    /// shipped.
    pub fn draw_marked_packed<P>(
        &mut self,
        layers: &mut [&mut dyn PackedLayer<C>],
        dirty: &mut DirtyRows<'_>,
        rows: u16,
        words: &mut [u32],
        target: &mut P,
    ) -> Result<u32, FrameError<P::Error>>
    where
        P: PackedBandTarget<Color = C> + ?Sized,
    {
        layers.take_changes(Some(dirty));
        self.mark_background(dirty);
        let done = self.packed_runs(layers, dirty.runs(), rows, words, target);
        self.shown_after(done).map(|(_, shipped)| shipped)
    }

    /// Draws and ships the runs of rows `runs` (top to bottom) into words,
    /// in bands of at most `rows` rows; returns the counts and the rows
    /// shipped.
    fn packed_runs<L, P, R>(
        &mut self,
        layers: &mut L,
        runs: R,
        rows: u16,
        words: &mut [u32],
        target: &mut P,
    ) -> Result<(Counts, u32), FrameError<P::Error>>
    where
        L: PackedLayer<C> + ?Sized,
        P: PackedBandTarget<Color = C> + ?Sized,
        R: IntoIterator<Item = (u16, u16)>,
    {
        self.restart();
        check_buffer(rows, self.size, words.len().saturating_mul(2))?;
        let w = self.size.0;
        self.each_band(runs, rows, |pass, y, n| {
            let n = pass.band_of_packed(layers, y, n, words).map_err(widen)?;
            let len = PackedBand::<C>::words_len(w, n);
            target
                .ship_words(y, n, w, &words[..len])
                .map_err(|error| BandsError::Ship { y, error })?;
            Ok(n)
        })
    }
}
