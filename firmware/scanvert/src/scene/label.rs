//! Labels: lines of text anchored at projected 3D points, drawn after the
//! 3D layer and never hidden by it.
//!
//! A label is placed when its segment is built: its 3D point goes through
//! the same transform and projection as the segment's faces
//! ([`Pipeline::project_point`](crate::geometry::Pipeline::project_point)),
//! and the store keeps the screen position, the colour and the text.
//! [`LabelStore::draw`] then writes every label into a [`SpanTarget`] with
//! an `embedded-graphics` mono font at its fixed scale, as horizontal spans.
//! The glyphs are read from the font's image, the pixels
//! `embedded-graphics` draws for the text (its `Text` with a
//! `MonoTextStyle` in the label's colour: no background, underline or
//! strikethrough; the tests compare the two for every font of its ASCII
//! set), and only the rows asked are read: a band
//! ([`LabelStore::draw_rows`]) costs the glyphs' rows on it, not the
//! whole label.
//!
//! # Placement
//!
//! The anchor is the lower-left corner of the first character's cell: with
//! the anchor at `(x, y)` (rounded to whole pixels, halves up), the first
//! character covers columns `x .. x + w` and rows `y − h .. y`, where
//! `w × h` is the font's character size. Characters follow at the font's
//! pitch (width plus spacing). A label whose point lies before the near
//! plane (at or behind the eye) is not placed; anything else is drawn as
//! far as it lies on the frame, so a label that runs off an edge is cut
//! there and one wholly off the frame costs one bounding-box test.
//!
//! # Memory
//!
//! All of it is the caller's: a slice of [`Label`] slots (20 bytes each on
//! 32-bit targets) and a byte slice for the text of all labels together.
//! Emptying a segment removes its labels and closes the gap in both, so
//! the other segments' labels keep their order and the memory needed is
//! that of the labels present, never of a worst case per label.

use crate::color::ListColor;
use crate::geometry::Anchor;
use crate::port::{Counts, Span, SpanTarget};
use core::fmt;
use embedded_graphics::image::GetPixel;
use embedded_graphics::mono_font::MonoFont;
use embedded_graphics::pixelcolor::BinaryColor::On;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::Rgb888;

/// The font labels are drawn in unless another is given: 6 × 10 pixels,
/// ASCII.
pub const DEFAULT_FONT: &MonoFont<'static> = &embedded_graphics::mono_font::ascii::FONT_6X10;

/// The longest label text, in bytes.
pub const MAX_TEXT: usize = 255;

/// Anchors farther than this many pixels from the frame's origin are not
/// placed: no text of at most [`MAX_TEXT`] characters of any mono font
/// could reach the frame from there, and every sum made while drawing
/// stays far inside `i32`.
pub const ANCHOR_LIMIT: i32 = 1 << 24;

/// One placed label.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Label {
    x: i32,
    y: i32,
    color: Rgb888,
    start: u32,
    len: u8,
    /// Its segment is hidden: kept, not drawn.
    hidden: bool,
    segment: u16,
}

impl Label {
    /// An unused slot.
    pub const EMPTY: Label = Label {
        x: 0,
        y: 0,
        color: Rgb888::new(0, 0, 0),
        start: 0,
        len: 0,
        hidden: false,
        segment: 0,
    };

    /// The anchor, whole pixels: the lower-left corner of the first
    /// character's cell.
    pub fn anchor(&self) -> (i32, i32) {
        (self.x, self.y)
    }

    /// The colour.
    pub fn color(&self) -> Rgb888 {
        self.color
    }

    /// The segment that owns it.
    pub fn segment(&self) -> u16 {
        self.segment
    }
}

/// What ran out, or what was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum LabelError {
    /// Every label slot is taken.
    Labels {
        /// Slots the store holds.
        capacity: usize,
    },
    /// The text space is full.
    Text {
        /// Bytes the store holds.
        capacity: usize,
    },
    /// The text is empty, longer than [`MAX_TEXT`], or holds a byte
    /// outside printable ASCII (`0x20..=0x7e`).
    Invalid,
}

impl fmt::Display for LabelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LabelError::Labels { capacity } => {
                write!(f, "more than the {capacity} labels the store holds")
            }
            LabelError::Text { capacity } => {
                write!(
                    f,
                    "more than the {capacity} bytes of label text the store holds"
                )
            }
            LabelError::Invalid => write!(
                f,
                "label text must be 1..={MAX_TEXT} bytes of printable ASCII"
            ),
        }
    }
}

impl core::error::Error for LabelError {}

/// Checks a label's text: 1..=[`MAX_TEXT`] bytes of printable ASCII.
#[doc(hidden)]
pub fn check_text(text: &str) -> Result<(), LabelError> {
    let b = text.as_bytes();
    if b.is_empty() || b.len() > MAX_TEXT || !b.iter().all(|c| (0x20..=0x7e).contains(c)) {
        return Err(LabelError::Invalid);
    }
    Ok(())
}

/// The anchor of a projected point in whole pixels: its 1/16-pixel
/// position rounded to the nearest pixel corner, halves up.
#[doc(hidden)]
pub fn to_pixels(a: Anchor) -> (i32, i32) {
    // i64: the anchor is saturated to i32, and + 8 must not wrap.
    let px = |u: i32| ((u as i64 + 8) >> 4) as i32;
    (px(a.x), px(a.y))
}

/// The labels of a scene, in caller-owned memory (see the
/// [module](self) docs).
#[derive(Debug)]
pub struct LabelStore<'a> {
    slots: &'a mut [Label],
    text: &'a mut [u8],
    len: usize,
    text_len: usize,
    /// The most labels, and bytes of text, held at once.
    most: (usize, usize),
}

impl<'a> LabelStore<'a> {
    /// An empty store of `slots.len()` labels holding at most
    /// `text.len()` bytes of text in all.
    #[doc(hidden)]
    pub fn new(slots: &'a mut [Label], text: &'a mut [u8]) -> Self {
        LabelStore {
            slots,
            text,
            len: 0,
            text_len: 0,
            most: (0, 0),
        }
    }

    /// Labels placed.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` with no label placed.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Bytes of text held.
    pub fn text_len(&self) -> usize {
        self.text_len
    }

    /// The most labels, and bytes of their text, held at once since the
    /// store was made: slots and text of these sizes would have held
    /// every label placed.
    pub fn peak(&self) -> (usize, usize) {
        self.most
    }

    /// The placed labels with their text, by segment, and in the order
    /// placed within a segment.
    pub fn iter(&self) -> impl Iterator<Item = (&Label, &str)> + '_ {
        self.slots[..self.len].iter().map(|l| {
            let bytes = &self.text[l.start as usize..l.start as usize + l.len as usize];
            // Checked to be ASCII when placed.
            (l, core::str::from_utf8(bytes).unwrap_or(""))
        })
    }

    /// Places a label of segment `segment` with its anchor at `(x, y)`
    /// whole pixels. An anchor outside ±[`ANCHOR_LIMIT`] is accepted and
    /// dropped (it can never show); `Ok(false)` says so.
    #[doc(hidden)]
    pub fn add(
        &mut self,
        segment: u16,
        (x, y): (i32, i32),
        color: Rgb888,
        text: &str,
    ) -> Result<bool, LabelError> {
        check_text(text)?;
        let bytes = text.as_bytes();
        if x.unsigned_abs() > ANCHOR_LIMIT as u32 || y.unsigned_abs() > ANCHOR_LIMIT as u32 {
            return Ok(false);
        }
        if self.len == self.slots.len() {
            return Err(LabelError::Labels {
                capacity: self.slots.len(),
            });
        }
        let end = self.text_len + bytes.len();
        if end > self.text.len() {
            return Err(LabelError::Text {
                capacity: self.text.len(),
            });
        }
        // Kept in segment order, so that overlapping labels are drawn in
        // the same order however the segments were rebuilt: after the
        // last label of a segment up to `segment`. The slots are sorted by
        // segment, so the place is a binary search, and a label of the
        // last segment (how a segment is built) is appended at once.
        let placed = &self.slots[..self.len];
        let at = match placed.last() {
            Some(l) if l.segment > segment => placed.partition_point(|l| l.segment <= segment),
            _ => self.len,
        };
        let n = bytes.len();
        let start = if at < self.len {
            let start = self.slots[at].start as usize;
            self.text.copy_within(start..self.text_len, start + n);
            self.slots.copy_within(at..self.len, at + 1);
            for l in &mut self.slots[at + 1..=self.len] {
                l.start += n as u32;
            }
            start
        } else {
            self.text_len
        };
        self.text[start..start + n].copy_from_slice(bytes);
        self.slots[at] = Label {
            x,
            y,
            color,
            // The text slice of a 32-bit target is below 2³² bytes.
            start: start as u32,
            len: n as u8,
            hidden: false,
            segment,
        };
        self.len += 1;
        self.text_len = end;
        self.most = (self.most.0.max(self.len), self.most.1.max(end));
        Ok(true)
    }

    /// Removes the labels of segment `segment`, closing the gaps; the
    /// others keep their order. Returns how many were removed.
    #[doc(hidden)]
    pub fn clear_segment(&mut self, segment: u16) -> usize {
        let (mut keep, mut text_at) = (0, 0);
        for i in 0..self.len {
            let l = self.slots[i];
            if l.segment == segment {
                continue;
            }
            let (s, n) = (l.start as usize, l.len as usize);
            self.text.copy_within(s..s + n, text_at);
            self.slots[keep] = Label {
                start: text_at as u32,
                ..l
            };
            keep += 1;
            text_at += n;
        }
        let removed = self.len - keep;
        self.len = keep;
        self.text_len = text_at;
        removed
    }

    /// Keeps the labels of segment `segment` but does not draw them
    /// (`true`), or draws them again (`false`).
    pub fn set_hidden(&mut self, segment: u16, hidden: bool) {
        for l in &mut self.slots[..self.len] {
            if l.segment == segment {
                l.hidden = hidden;
            }
        }
    }

    /// Removes every label.
    #[doc(hidden)]
    pub fn clear(&mut self) {
        self.len = 0;
        self.text_len = 0;
    }

    /// Draws every label into `target` with `font`, clipped to the
    /// target's frame, and returns the spans written.
    #[doc(hidden)]
    pub fn draw<T>(&self, font: &MonoFont<'_>, target: &mut T) -> Result<LabelCounts, T::Error>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        // Every row: a label on the frame reaches one of them.
        self.draw_rows(font, (0, i32::MAX), target)
    }
}

/// What [`LabelStore::draw`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LabelCounts {
    /// Labels drawn (at least partly on the frame). Drawn a band at a
    /// time ([`LabelStore::draw_rows`]), a label counts in the band that
    /// holds its first row on the frame only.
    pub drawn: u32,
    /// Labels wholly off the frame, skipped.
    pub off_frame: u32,
    /// Spans and pixels written.
    pub written: Counts,
}

/// Pixels that follow each other along a row, gathered into spans for a
/// [`SpanTarget`].
struct Spans<'t, T: SpanTarget + ?Sized> {
    target: &'t mut T,
    /// The open run: row, first column, one past the last.
    run: Option<(u16, u16, u16)>,
    color: T::Color,
    written: Counts,
    error: Option<T::Error>,
}

impl<T: SpanTarget + ?Sized> Spans<'_, T> {
    fn flush(&mut self) {
        if let Some((y, x0, x1)) = self.run.take() {
            if self.error.is_none() {
                match self.target.fill_span(Span { y, x0, x1 }, self.color) {
                    Ok(()) => {
                        self.written.span((x1 - x0) as u32);
                    }
                    Err(e) => self.error = Some(e),
                }
            }
        }
    }

    /// Pixel `(x, y)`, on the frame.
    #[inline(always)]
    fn pixel(&mut self, x: u16, y: u16) {
        match &mut self.run {
            Some((ry, _, x1)) if *ry == y && *x1 == x => *x1 += 1,
            _ => {
                self.flush();
                self.run = Some((y, x, x + 1));
            }
        }
    }
}

/// Where a glyph lies in a mono font's image, as `embedded-graphics`
/// places it (`MonoFont::glyph`): the top-left corner of its cell, or
/// `None` when the font draws nothing for it (a cell of no width or
/// height, an image narrower than a cell, a cell not wholly inside the
/// image).
fn glyph_cell(font: &MonoFont<'_>, c: char) -> Option<(i32, i32)> {
    let (cw, ch) = (font.character_size.width, font.character_size.height);
    let Size {
        width: iw,
        height: ih,
    } = font.image.size();
    if cw == 0 || ch == 0 || iw < cw {
        return None;
    }
    let per_row = (iw / cw) as u64;
    let index = font.glyph_mapping.index(c) as u64;
    let (row, col) = (index / per_row, index % per_row);
    let (gx, gy) = (col * cw as u64, row * ch as u64);
    if gy + ch as u64 > ih as u64 {
        return None;
    }
    Some((gx as i32, gy as i32))
}

impl LabelStore<'_> {
    /// Draws the labels that reach rows `rows.0..rows.1` as
    /// [`draw`](Self::draw) does, for a band of those rows, and only their
    /// pixels on those rows: the others cost one test each. Labels wholly
    /// off the frame count as `off_frame`; those on it that miss the rows
    /// are not counted.
    #[inline]
    #[doc(hidden)]
    pub fn draw_rows<T>(
        &self,
        font: &MonoFont<'_>,
        rows: (i32, i32),
        target: &mut T,
    ) -> Result<LabelCounts, T::Error>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        if self.is_empty() {
            return Ok(LabelCounts::default());
        }
        self.draw_some_rows(font, rows, target)
    }

    /// [`draw_rows`](Self::draw_rows) with labels. Not inlined, so that the
    /// 2D band path in `ListBands::draw` compiles as it does without labels:
    /// inlined there, it makes that path cost more instructions on the
    /// Cortex-M4.
    #[inline(never)]
    fn draw_some_rows<T>(
        &self,
        font: &MonoFont<'_>,
        rows: (i32, i32),
        target: &mut T,
    ) -> Result<LabelCounts, T::Error>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        let mut counts = LabelCounts::default();
        let (w, h) = target.size();
        let pitch = (font.character_size.width + font.character_spacing) as i32;
        let (cw, ch) = (
            font.character_size.width as i32,
            font.character_size.height as i32,
        );
        let (y0, y1) = (rows.0.max(0), rows.1.min(h as i32));
        for l in self.slots[..self.len].iter().filter(|l| !l.hidden) {
            // |x|, |y| ≤ 2²⁴, text ≤ 255 characters of a font below 2¹⁶
            // pixels: every sum below is far inside i32.
            let right = l.x + (l.len as i32 - 1) * pitch + cw;
            let top = l.y - ch;
            if right <= 0 || l.x >= w as i32 || l.y <= 0 || top >= h as i32 {
                counts.off_frame += 1;
                continue;
            }
            if l.y <= y0 || top >= y1 {
                continue;
            }
            let mut adapter = Spans {
                target: &mut *target,
                run: None,
                color: T::Color::from_rgb888(l.color),
                written: Counts::default(),
                error: None,
            };
            // The glyphs' rows on the band: rows `top + r0 .. top + r1`.
            let (r0, r1) = ((y0 - top).max(0), (y1 - top).min(ch));
            let mut x = l.x;
            // Printable ASCII (checked when placed): a byte a character.
            let text = &self.text[l.start as usize..l.start as usize + l.len as usize];
            for &b in text {
                let c = b as char;
                if x >= w as i32 {
                    break;
                }
                if x + cw > 0 {
                    if let Some((gx, gy)) = glyph_cell(font, c) {
                        // Columns of the cell on the frame.
                        let (c0, c1) = ((-x).max(0), (w as i32 - x).min(cw));
                        for r in r0..r1 {
                            let y = (top + r) as u16;
                            for i in c0..c1 {
                                if font.image.pixel(Point::new(gx + i, gy + r)) == Some(On) {
                                    adapter.pixel((x + i) as u16, y);
                                }
                            }
                        }
                    }
                }
                x += pitch;
            }
            adapter.flush();
            counts.written += adapter.written;
            if let Some(e) = adapter.error {
                return Err(e);
            }
            // Counted by the rows that hold its first on the frame, so
            // that a label across several bands counts once.
            if top.max(0) >= y0 {
                counts.drawn += 1;
            }
        }
        Ok(counts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::port::framebuffer::FrameBuffer;
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

    fn store<'a>(slots: &'a mut [Label], text: &'a mut [u8]) -> LabelStore<'a> {
        LabelStore::new(slots, text)
    }

    #[test]
    fn clear_segment_closes_gaps() {
        let (mut slots, mut text) = ([Label::EMPTY; 4], [0u8; 16]);
        let mut s = store(&mut slots, &mut text);
        s.add(0, (1, 1), Rgb888::RED, "ab").unwrap();
        s.add(1, (2, 2), Rgb888::RED, "cde").unwrap();
        s.add(0, (3, 3), Rgb888::RED, "fg").unwrap();
        s.add(2, (4, 4), Rgb888::RED, "h").unwrap();
        assert_eq!(s.clear_segment(0), 2);
        {
            let left: heapless::Vec<(&str, (i32, i32)), 4> =
                s.iter().map(|(l, t)| (t, l.anchor())).collect();
            assert_eq!(&left[..], &[("cde", (2, 2)), ("h", (4, 4))]);
        }
        assert_eq!(s.text_len(), 4);
        // The freed space is usable again.
        s.add(3, (5, 5), Rgb888::RED, "ijklmnopqrst").unwrap();
        assert_eq!(
            s.add(3, (5, 5), Rgb888::RED, "u"),
            Err(LabelError::Text { capacity: 16 })
        );
    }

    #[test]
    fn kept_in_segment_order() {
        let (mut slots, mut text) = ([Label::EMPTY; 5], [0u8; 32]);
        let mut s = store(&mut slots, &mut text);
        for (seg, t) in [(2, "c1"), (0, "a1"), (1, "b1"), (0, "a2"), (2, "c2")] {
            s.add(seg, (0, 0), Rgb888::RED, t).unwrap();
        }
        let order: heapless::Vec<&str, 5> = s.iter().map(|(_, t)| t).collect();
        assert_eq!(&order[..], &["a1", "a2", "b1", "c1", "c2"]);
    }

    #[test]
    fn any_order_of_adds_and_removals_keeps_segment_order() {
        // A model: the labels, stably sorted by segment.
        let (mut slots, mut text) = ([Label::EMPTY; 64], [0u8; 256]);
        let mut s = store(&mut slots, &mut text);
        let mut model: heapless::Vec<(u16, u8), 64> = heapless::Vec::new();
        let mut seed = 12345u32;
        for step in 0..2000u32 {
            seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12345);
            let segment = ((seed >> 16) % 5) as u16;
            if (seed >> 8).is_multiple_of(7) {
                s.clear_segment(segment);
                model.retain(|&(g, _)| g != segment);
            } else if model.len() < 64 {
                let c = b'a' + (step % 26) as u8;
                let t = [c; 3];
                let len = 1 + (step % 3) as usize;
                let t = core::str::from_utf8(&t[..len]).unwrap();
                if s.add(segment, (0, 0), Rgb888::RED, t).is_ok() {
                    let at = model.partition_point(|&(g, _)| g <= segment);
                    model.insert(at, (segment, c)).unwrap();
                }
            }
            let got = s.iter().map(|(l, t)| (l.segment(), t.as_bytes()[0]));
            assert!(got.eq(model.iter().copied()), "step {step}");
            let text: usize = s.iter().map(|(_, t)| t.len()).sum();
            assert_eq!(text, s.text_len());
        }
    }

    #[test]
    fn refuses_and_drops() {
        let (mut slots, mut text) = ([Label::EMPTY; 1], [0u8; 300]);
        let mut s = store(&mut slots, &mut text);
        assert_eq!(s.add(0, (0, 0), Rgb888::RED, ""), Err(LabelError::Invalid));
        assert_eq!(
            s.add(0, (0, 0), Rgb888::RED, "a\tb"),
            Err(LabelError::Invalid)
        );
        assert_eq!(s.add(0, (0, 0), Rgb888::RED, "é"), Err(LabelError::Invalid));
        assert_eq!(s.add(0, (i32::MIN, 0), Rgb888::RED, "far"), Ok(false));
        assert_eq!(s.add(0, (0, i32::MAX), Rgb888::RED, "far"), Ok(false));
        assert_eq!(s.add(0, (0, 0), Rgb888::RED, "x"), Ok(true));
        assert_eq!(
            s.add(0, (0, 0), Rgb888::RED, "y"),
            Err(LabelError::Labels { capacity: 1 })
        );
    }

    #[test]
    fn lower_left_corner_at_the_anchor() {
        let (mut slots, mut text) = ([Label::EMPTY; 2], [0u8; 8]);
        let mut s = store(&mut slots, &mut text);
        // 'I' of FONT_6X10 has ink in its middle columns.
        s.add(0, (10, 20), Rgb888::WHITE, "II").unwrap();
        let mut px = [Rgb565::BLACK; 40 * 30];
        let mut fb = FrameBuffer::new(&mut px, 40, 30).unwrap();
        let c = s.draw(DEFAULT_FONT, &mut fb).unwrap();
        assert_eq!((c.drawn, c.off_frame), (1, 0));
        let (mut x0, mut x1, mut y0, mut y1) = (99, 0, 99, 0);
        for y in 0..30u16 {
            for x in 0..40u16 {
                if fb.pixel(x, y) == Some(Rgb565::WHITE) {
                    (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
                }
            }
        }
        // Ink lies in the cells: columns 10..22, rows 10..20.
        assert!(
            x0 >= 10 && x1 < 22 && y0 >= 10 && y1 < 20,
            "{x0} {x1} {y0} {y1}"
        );
        assert!(c.written.pixels > 0 && c.written.spans < c.written.pixels);
    }

    /// A frame that `embedded-graphics` draws into, the reference.
    struct Grid([Rgb565; 40 * 30]);

    impl embedded_graphics_core::geometry::OriginDimensions for Grid {
        fn size(&self) -> Size {
            Size::new(40, 30)
        }
    }

    impl embedded_graphics_core::draw_target::DrawTarget for Grid {
        type Color = Rgb565;
        type Error = core::convert::Infallible;
        fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
        where
            I: IntoIterator<Item = embedded_graphics_core::Pixel<Rgb565>>,
        {
            for embedded_graphics_core::Pixel(p, c) in pixels {
                if (0..40).contains(&p.x) && (0..30).contains(&p.y) {
                    self.0[p.y as usize * 40 + p.x as usize] = c;
                }
            }
            Ok(())
        }
    }

    /// The glyphs read from the font's image are the pixels
    /// `embedded-graphics` draws for the same text (`Text` with a
    /// `MonoTextStyle`, baseline at the bottom), for every font of its
    /// ASCII set, every printable character, labels cut by every edge of
    /// the frame, and cut again to bands of 1, 3, 7 and 16 rows (each band
    /// writing only its rows); and for a font whose cells run past its
    /// image, which draws nothing for those.
    #[test]
    fn glyphs_are_those_embedded_graphics_draws() {
        use embedded_graphics::mono_font::{ascii, mapping::StrGlyphMapping};
        use embedded_graphics::mono_font::{DecorationDimensions, MonoTextStyle};
        use embedded_graphics::text::{Baseline, Text};
        use embedded_graphics::Drawable;
        // 2 cells of 3 × 2 a row, one row: 'c' and the replacement's
        // cells lie below the image.
        const SMALL_DATA: [u8; 2] = [0b1010_1100, 0b0110_1000];
        let small_map = StrGlyphMapping::new("abc", 5);
        let small = MonoFont {
            image: embedded_graphics::image::ImageRaw::new(&SMALL_DATA, 8),
            glyph_mapping: &small_map,
            character_size: Size::new(3, 2),
            character_spacing: 0,
            baseline: 1,
            strikethrough: DecorationDimensions::new(0, 1),
            underline: DecorationDimensions::new(1, 1),
        };
        let fonts = [
            &ascii::FONT_4X6,
            &ascii::FONT_5X7,
            &ascii::FONT_5X8,
            &ascii::FONT_6X9,
            &ascii::FONT_6X10,
            &ascii::FONT_6X12,
            &ascii::FONT_6X13,
            &ascii::FONT_6X13_BOLD,
            &ascii::FONT_6X13_ITALIC,
            &ascii::FONT_7X13,
            &ascii::FONT_7X14,
            &ascii::FONT_8X13,
            &ascii::FONT_9X15,
            &ascii::FONT_9X18,
            &ascii::FONT_10X20,
            &small,
        ];
        let printable: heapless::String<95> = (0x20u8..0x7f).map(|b| b as char).collect();
        let texts = [
            "abcab",
            &printable[..32],
            &printable[32..64],
            &printable[64..],
        ];
        let anchors = [
            (0, 12),
            (-7, 9),
            (3, 3),
            (30, 31),
            (25, 40),
            (-100, 15),
            (12, 29),
            (-5, 20),
            (-3, 22),
            (-9, 26),
            (-1, 17),
            (37, 18),
            (39, 8),
        ];
        for font in fonts {
            for text in texts {
                for at in anchors {
                    let color = Rgb888::new(200, 100, 50);
                    let mut want = Grid([Rgb565::BLACK; 40 * 30]);
                    let style = MonoTextStyle::new(font, Rgb565::from_rgb888(color));
                    let p = Point::new(at.0, at.1 - 1);
                    let _ = Text::with_baseline(text, p, style, Baseline::Bottom).draw(&mut want);
                    let (mut slots, mut bytes) = ([Label::EMPTY; 1], [0u8; 100]);
                    let mut s = store(&mut slots, &mut bytes);
                    s.add(0, at, color, text).unwrap();
                    let mut px = [Rgb565::BLACK; 40 * 30];
                    let mut fb = FrameBuffer::new(&mut px, 40, 30).unwrap();
                    s.draw(font, &mut fb).unwrap();
                    assert!(px == want.0, "{text:?} at {at:?}");
                    for rows in [1, 3, 7, 16] {
                        for y0 in (0..30).step_by(rows) {
                            let mut px = [Rgb565::BLACK; 40 * 30];
                            let mut fb = FrameBuffer::new(&mut px, 40, 30).unwrap();
                            let y1 = y0 + rows as i32;
                            s.draw_rows(font, (y0, y1), &mut fb).unwrap();
                            for (i, (&got, &w)) in px.iter().zip(&want.0).enumerate() {
                                let y = (i / 40) as i32;
                                let w = if (y0..y1).contains(&y) {
                                    w
                                } else {
                                    Rgb565::BLACK
                                };
                                assert_eq!(
                                    got, w,
                                    "{text:?} at {at:?}, rows {y0}..{y1}, pixel {i}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn off_frame_and_cut_at_edges() {
        let (mut slots, mut text) = ([Label::EMPTY; 6], [0u8; 64]);
        let mut s = store(&mut slots, &mut text);
        for at in [(-100, 5), (5, -1), (50, 5), (5, 500)] {
            s.add(0, at, Rgb888::WHITE, "MMMM").unwrap();
        }
        // Partly off the left and bottom edges.
        s.add(0, (-9, 12), Rgb888::WHITE, "MMMM").unwrap();
        s.add(0, (30, 25), Rgb888::WHITE, "MMMM").unwrap();
        let mut px = [Rgb565::BLACK; 40 * 20];
        let mut fb = FrameBuffer::new(&mut px, 40, 20).unwrap();
        let c = s.draw(DEFAULT_FONT, &mut fb).unwrap();
        assert_eq!((c.drawn, c.off_frame), (2, 4));
        assert!(c.written.pixels > 0);
    }
}
