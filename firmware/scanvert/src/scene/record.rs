//! Segment records: what a segment's procedure described, kept so that
//! the segment can be placed anew ([`Scene::place`](super::Scene::place))
//! without running its procedure again.
//!
//! A record is the procedure's calls as display-list commands in the
//! binary form (`push`, `pop`, `translate`, `rotate`, `scale`, `color`,
//! `face`, `label`), in the caller's byte buffer
//! ([`Scene::keep_records`](super::Scene::keep_records)). Placing a
//! segment replays them through [`list`](super::list)'s interpreter under
//! the camera and the segment's [`Placement`]: the very transforms, in the
//! same order, so the segment's pixels are exactly those its procedure
//! would give with the placement's transforms at its start. Every vertex
//! is transformed again and every face cut again; the procedure is not
//! run.
//!
//! # Memory
//!
//! One buffer for all segments: each recorded segment is a chunk of
//! [`HEADER`] bytes (its index, whether the record is complete, its
//! length, its placement) and its commands, 13 bytes a transform, 4 a
//! colour, 3 + 12·n a face of n points, 14 + len a label. A segment being
//! rebuilt moves to the end of the buffer (the others close up), so the
//! buffer needs the sum of the segments' chunks:
//! [`Scene::records_needed`](super::Scene::records_needed) is the most
//! the scene has held, to be planned like [`Scene::needed`](super::Scene::needed).
//!
//! A segment whose record did not fit, or whose procedure did something a
//! record does not hold (a mesh's `v`/`f` commands through
//! [`Builder::command_in`](super::Builder::command_in), a camera or
//! projection command, a change of the transform stack through
//! [`Builder::stack_mut`](super::Builder::stack_mut)), is *incomplete*:
//! placing it marks it stale instead, and the next update runs its
//! procedure (counted in [`Update::regenerated`](super::Update)).
//! [`Builder::mesh`](super::Builder::mesh) is recorded as one `face` a
//! face of the mesh, which draws the same pixels.

use crate::display_list::{self, Axis, Command, Placement, WriteError, Writer};
use crate::geometry::{Angle, Point3, Q16};
use embedded_graphics_core::pixelcolor::Rgb888;

impl Placement {
    /// Its bytes in a chunk's header.
    fn to_bytes(self) -> [u8; PLACEMENT] {
        let mut b = [0u8; PLACEMENT];
        let p = |q: Point3| [q.x, q.y, q.z].map(|v| v.to_bits().to_le_bytes());
        for (i, w) in p(self.translate)
            .iter()
            .chain(p(self.scale).iter())
            .enumerate()
        {
            let at = if i < 3 { 4 * i } else { 18 + 4 * (i - 3) };
            b[at..at + 4].copy_from_slice(w);
        }
        for (i, a) in self.rotate.iter().enumerate() {
            b[12 + 2 * i..14 + 2 * i].copy_from_slice(&a.to_bits().to_le_bytes());
        }
        b
    }

    /// Read back from a chunk's header.
    fn from_bytes(b: &[u8]) -> Placement {
        let i = |at: usize| {
            let w = b.get(at..at + 4).and_then(|s| s.try_into().ok());
            Q16::from_bits(i32::from_le_bytes(w.unwrap_or([0; 4])))
        };
        let a = |at: usize| {
            let w = b.get(at..at + 2).and_then(|s| s.try_into().ok());
            Angle::from_bits(u16::from_le_bytes(w.unwrap_or([0; 2])))
        };
        Placement {
            translate: Point3::new(i(0), i(4), i(8)),
            rotate: [a(12), a(14), a(16)],
            scale: Point3::new(i(18), i(22), i(26)),
        }
    }
}

/// Bytes of a placement in a chunk's header.
const PLACEMENT: usize = 30;
/// Bytes of a chunk's header: the segment (`u16`), complete (`u8`), the
/// commands' length (`u32`), the placement.
pub const HEADER: usize = 7 + PLACEMENT;

/// The records of a scene's segments in one caller-owned buffer (see the
/// [module](self) docs).
#[derive(Debug, Default)]
pub(crate) struct Records<'a> {
    bytes: &'a mut [u8],
    len: usize,
    peak: usize,
    /// The segment being recorded (its chunk is the last), and the colour
    /// its record has in force.
    open: Option<(u16, Option<Rgb888>)>,
}

/// A chunk: where it starts, its segment, complete, its commands' length.
#[derive(Clone, Copy)]
struct Chunk {
    at: usize,
    segment: u16,
    complete: bool,
    body: usize,
}

impl Chunk {
    fn end(&self) -> usize {
        self.at + HEADER + self.body
    }
}

impl<'a> Records<'a> {
    pub(crate) fn new(bytes: &'a mut [u8]) -> Self {
        Records {
            bytes,
            len: 0,
            peak: 0,
            open: None,
        }
    }

    /// `true` while a segment is being recorded.
    #[inline(always)]
    pub(crate) fn recording(&self) -> bool {
        self.open.is_some()
    }

    /// Bytes of the buffer.
    pub(crate) fn capacity(&self) -> usize {
        self.bytes.len()
    }

    /// The most bytes held at once.
    pub(crate) fn peak(&self) -> usize {
        self.peak
    }

    fn chunk_at(&self, at: usize) -> Option<Chunk> {
        let h = self.bytes.get(at..at + HEADER)?;
        Some(Chunk {
            at,
            segment: u16::from_le_bytes([h[0], h[1]]),
            complete: h[2] != 0,
            body: u32::from_le_bytes([h[3], h[4], h[5], h[6]]) as usize,
        })
    }

    fn find(&self, s: u16) -> Option<Chunk> {
        let mut at = 0;
        while at < self.len {
            let c = self.chunk_at(at)?;
            if c.segment == s {
                return Some(c);
            }
            at = c.end();
        }
        None
    }

    /// Segment `s`'s placement ([`Placement::IDENTITY`] with no chunk).
    pub(crate) fn placement(&self, s: u16) -> Placement {
        self.find(s).map_or(Placement::IDENTITY, |c| {
            Placement::from_bytes(&self.bytes[c.at + 7..c.at + HEADER])
        })
    }

    /// Segment `s`'s commands when its record is complete.
    pub(crate) fn commands(&self, s: u16) -> Option<&[u8]> {
        let c = self.find(s).filter(|c| c.complete)?;
        self.bytes.get(c.at + HEADER..c.end())
    }

    fn remove(&mut self, c: Chunk) {
        let end = c.end();
        self.bytes.copy_within(end..self.len, c.at);
        self.len -= end - c.at;
    }

    fn push_header(&mut self, s: u16, complete: bool, p: Placement) -> bool {
        let Some(h) = self.bytes.get_mut(self.len..self.len + HEADER) else {
            return false;
        };
        h[..2].copy_from_slice(&s.to_le_bytes());
        h[2] = complete as u8;
        h[3..7].fill(0);
        h[7..].copy_from_slice(&p.to_bytes());
        self.len += HEADER;
        self.peak = self.peak.max(self.len);
        true
    }

    /// Sets segment `s`'s placement, keeping its commands. `false` when
    /// the buffer has no room for a chunk of `s`.
    pub(crate) fn set_placement(&mut self, s: u16, p: Placement) -> bool {
        match self.find(s) {
            Some(c) => {
                self.bytes[c.at + 7..c.at + HEADER].copy_from_slice(&p.to_bytes());
                true
            }
            // Not recorded: incomplete, so a place rebuilds it.
            None => self.push_header(s, false, p),
        }
    }

    /// Starts segment `s`'s record anew, at the end of the buffer,
    /// keeping its placement. With no room for its header, `s` is not
    /// recorded (and keeps no placement: only possible when it had none).
    pub(crate) fn begin(&mut self, s: u16) {
        self.open = None;
        let p = match self.find(s) {
            Some(c) => {
                let p = self.placement(s);
                self.remove(c);
                p
            }
            None => Placement::IDENTITY,
        };
        if self.bytes.is_empty() {
            return;
        }
        if self.push_header(s, true, p) {
            self.open = Some((s, None));
        }
    }

    /// Marks the open record incomplete and drops its commands.
    pub(crate) fn give_up(&mut self) {
        if let Some((s, _)) = self.open.take() {
            if let Some(c) = self.find(s) {
                self.len = c.at + HEADER;
                self.bytes[c.at + 2] = 0;
                self.bytes[c.at + 3..c.at + 7].fill(0);
            }
        }
    }

    /// Appends to segment `s`'s open record what `write` writes, with the
    /// colour `color` in force; a record that does not fit is given up.
    pub(crate) fn append(
        &mut self,
        s: usize,
        color: Option<Rgb888>,
        write: impl FnOnce(&mut Writer<'_>) -> Result<(), WriteError>,
    ) {
        let Some((open, in_force)) = self.open else {
            return;
        };
        if usize::from(open) != s {
            return;
        }
        let start = self.len;
        let mut w = Writer::body(&mut self.bytes[start..]);
        let mut r = Ok(());
        if let Some(c) = color.filter(|&c| Some(c) != in_force) {
            r = w.color(c);
        }
        let r = r.and_then(|_| write(&mut w));
        let n = w.written();
        match r {
            Ok(()) => {
                self.len += n;
                self.peak = self.peak.max(self.len);
                let at = self.len;
                if let Some(c) = self.find(open) {
                    let body = (at - c.at - HEADER) as u32;
                    self.bytes[c.at + 3..c.at + 7].copy_from_slice(&body.to_le_bytes());
                }
                if color.is_some() {
                    self.open = Some((open, color));
                }
            }
            Err(_) => self.give_up(),
        }
    }

    /// Appends a command of a list to segment `s`'s open record, or gives
    /// it up for a command a record does not hold.
    pub(crate) fn command(&mut self, s: usize, cmd: &Command<'_>, color: Rgb888) {
        match *cmd {
            Command::Push => self.append(s, None, |w| w.push()),
            Command::Pop => self.append(s, None, |w| w.pop()),
            Command::Translate(t) => self.append(s, None, |w| w.translate(t)),
            Command::Rotate(a, g) => self.append(s, None, |w| w.rotate(a, g)),
            Command::Scale(f) => self.append(s, None, |w| w.scale(f)),
            Command::Face(p) => self.append(s, Some(color), |w| w.face(p.iter())),
            Command::Label { at, text } => self.append(s, Some(color), |w| w.label(at, text)),
            // 2D commands are not the segment's; `color` and `clip` are in
            // force for what follows and are recorded with it (the clip
            // is the scene's).
            Command::Clear(_)
            | Command::Poly(_)
            | Command::Line(..)
            | Command::Color(_)
            | Command::Clip(_)
            | Command::Hide(_)
            | Command::Show(_)
            | Command::Highlight(..)
            | Command::Place(..) => {}
            _ => self.give_up(),
        }
    }

    /// Records a rotation.
    pub(crate) fn rotate(&mut self, s: usize, axis: Axis, a: Angle) {
        self.append(s, None, |w| w.rotate(axis, a));
    }
}

/// The commands of a record, decoded.
pub(crate) fn commands(bytes: &[u8]) -> impl Iterator<Item = Command<'_>> {
    let mut at = 0;
    core::iter::from_fn(move || {
        let (c, n) = display_list::decode(bytes.get(at..)?)?;
        at += n;
        Some(c)
    })
}
