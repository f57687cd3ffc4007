//! The span stores of the frame buffers and bands against a plain
//! per-pixel reference: every start and end parity, lengths 0 to 40 and
//! spans as wide as the frame, clipped at the frame's right side and
//! bottom (and at a band's rows), written through `fill_span`,
//! `fill_span_inside`, `fill_row_inside` and `fill_rect` of
//! `PackedFrameBuffer`, `PackedBand`, `FrameBuffer` and `Band`. The
//! reference is a `Vec<u16>` of the frame, one pixel set at a time; the
//! words past a packed frame (and the padding half of an odd one's last
//! word) must stay as they were.

use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::Rgb565;
use proptest::prelude::*;
use scanvert::port::band::Band;
use scanvert::port::packed_band::PackedBand;
use scanvert::port::{FrameBuffer, PackedFrameBuffer, Span, SpanTarget};

fn px(v: u16) -> Rgb565 {
    Rgb565::from(RawU16::new(v))
}

fn raw(c: Rgb565) -> u16 {
    RawU16::from(c).into_inner()
}

/// The pixel a frame starts with at index `i`: no two neighbours equal,
/// so a half-word written to the wrong pixel shows.
fn pattern(i: usize) -> u16 {
    (i as u16).wrapping_mul(0x9e37) ^ 0x5aa5
}

/// The guard value of the words past a packed frame.
const GUARD: u32 = 0xdead_beef;

/// How a span reaches the target.
#[derive(Clone, Copy, Debug)]
enum Write {
    /// `fill_span`, any span (clipped by the target).
    Checked,
    /// `fill_span_inside`, spans inside the target only.
    Inside,
    /// `fill_row_inside` from `row_start`, spans inside the target only.
    Row,
    /// `fill_rect` of the span's columns over `h` rows.
    Rect(u16),
}

/// The reference: a `w × h` frame, one `u16` a pixel.
struct Reference {
    w: u16,
    h: u16,
    px: Vec<u16>,
}

impl Reference {
    fn new(w: u16, h: u16) -> Self {
        let px = (0..w as usize * h as usize).map(pattern).collect();
        Reference { w, h, px }
    }

    /// Sets the pixels of `span` that are in the frame and in rows
    /// `rows`, one at a time.
    fn span(&mut self, s: Span, c: u16, rows: core::ops::Range<u16>) {
        for x in s.x0..s.x1 {
            if x < self.w && s.y < self.h && rows.contains(&s.y) {
                self.px[s.y as usize * self.w as usize + x as usize] = c;
            }
        }
    }

    fn write(&mut self, s: Span, how: Write, c: u16, rows: core::ops::Range<u16>) {
        match how {
            Write::Rect(h) => {
                for y in s.y..s.y.saturating_add(h) {
                    self.span(Span { y, ..s }, c, rows.clone());
                }
            }
            _ => self.span(s, c, rows),
        }
    }
}

/// Writes `s` into `t` as `how` says.
fn write<T: SpanTarget<Color = Rgb565>>(t: &mut T, s: Span, how: Write, c: Rgb565) {
    let _ = match how {
        Write::Checked => t.fill_span(s, c),
        Write::Inside => t.fill_span_inside(s, c),
        Write::Row => {
            let row = t.row_start(s.y);
            t.fill_row_inside(row, s.x0, s.x1, c)
        }
        Write::Rect(h) => t.fill_rect(s, h, c),
    };
}

/// Words holding `pixels` two a word (`wire`: each pixel's bytes
/// swapped, a band's order), then two guard words; an odd count's
/// padding half is the guard's.
fn words_of(pixels: &[u16], wire: bool) -> Vec<u32> {
    let mut words = vec![GUARD; pixels.len().div_ceil(2) + 2];
    for (i, &p) in pixels.iter().enumerate() {
        let p = if wire { p.swap_bytes() } else { p } as u32;
        let shift = 16 * (i % 2);
        words[i / 2] = (words[i / 2] & !(0xffff << shift)) | (p << shift);
    }
    words
}

/// Asserts the words past `n` pixels are the guard's.
fn guards_kept(words: &[u32], n: usize, what: &str) {
    if n % 2 == 1 {
        assert_eq!(words[n / 2] >> 16, GUARD >> 16, "padding half, {what}");
    }
    assert!(
        words[n.div_ceil(2)..].iter().all(|&w| w == GUARD),
        "words past the frame, {what}"
    );
}

/// Every span of `spans` through `how` into each target of a `w × h`
/// frame (the bands: rows `y0..y0 + rows`), against the reference.
fn check(w: u16, h: u16, (y0, rows): (u16, u16), spans: &[(Span, u16)], how: Write) {
    let what = format!("{w}x{h} band {y0}+{rows} {how:?} {spans:?}");
    let rows = rows.min(h - y0);
    let band_rows = y0..y0 + rows;

    let mut reference = Reference::new(w, h);
    for &(s, c) in spans {
        reference.write(s, how, c, 0..h);
    }
    let mut band_reference = Reference::new(w, h);
    for &(s, c) in spans {
        band_reference.write(s, how, c, band_rows.clone());
    }
    let band_px = &band_reference.px[y0 as usize * w as usize..][..rows as usize * w as usize];

    // The packed frame.
    let n = w as usize * h as usize;
    let mut words = words_of(&reference_start(w, h), false);
    {
        let mut fb = PackedFrameBuffer::<Rgb565>::new(&mut words, w, h).unwrap();
        for &(s, c) in spans {
            write(&mut fb, s, how, px(c));
        }
        let got: Vec<u16> = fb.pixels().map(raw).collect();
        assert_eq!(got, reference.px, "PackedFrameBuffer, {what}");
    }
    guards_kept(&words, n, &format!("PackedFrameBuffer, {what}"));

    // The plain frame.
    let mut pixels: Vec<Rgb565> = reference_start(w, h).into_iter().map(px).collect();
    {
        let mut fb = FrameBuffer::new(&mut pixels, w, h).unwrap();
        for &(s, c) in spans {
            write(&mut fb, s, how, px(c));
        }
    }
    let got: Vec<u16> = pixels.iter().copied().map(raw).collect();
    assert_eq!(got, reference.px, "FrameBuffer, {what}");

    // Bands take every span, only their rows' pixels change; the spans
    // written inside (`fill_span_inside`, `fill_row_inside` from the
    // band's `row_start`) are the band's rows' only.
    let start: Vec<u16> =
        reference_start(w, h)[y0 as usize * w as usize..][..rows as usize * w as usize].to_vec();
    let bn = start.len();
    let mut bwords = words_of(&start, true);
    {
        let mut band = PackedBand::<Rgb565>::new(&mut bwords, (w, h), y0, rows).unwrap();
        for &(s, c) in spans {
            if matches!(how, Write::Inside | Write::Row) && !band_rows.contains(&s.y) {
                continue;
            }
            write(&mut band, s, how, px(c));
        }
        let got: Vec<u16> = band.pixels().map(raw).collect();
        assert_eq!(got, band_px, "PackedBand, {what}");
    }
    guards_kept(&bwords, bn, &format!("PackedBand, {what}"));

    let mut bpixels: Vec<Rgb565> = start.iter().copied().map(px).collect();
    {
        let mut band = Band::new(&mut bpixels, (w, h), y0, rows).unwrap();
        for &(s, c) in spans {
            if matches!(how, Write::Inside | Write::Row) && !band_rows.contains(&s.y) {
                continue;
            }
            write(&mut band, s, how, px(c));
        }
    }
    let got: Vec<u16> = bpixels.iter().copied().map(raw).collect();
    assert_eq!(got, band_px, "Band, {what}");
}

/// The frame's first pixels.
fn reference_start(w: u16, h: u16) -> Vec<u16> {
    Reference::new(w, h).px
}

/// Every start of the first 44 columns and every length 0 to 40, on an
/// odd and an even width, on a frame's first and an odd row (which in an
/// odd-width frame starts in the middle of a word), each way of writing.
#[test]
fn every_parity_and_short_length() {
    for w in [45u16, 46] {
        for y in [0u16, 1] {
            for x0 in 0..44u16 {
                for len in 0..=40u16 {
                    let x1 = x0 + len;
                    let s = Span { y, x0, x1 };
                    let c = 0x1234 ^ x0 ^ (len << 6);
                    check(w, 3, (0, 3), &[(s, c)], Write::Checked);
                    check(w, 3, (1, 1), &[(s, c)], Write::Checked);
                    if len > 0 && x1 <= w {
                        check(w, 3, (0, 3), &[(s, c)], Write::Inside);
                        check(w, 3, (0, 3), &[(s, c)], Write::Row);
                    }
                }
            }
        }
    }
}

/// A span: short or wide, anywhere in or past a frame of `w × h`.
fn span(w: u16, h: u16) -> impl Strategy<Value = (Span, u16)> {
    (
        0..=h,
        0..w + 4,
        prop_oneof![0u16..=40, 0..w + 8],
        any::<u16>(),
    )
        .prop_map(|(y, x0, len, c)| {
            (
                Span {
                    y,
                    x0,
                    x1: x0.saturating_add(len),
                },
                c,
            )
        })
}

/// A span inside a frame of `w × h`.
fn inside(w: u16, h: u16) -> impl Strategy<Value = (Span, u16)> {
    (0..h, 0..w, prop_oneof![1u16..=40, 1..=w], any::<u16>()).prop_map(move |(y, x0, len, c)| {
        (
            Span {
                y,
                x0,
                x1: (x0 + len).min(w),
            },
            c,
        )
    })
}

/// A frame (odd and even widths up to 600 pixels, so spans of a few
/// hundred words) with a band of its rows.
fn frame() -> impl Strategy<Value = (u16, u16, u16, u16)> {
    (1u16..=600, 1u16..=5).prop_flat_map(|(w, h)| (Just(w), Just(h), 0..h, 1..=h))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Checked spans and rectangles, anywhere: clipped at the frame's
    /// right side and bottom and at the band's rows.
    #[test]
    fn checked_spans_and_rectangles_write_what_the_reference_writes(
        ((w, h, y0, rows), spans, rect) in frame().prop_flat_map(|(w, h, y0, rows)| {
            (
                Just((w, h, y0, rows)),
                prop::collection::vec(span(w, h), 1..6),
                0u16..=h + 1,
            )
        })
    ) {
        check(w, h, (y0, rows), &spans, Write::Checked);
        check(w, h, (y0, rows), &spans, Write::Rect(rect));
    }

    /// Spans inside the frame, through the unchecked stores.
    #[test]
    fn inside_spans_write_what_the_reference_writes(
        ((w, h, y0, rows), spans) in frame().prop_flat_map(|(w, h, y0, rows)| {
            (Just((w, h, y0, rows)), prop::collection::vec(inside(w, h), 1..6))
        })
    ) {
        check(w, h, (y0, rows), &spans, Write::Inside);
        check(w, h, (y0, rows), &spans, Write::Row);
    }
}
