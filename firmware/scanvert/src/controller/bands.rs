//! A display list rendered band by band, with no frame buffer (see
//! [`port::band`](crate::port::band)).
//!
//! [`Controller::bands`] prepares the frame's work once: the list is
//! checked, its 3D layer built (as [`Controller::render`] builds it, with
//! the same interpreter into the same memory), and every `poly` and `line`
//! after the last `clear` entered into an
//! [`EdgeTable`]. [`ListBands::draw`]
//! then draws the bands top to bottom, each in the full-frame path's
//! order: the background (the last `clear`'s colour, or black), the 2D
//! polygons and lines in painter's order, the 3D layer's rows over them with its
//! background skipped, then the labels cut to the band's rows. So every
//! band is, pixel for pixel, those rows of the frame [`Controller::render`]
//! draws into a black frame buffer. [`Controller::render_bands`] runs the
//! whole frame through one buffer and a [`BandTarget`].

use super::frame::{FramePass, Layer};
use super::{build_layer, Controller, ListScene, RenderError, RenderStats};
use crate::color::ListColor;
use crate::display_list::DisplayList;
use crate::port::band::{check_band, check_buffer};
use crate::port::band::{Band, BandTarget, BandsError};
use crate::port::packed_band::{PackedBand, PackedBandTarget};
use crate::port::runs::{RowRuns, Rows, RowsError};
use crate::port::Counts;
use crate::raster::table::{EdgeTable, TableError, TableMemory};
use crate::scene::label;
use crate::visible::{Sweep, VisibleError};
use core::convert::Infallible;
use core::fmt;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// Why a list's bands could not be prepared or drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PrepareError {
    /// What [`Controller::render`] would report.
    Render(RenderError<Infallible>),
    /// The edge table is too small for the list's polygons.
    Table(TableError),
}

impl PrepareError {
    /// Byte offset of the command at fault.
    pub fn offset(&self) -> usize {
        match self {
            PrepareError::Render(e) => e.offset(),
            PrepareError::Table(e) => e.offset(),
        }
    }
}

impl fmt::Display for PrepareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PrepareError::Render(e) => write!(f, "{e}"),
            PrepareError::Table(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for PrepareError {}

/// The errors of the band path of a list.
pub type ListBandsError<E> = BandsError<PrepareError, E>;

/// A display list's frame, prepared once and drawn band by band, top to
/// bottom (see the [module](self) docs). From [`Controller::bands`].
#[derive(Debug)]
pub struct ListBands<'t> {
    table: EdgeTable<'t>,
    /// The 3D layer, its pass, and the offset of its first command.
    layer: Option<ListScene<'t>>,
    /// The layer's sweep and first command's offset.
    sweep: Option<(Sweep, usize)>,
    /// The colour of the list's last `clear`.
    clear: Option<Rgb888>,
    size: (u16, u16),
    next: u16,
    stats: RenderStats,
}

impl ListBands<'_> {
    /// Bands of `list` with nothing prepared: what
    /// [`Controller::prepare`] fills.
    fn unprepared(list: &DisplayList<'_>) -> Self {
        ListBands {
            table: EdgeTable::empty(),
            layer: None,
            sweep: None,
            clear: None,
            size: (list.width(), list.height()),
            next: 0,
            stats: RenderStats::default(),
        }
    }

    /// Width and height of the frame.
    pub fn size(&self) -> (u16, u16) {
        self.size
    }

    /// The first row the next band may start at.
    pub fn next_row(&self) -> u16 {
        self.next
    }

    /// What has been drawn so far: the 3D layer's counts as of the last
    /// band; `polygons` are those entered in the table (the full frame
    /// counts every `poly`; lines are not polygons in either), and spans,
    /// pixels and labels are summed over
    /// the bands (a label reaching two bands counts twice).
    pub fn stats(&self) -> RenderStats {
        self.stats
    }

    /// The colour of rows no command writes: the last `clear`'s, or
    /// black.
    pub fn background(&self) -> Rgb888 {
        self.clear.unwrap_or(Rgb888::BLACK)
    }

    /// Draws rows `y..y + rows` (cut at the frame's last row) into
    /// `pixels`, row by row, `width` pixels a row; returns the rows drawn.
    /// Rows between the last band and `y` are skipped. Nothing is drawn
    /// when the band is refused. The same as a [`FramePass`] of this one
    /// layer over a black background.
    pub fn draw<C>(
        &mut self,
        y: u16,
        rows: u16,
        pixels: &mut [C],
    ) -> Result<u16, ListBandsError<Infallible>>
    where
        C: ListColor,
    {
        check_band(y, rows, self.next, self.size.1)?;
        let mut band = Band::new(pixels, self.size, y, rows)?;
        let background = Some(C::from_rgb888(Rgb888::BLACK));
        self.draw_band(&mut band, background)
            .map_err(|e| BandsError::Render(self.layer_error(e)))?;
        Ok(band.rows())
    }

    /// [`draw`](Self::draw) into a band of words, two pixels a word in a
    /// panel's wire order ([`PackedBand`]): the same pixels, written a
    /// word at a time; `words` holds at least
    /// [`PackedBand::words_len`]`(width, rows)`.
    pub fn draw_packed<C>(
        &mut self,
        y: u16,
        rows: u16,
        words: &mut [u32],
    ) -> Result<u16, ListBandsError<Infallible>>
    where
        C: ListColor + Into<RawU16> + From<RawU16>,
    {
        check_band(y, rows, self.next, self.size.1)?;
        let mut band = PackedBand::<C>::new(words, self.size, y, rows)?;
        let background = Some(C::from_rgb888(Rgb888::BLACK));
        self.draw_band(&mut band, background)
            .map_err(|e| BandsError::Render(self.layer_error(e)))?;
        Ok(band.rows())
    }

    /// Composes row `y` as colour runs into `row` (see
    /// [`port::runs`](crate::port::runs)), through the same stages and in
    /// the same order as [`draw`](Self::draw) draws a band of that row:
    /// the background one run, then every span inserted over it. Rows
    /// between the last one drawn and `y` are skipped. The row decodes to
    /// the pixels `draw` writes for it. Returns what was drawn.
    pub fn draw_runs<C>(
        &mut self,
        y: u16,
        row: &mut RowRuns<'_, C>,
    ) -> Result<Counts, RowsError<PrepareError>>
    where
        C: ListColor,
    {
        check_band(y, 1, self.next, self.size.1)?;
        let black = C::from_rgb888(Rgb888::BLACK);
        row.start(y, self.size, black);
        let counts = self
            .draw_band(row, Some(black))
            .map_err(|e| RowsError::Render(self.layer_error(e)))?;
        if row.overflowed() {
            return Err(RowsError::Full {
                y,
                capacity: row.capacity(),
            });
        }
        Ok(counts)
    }

    /// A visible-surface error of the 3D layer, as the full frame reports
    /// it.
    fn layer_error(&self, e: VisibleError<Infallible>) -> PrepareError {
        let first = self.sweep.as_ref().map_or(0, |(_, first)| *first);
        PrepareError::Render(super::visible_error(first, e))
    }

    /// Draws the band's rows (pixels or runs) over what is in it (see
    /// [`Layer::draw`]).
    fn draw_band<C: ListColor, B: Rows<Color = C>>(
        &mut self,
        band: &mut B,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        let (w, h) = self.size;
        let y = band.first();
        if y > self.next {
            self.table.skip(y as i32);
            if let (Some(scene), Some((sweep, _))) = (self.layer.as_mut(), self.sweep.as_mut()) {
                let (store, _, ws) = scene.band_parts();
                sweep.skip(store, ws, y - self.next)?;
            }
        }
        // The list's last `clear` covers what is below it; without one,
        // the lowest layer's background.
        let background = match self.clear {
            Some(c) => Some(C::from_rgb888(c)),
            None => background,
        };
        // With nothing 2D to draw under the 3D layer, and the layer as
        // large as the frame, the sweep writes the background runs itself
        // (every pixel once) instead of a fill that the faces overwrite.
        let layer_fills = self.table.is_empty()
            && self
                .layer
                .as_ref()
                .is_some_and(|scene| (scene.store().width(), scene.store().height()) == (w, h));
        if !layer_fills {
            band.background(background);
        }
        let mut counts = ok(self.table.draw_band(band));
        if let (Some(scene), Some((sweep, _))) = (self.layer.as_mut(), self.sweep.as_mut()) {
            let (store, labels, ws) = scene.band_parts();
            let under = if layer_fills { background } else { None };
            counts += sweep.draw(store, ws, band.count(), band, under)?;
            self.stats.visible = sweep.stats();
            let rows = (band.first() as i32, band.end() as i32);
            let c = ok(labels.draw_rows(label::DEFAULT_FONT, rows, band));
            counts += c.written;
            self.stats.labels += c.drawn;
        }
        self.stats.spans += counts.spans;
        self.stats.pixels += counts.pixels as u64;
        self.next = band.end();
        Ok(counts)
    }
}

/// A display list's frame as a layer: its 2D commands in painter's
/// order, then its 3D layer and labels. Its last `clear` covers the
/// layers below it.
impl<C: ListColor> Layer<C> for ListBands<'_> {
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        self.draw_band(band, background)
    }
}

/// A display list's frame as a layer drawn into words.
impl<C> super::frame::PackedLayer<C> for ListBands<'_>
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

impl<'e> Controller<'e> {
    /// Prepares `list` to be drawn band by band (see the
    /// [module](self) docs), with `table` for its 2D polygons and lines: checks it
    /// as [`render`](Self::render) does, builds its 3D layer, and enters
    /// its polygons. On any error nothing is drawn.
    pub fn bands<'t>(
        &'t mut self,
        list: &DisplayList<'_>,
        table: TableMemory<'t>,
    ) -> Result<ListBands<'t>, PrepareError> {
        let mut bands = ListBands::unprepared(list);
        self.prepare(list, table, &mut bands)?;
        Ok(bands)
    }

    /// [`bands`](Self::bands) into `out` (from [`ListBands::unprepared`]),
    /// which holds the 3D layer from the start: the scene, about a
    /// kilobyte, is not moved from frame to frame on the stack.
    fn prepare<'t>(
        &'t mut self,
        list: &DisplayList<'_>,
        table: TableMemory<'t>,
        out: &mut ListBands<'t>,
    ) -> Result<(), PrepareError> {
        self.check(list).map_err(PrepareError::Render)?;
        let (w, h) = (list.width(), list.height());
        let Controller {
            three,
            resolve,
            vertices,
            ..
        } = self;
        // The 3D layer as `render` builds and checks it, through the same
        // interpreter.
        let first = match three {
            Some(_) => list.summary().first_3d,
            None => None,
        };
        if let (Some(mem), Some(first)) = (three.as_mut(), first) {
            layer_into(
                (&mut out.layer, &mut out.sweep),
                (mem.reborrow(), vertices),
                list,
                first,
                *resolve,
                &mut out.stats,
            )?;
        }
        let commands = list.summary().commands as u32;
        let table = EdgeTable::build(table, list.draws((w, h)), h, commands)
            .map_err(PrepareError::Table)?;
        out.stats.commands = table.commands();
        out.stats.polygons = (table.len() - table.lines()) as u32;
        out.stats.clears = table.clear_color().is_some() as u32;
        out.clear = table.clear_color();
        out.table = table;
        Ok(())
    }

    /// Renders `list` band by band, `rows` rows at a time, through the
    /// caller's buffer `band` (at least `rows × width` pixels), each band
    /// handed to `target` to ship before the next is drawn. The frame is
    /// the list's; the pixels are those [`render`](Self::render) writes
    /// into a black frame buffer.
    pub fn render_bands<P>(
        &mut self,
        list: &DisplayList<'_>,
        table: TableMemory<'_>,
        rows: u16,
        band: &mut [P::Color],
        target: &mut P,
    ) -> Result<RenderStats, ListBandsError<P::Error>>
    where
        P: BandTarget + ?Sized,
        P::Color: ListColor,
    {
        let size = (list.width(), list.height());
        check_buffer(rows, size, band.len())?;
        let mut bands = ListBands::unprepared(list);
        self.prepare(list, table, &mut bands)
            .map_err(BandsError::Render)?;
        let black = P::Color::from_rgb888(Rgb888::BLACK);
        let all = core::iter::once((0, size.1));
        let pass = FramePass::new(size, black).draw_runs(&mut bands, all, rows, band, target);
        if let Err(e) = pass {
            return Err(match e {
                BandsError::Band(b) => BandsError::Band(b),
                BandsError::Render(e) => BandsError::Render(bands.layer_error(e)),
                BandsError::Ship { y, error } => BandsError::Ship { y, error },
            });
        }
        Ok(bands.stats())
    }
}

impl Controller<'_> {
    /// [`render_bands`](Self::render_bands) into a band buffer of words,
    /// two pixels a word in a panel's wire order ([`PackedBand`]), each
    /// band's words handed to `target`: the same pixels, written a word at
    /// a time. `words` holds at least
    /// [`PackedBand::words_len`]`(width, rows)`.
    pub fn render_bands_packed<P>(
        &mut self,
        list: &DisplayList<'_>,
        table: TableMemory<'_>,
        rows: u16,
        words: &mut [u32],
        target: &mut P,
    ) -> Result<RenderStats, ListBandsError<P::Error>>
    where
        P: PackedBandTarget + ?Sized,
        P::Color: ListColor,
    {
        let size = (list.width(), list.height());
        check_buffer(rows, size, words.len().saturating_mul(2))?;
        let mut bands = ListBands::unprepared(list);
        self.prepare(list, table, &mut bands)
            .map_err(BandsError::Render)?;
        let mut y = 0;
        while y < size.1 {
            let n = bands
                .draw_packed::<P::Color>(y, rows, words)
                .map_err(super::frame::widen)?;
            let len = PackedBand::<P::Color>::words_len(size.0, n);
            target
                .ship_words(y, n, size.0, &words[..len])
                .map_err(|error| BandsError::Ship { y, error })?;
            y += n;
        }
        Ok(bands.stats())
    }
}

/// The 3D layer of `list` built (as `render` builds it) and checked into
/// `slot`, with its sweep at row 0.
fn layer_into<'t>(
    (slot, at): (&mut Option<ListScene<'t>>, &mut Option<(Sweep, usize)>),
    mem: (
        crate::scene::SceneMemory<'t>,
        &mut [crate::geometry::ViewPoint],
    ),
    list: &DisplayList<'_>,
    first: usize,
    resolve: crate::visible::Resolve,
    stats: &mut RenderStats,
) -> Result<(), PrepareError> {
    let (w, h) = (list.width(), list.height());
    let scene = build_layer(slot, mem, list, (w, h), first, stats).map_err(PrepareError::Render)?;
    scene
        .check()
        .map_err(|e| PrepareError::Render(super::visible_error(first, e)))?;
    let resolve = scene
        .settle(resolve)
        .map_err(|e| PrepareError::Render(super::visible_error(first, e)))?;
    *at = Some((Sweep::new(scene.band_parts().2, resolve), first));
    Ok(())
}

/// The value of a result that cannot fail.
pub(crate) fn ok<T>(r: Result<T, Infallible>) -> T {
    match r {
        Ok(t) => t,
        Err(e) => match e {},
    }
}
