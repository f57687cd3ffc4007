//! A scene drawn band by band, with no frame buffer (see
//! [`port::band`](crate::port::band)).
//!
//! [`Scene::bands`] starts one top-to-bottom pass of the visible-surface
//! sweep over the scene's store, in the scene's own workspace (its
//! [`SceneMemory`](super::SceneMemory)'s active list and runs);
//! [`SceneBands::draw`] fills a band's buffer with rows `y..y + rows`: the
//! background, the visible faces, then the labels cut to the band (only
//! their glyphs' rows on it). Rows between two bands are skipped: the
//! active list jumps over them at once ([`Sweep::skip`]: one exact jump
//! per trapezoid live after them, nothing for those that start and end
//! within them, nothing resolved), so a pass that draws only the bottom
//! of the frame costs little more than those rows. The scene is only
//! read: [`Scene::bands_in`] runs a pass in
//! another [`Workspace`], so several passes may run over one scene at
//! once, each drawing some bands and skipping the others (two cores taking
//! every other band).

use super::{Frame, LabelStore, Scene, Update};
use crate::color::ListColor;
pub use crate::port::band::DirtyRows;
use crate::port::band::Mix;
use crate::port::band::{check_band, Band, BandsError};
use crate::port::packed_band::PackedBand;
use crate::port::runs::{RowRuns, Rows, RowsError};
use crate::port::Counts;
use crate::visible::store::TrapezoidStore;
use crate::visible::sweep::Checked;
use crate::visible::{Resolve, Sweep, VisibleError, Workspace};
use core::convert::Infallible;
use embedded_graphics::mono_font::MonoFont;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::RgbColor;

/// The errors of the band path of a scene.
pub type SceneBandsError<E> = BandsError<VisibleError<Infallible>, E>;

/// One top-to-bottom pass over a scene, band by band. From
/// [`Scene::bands`] or [`Scene::bands_in`].
#[derive(Debug)]
pub struct SceneBands<'s, 'a, 'w, C> {
    store: &'s TrapezoidStore<'a>,
    labels: &'s LabelStore<'a>,
    workspace: &'s mut Workspace<'w>,
    sweep: Sweep,
    background: C,
    font: &'s MonoFont<'s>,
    next: u16,
    frame: Frame,
}

impl<C: ListColor> SceneBands<'_, '_, '_, C> {
    /// The first row the next band may start at.
    pub fn next_row(&self) -> u16 {
        self.next
    }

    /// What the bands drawn so far did: spans, pixels and labels summed
    /// over the bands (a label reaching two bands counts twice).
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// Draws rows `y..y + rows` (cut at the frame's last row) into
    /// `pixels`, row by row, the frame's width a row; returns the rows
    /// drawn. Rows between the last band and `y` are skipped. Nothing is
    /// drawn when the band is refused. The same as a
    /// [`FramePass`](crate::controller::frame::FramePass) of this one
    /// layer over the pass's background.
    pub fn draw(
        &mut self,
        y: u16,
        rows: u16,
        pixels: &mut [C],
    ) -> Result<u16, SceneBandsError<Infallible>> {
        let size = (self.store.width(), self.store.height());
        check_band(y, rows, self.next, size.1)?;
        let mut band = Band::new(pixels, size, y, rows)?;
        let background = Some(self.background);
        self.draw_band(&mut band, background)
            .map_err(BandsError::Render)?;
        Ok(band.rows())
    }

    /// [`draw`](Self::draw) into a band of words, two pixels a word in a
    /// panel's wire order
    /// ([`PackedBand`]): the same
    /// pixels, written a word at a time; `words` holds at least
    /// `PackedBand::words_len(width, rows)`.
    pub fn draw_packed(
        &mut self,
        y: u16,
        rows: u16,
        words: &mut [u32],
    ) -> Result<u16, SceneBandsError<Infallible>>
    where
        C: Into<RawU16> + From<RawU16>,
    {
        let size = (self.store.width(), self.store.height());
        check_band(y, rows, self.next, size.1)?;
        let mut band = PackedBand::<C>::new(words, size, y, rows)?;
        let background = Some(self.background);
        self.draw_band(&mut band, background)
            .map_err(BandsError::Render)?;
        Ok(band.rows())
    }

    /// Composes row `y` as colour runs into `row` (see
    /// [`port::runs`](crate::port::runs)), through the same stages as
    /// [`draw`](Self::draw) draws a band of that row: the sweep's runs
    /// (the background between faces among them), then the labels'
    /// glyph rows. Rows between the last one drawn and `y` are skipped.
    /// The row decodes to the pixels `draw` writes for it. Returns what
    /// was drawn.
    pub fn draw_runs(
        &mut self,
        y: u16,
        row: &mut RowRuns<'_, C>,
    ) -> Result<Counts, RowsError<VisibleError<Infallible>>> {
        let size = (self.store.width(), self.store.height());
        check_band(y, 1, self.next, size.1)?;
        row.start(y, size, self.background);
        let background = Some(self.background);
        let counts = self.draw_band(row, background).map_err(RowsError::Render)?;
        if row.overflowed() {
            return Err(RowsError::Full {
                y,
                capacity: row.capacity(),
            });
        }
        Ok(counts)
    }

    /// Draws the band's rows (pixels or runs) over what is in it: the
    /// lowest layer with `background` (see
    /// [`Layer::draw`](crate::controller::frame::Layer::draw)).
    pub(crate) fn draw_band<B: Rows<Color = C>>(
        &mut self,
        band: &mut B,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        let (store, y) = (self.store, band.first());
        if y > self.next {
            self.sweep.skip(store, self.workspace, y - self.next)?;
        }
        let d = self
            .sweep
            .draw(store, self.workspace, band.count(), band, background)?;
        let rows = (band.first() as i32, band.end() as i32);
        let l = match self.labels.draw_rows(self.font, rows, band) {
            Ok(l) => l,
            Err(e) => match e {},
        };
        let f = &mut self.frame;
        f.visible = self.sweep.stats();
        f.decoded += d;
        f.labels.drawn += l.drawn;
        f.labels.off_frame = l.off_frame;
        f.labels.written += l.written;
        self.next = band.end();
        Ok(d + l.written)
    }
}

impl<'a, const DEPTH: usize, const N: usize> Scene<'a, DEPTH, N> {
    /// Starts a band-by-band pass over the scene in its own workspace:
    /// visible surfaces resolved with `resolve`, the background filled
    /// with `background`, labels in `font`. Checks first that the
    /// workspace holds every trapezoid overlapping a row.
    pub fn bands<'s, C: ListColor>(
        &'s mut self,
        resolve: Resolve,
        background: C,
        font: &'s MonoFont<'s>,
    ) -> Result<SceneBands<'s, 'a, 'a, C>, VisibleError<Infallible>> {
        let resolve = self.settle(resolve)?;
        let Scene {
            store,
            labels,
            workspace,
            checked,
            ..
        } = self;
        pass(
            store, labels, workspace, *checked, resolve, background, font,
        )
    }

    /// [`bands`](Self::bands) in `workspace` instead of the scene's own,
    /// reading the scene only: another pass over the same scene at the
    /// same time (another core's, taking other bands). After
    /// [`Scene::check`] (and until a segment changes) the workspace's
    /// capacity is only compared with the number it found.
    pub fn bands_in<'s, 'w, C: ListColor>(
        &'s self,
        workspace: &'s mut Workspace<'w>,
        resolve: Resolve,
        background: C,
        font: &'s MonoFont<'s>,
    ) -> Result<SceneBands<'s, 'a, 'w, C>, VisibleError<Infallible>> {
        pass(
            &self.store,
            &self.labels,
            workspace,
            self.checked,
            resolve,
            background,
            font,
        )
    }
}

impl<'a, const DEPTH: usize, const N: usize> Scene<'a, DEPTH, N> {
    /// The store and labels, read, and the workspace, for a pass kept
    /// outside the scene (the controller's bands).
    pub(crate) fn band_parts(
        &mut self,
    ) -> (&TrapezoidStore<'a>, &LabelStore<'a>, &mut Workspace<'a>) {
        (&self.store, &self.labels, &mut self.workspace)
    }
}

/// A pass over `store` and `labels` in `workspace`, with what
/// [`Scene::check`] found of them when known. [`Resolve::Auto`] is
/// settled here; it paints only where the store's depths are all worked
/// out (a pass that reads the scene cannot work them out).
fn pass<'s, 'a, 'w, C: ListColor>(
    store: &'s TrapezoidStore<'a>,
    labels: &'s LabelStore<'a>,
    workspace: &'s mut Workspace<'w>,
    checked: Option<Checked>,
    resolve: Resolve,
    background: C,
    font: &'s MonoFont<'s>,
) -> Result<SceneBands<'s, 'a, 'w, C>, VisibleError<Infallible>> {
    let checked = match checked {
        Some(c) => {
            if workspace.run_capacity() < store.width() as usize {
                return Err(VisibleError::Runs {
                    capacity: workspace.run_capacity(),
                });
            }
            if workspace.capacity() < c.most as usize {
                return Err(VisibleError::Active {
                    capacity: workspace.capacity(),
                });
            }
            c
        }
        None => workspace.check_rows(store)?,
    };
    let resolve = match checked.settle(resolve) {
        Resolve::Paint if resolve == Resolve::Auto && store.has_later_depths() => Resolve::Crossing,
        m => m,
    };
    let sweep = Sweep::new(workspace, resolve);
    Ok(SceneBands {
        store,
        labels,
        workspace,
        sweep,
        background,
        font,
        next: 0,
        frame: Frame::default(),
    })
}

/// Segments whose stale marks [`Scene::update_marking`] remembers; with
/// more segments, every row is marked.
const MARKED_SEGMENTS: usize = 256;

impl<'a, const DEPTH: usize, const N: usize> Scene<'a, DEPTH, N> {
    /// Marks the rows segment `s` shows on: those of its trapezoids, and
    /// those of its labels' cells in `font`.
    pub fn mark_segment_rows(&self, s: usize, font: &MonoFont<'_>, dirty: &mut DirtyRows<'_>) {
        for (_, t) in self.store.segment_trapezoids(s) {
            dirty.mark(t.top(), t.end());
        }
        let ch = font.character_size.height as i32;
        for (l, _) in self.labels.iter() {
            if l.segment() as usize == s {
                let (_, y) = l.anchor();
                dirty.mark(y - ch, y);
            }
        }
    }

    /// Runs `change` on the scene (an attribute of segment `s`:
    /// [`set_visible`](Self::set_visible),
    /// [`set_highlight`](Self::set_highlight), [`place`](Self::place))
    /// and marks in `dirty` the rows segment `s` showed on before it and
    /// shows on after it, so that [`draw_marked`](Self::draw_marked)
    /// ships every pixel the change made different.
    pub fn marking<R>(
        &mut self,
        s: usize,
        font: &MonoFont<'_>,
        dirty: &mut DirtyRows<'_>,
        change: impl FnOnce(&mut Self) -> R,
    ) -> R {
        self.mark_segment_rows(s, font, dirty);
        let r = change(self);
        self.mark_segment_rows(s, font, dirty);
        r
    }

    /// Adds to `sig[y]`, for every row `y`, a hash of what segment `s`
    /// puts on the row: its trapezoids (edges, rows, columns, their
    /// faces' depth and colour)
    /// and its labels' cells (anchor, colour, text) in `font`. Sums are
    /// order-free, so the same content hashes the same however it was
    /// built.
    fn add_signature(&self, s: usize, font: &MonoFont<'_>, sig: &mut [u64]) {
        let h = sig.len() as i32;
        for (_, t) in self.store.segment_trapezoids(s) {
            let mut k = Mix::new();
            let face = self.store.face(t.face()).map_or([0; 4], |f| {
                let d = f.depth();
                [d.z, d.zx, d.zy, f.color_bits() as i32]
            });
            for f in t.fields().into_iter().chain(face) {
                k.add(f as u32 as u64);
            }
            let k = k.finish();
            for y in t.top().max(0)..t.end().min(h) {
                sig[y as usize] = sig[y as usize].wrapping_add(k);
            }
        }
        let ch = font.character_size.height as i32;
        for (l, text) in self.labels.iter() {
            if l.segment() as usize != s {
                continue;
            }
            let (x, y) = l.anchor();
            let mut k = Mix::new();
            k.add(x as u32 as u64);
            k.add(y as u32 as u64);
            let c = l.color();
            k.add(((c.r() as u64) << 16) | ((c.g() as u64) << 8) | c.b() as u64);
            for b in text.bytes() {
                k.add(b as u64);
            }
            k.add(text.len() as u64);
            let k = k.finish();
            for y in (y - ch).max(0)..y.min(h) {
                sig[y as usize] = sig[y as usize].wrapping_add(k);
            }
        }
    }

    /// [`update`](Self::update), marking in `dirty` the rows where a
    /// rebuilt segment's content changed. With `scratch` of twice the
    /// frame's height, a row is marked when the hash of what the rebuilt
    /// segments put on it (see below) differs before and after, so a
    /// segment rebuilt the same costs no row; with less, every row a
    /// rebuilt segment showed on before or shows on after is marked, and
    /// the update says so ([`Update::coarse_marks`]).
    ///
    /// The hash of a row is the sum of 64-bit mixes of each trapezoid's
    /// and label's every field: two different contents of a row hash the
    /// same with a chance of about 2⁻⁶⁴. Changes the update does not see
    /// (the background) are the caller's to mark; those that mark every
    /// segment stale (the camera, the projection, the light, the clip)
    /// it sees. With more than 256 segments every row is marked.
    pub fn update_marking(
        &mut self,
        procedures: &mut [&mut dyn super::Procedure<DEPTH, N>],
        font: &MonoFont<'_>,
        dirty: &mut DirtyRows<'_>,
        scratch: &mut [u64],
    ) -> Result<Update, super::UpdateError> {
        let n = procedures.len();
        let h = self.store.height() as usize;
        let mut stale = [0u32; MARKED_SEGMENTS / 32];
        let sigs = scratch.get_mut(..2 * h);
        let exact = sigs.is_some();
        let (before, after) = match sigs {
            Some(s) => {
                s.fill(0);
                s.split_at_mut(h)
            }
            None => (&mut [][..], &mut [][..]),
        };
        for s in 0..n {
            if self.is_stale(s) {
                if exact {
                    self.add_signature(s, font, before);
                } else {
                    self.mark_segment_rows(s, font, dirty);
                }
                if s < MARKED_SEGMENTS {
                    stale[s / 32] |= 1 << (s % 32);
                } else {
                    dirty.mark_all();
                }
            }
        }
        let r = self.update(procedures);
        for s in 0..n.min(MARKED_SEGMENTS) {
            if stale[s / 32] & (1 << (s % 32)) != 0 {
                if exact {
                    self.add_signature(s, font, after);
                } else {
                    self.mark_segment_rows(s, font, dirty);
                }
            }
        }
        for (y, (a, b)) in before.iter().zip(after.iter()).enumerate() {
            if a != b {
                dirty.mark(y as i32, y as i32 + 1);
            }
        }
        r.map(|u| Update {
            coarse_marks: !exact,
            ..u
        })
    }
}

#[cfg(test)]
mod tests {
    use super::DirtyRows;

    #[test]
    fn dirty_rows_mark_cut_and_run() {
        let mut bits = [u32::MAX; 3];
        assert!(DirtyRows::new(&mut bits[..1], 40).is_none());
        let mut d = DirtyRows::new(&mut bits, 70).unwrap();
        assert_eq!(d.count(), 0, "starts empty");
        d.mark(-5, 2);
        d.mark(30, 34);
        d.mark(33, 40);
        d.mark(69, 90);
        let runs: [(u16, u16); 3] = [(0, 2), (30, 40), (69, 70)];
        assert!(d.runs().eq(runs));
        assert_eq!(d.count(), 13);
        assert!(d.is_marked(31) && !d.is_marked(40) && !d.is_marked(70));
        d.clear();
        assert_eq!(d.runs().count(), 0);
        d.mark_all();
        assert!(d.runs().eq([(0u16, 70u16)]));
    }
}
