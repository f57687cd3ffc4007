//! The rendering core: what the panel shows, with no hardware in it.
//!
//! A 240 × 240 frame is a stack of layers, drawn band by band (16 rows,
//! 7.5 KiB, two pixels a word in the panel's byte order) by one
//! [`FramePass`] and shipped to any [`PackedBandTarget`] (the board's SPI
//! panel, or a host test's model of it):
//!
//! 1. a display list's 2D UI: the background, a title bar and a toolbar;
//! 2. a 3D scene: a lit cube that turns, with hidden surfaces, and a HUD
//!    label on its corner;
//! 3. embedded-graphics drawables: the time in a large font, and a dot
//!    that moves along the toolbar.
//!
//! Only the rows that changed are drawn and sent: the scene marks the rows
//! its turning cube changed, and each drawable layer the rows of what
//! changed in it. All memory is in [`Memory`], which the board keeps in a
//! `static` (`.bss`) and a host test in a `Box`.

use core::convert::Infallible;
use embedded_graphics::mono_font::{ascii::FONT_10X20, MonoTextStyle};
use embedded_graphics::prelude::{Point, Primitive};
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Styled};
use embedded_graphics::text::Text;
use scanvert::controller::PrepareError;
use scanvert::display_list::Axis;
use scanvert::frame::{DrawableLayer, FrameError, FramePass, PackedLayer};
use scanvert::port::band::DirtyRows;
use scanvert::port::packed_band::{PackedBand, PackedBandTarget};
use scanvert::prelude::*;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::{Capacities, UpdateError, DEFAULT_FONT};
use scanvert::visible::VisibleError;
use scanvert::{Angle, Builder, Light, Perspective, Pipeline, Point3, Procedure, Resolve, Scene};
use scanvert::{SceneError, View, Viewport, Q16};

/// The panel's width, pixels.
pub const W: u16 = 240;
/// The panel's height, pixels.
pub const H: u16 = 240;
/// Rows in a band.
pub const ROWS: u16 = 16;

/// The scene's memory, by name: one segment (the cube, 6 faces and a
/// label) at 240 × 240.
pub const CAPS: Capacities = Capacities {
    trapezoids: 64,
    faces: 16,
    segments: 2,
    rows: H as usize,
    edges: 16,
    active: 32,
    runs: W as usize,
    labels: 2,
    text: 32,
};
/// The scene's storage.
pub type Storage = scanvert::scene_storage!(CAPS);

/// A segment's builder: a transform stack of 4, faces of up to 16
/// vertices after clipping.
type Segment<'s, 'a> = Builder<'s, 'a, 4, 16>;

/// Words of a band: two pixels a word.
const BAND_WORDS: usize = PackedBand::<Rgb565>::words_len(W, ROWS);

/// Bytes of the 2D UI's display list.
const LIST: usize = 128;
/// Polygons of the 2D UI, and their vertices.
const POLYGONS: usize = 2;
const VERTICES: usize = 8;

/// Every byte the core uses besides its stack: `const`-made, so a
/// `static` of it is zero-initialised where the compiler can, and the
/// rest is in `.data` (see the README).
pub struct Memory {
    list: [u8; LIST],
    storage: Storage,
    dirty: [u32; DirtyRows::words(H)],
    scratch: [u64; 2 * H as usize],
    band: [u32; BAND_WORDS],
    polygons: [TablePolygon; POLYGONS],
    index: [u32; 2 * POLYGONS],
    table_edges: [Edge; VERTICES],
    edges: [Edge; VERTICES],
}

impl Memory {
    /// All of it, unused.
    pub const fn new() -> Self {
        Memory {
            list: [0; LIST],
            storage: Storage::new(),
            dirty: [0; DirtyRows::words(H)],
            scratch: [0; 2 * H as usize],
            band: [0; BAND_WORDS],
            polygons: [TablePolygon::EMPTY; POLYGONS],
            index: [0; 2 * POLYGONS],
            table_edges: [Edge::EMPTY; VERTICES],
            edges: [Edge::EMPTY; VERTICES],
        }
    }
}

impl Default for Memory {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a frame could not be drawn.
#[derive(Debug)]
pub enum Error<E> {
    /// The UI's display list or row marks do not fit their memory.
    Setup,
    /// The scene refused a change.
    Scene(SceneError),
    /// The scene could not be updated.
    Update(UpdateError),
    /// The 2D layer could not be prepared.
    Prepare(PrepareError),
    /// A layer could not be drawn, or the target failed.
    Frame(FrameError<E>),
}

impl<E: core::fmt::Debug> core::fmt::Display for Error<E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Error::Setup => f.write_str("the UI's list or row marks do not fit their memory"),
            Error::Scene(e) => write!(f, "scene: {e}"),
            Error::Update(e) => write!(f, "update: {e}"),
            Error::Prepare(e) => write!(f, "2D layer: {e:?}"),
            Error::Frame(e) => write!(f, "frame: {e:?}"),
        }
    }
}

impl<E> From<SceneError> for Error<E> {
    fn from(e: SceneError) -> Self {
        Error::Scene(e)
    }
}
impl<E> From<UpdateError> for Error<E> {
    fn from(e: UpdateError) -> Self {
        Error::Update(e)
    }
}
impl<E> From<PrepareError> for Error<E> {
    fn from(e: PrepareError) -> Self {
        Error::Prepare(e)
    }
}
impl<E> From<FrameError<E>> for Error<E> {
    fn from(e: FrameError<E>) -> Self {
        Error::Frame(e)
    }
}
impl<E> From<VisibleError<Infallible>> for Error<E> {
    fn from(e: VisibleError<Infallible>) -> Self {
        Error::Frame(FrameError::Render(e))
    }
}

/// The time, as a layer.
pub type Clock = DrawableLayer<Text<'static, MonoTextStyle<'static, Rgb565>>>;
/// The dot, as a layer.
pub type Dot = DrawableLayer<Styled<Circle, PrimitiveStyle<Rgb565>>>;

/// The time shown at frame `frame`.
pub fn clock(frame: u32) -> Text<'static, MonoTextStyle<'static, Rgb565>> {
    const TIMES: [&str; 3] = ["12:00", "12:01", "12:02"];
    let style = MonoTextStyle::new(&FONT_10X20, Rgb565::WHITE);
    Text::new(TIMES[(frame / 10) as usize % 3], Point::new(8, 20), style)
}

/// The dot at frame `frame`.
pub fn dot(frame: u32) -> Styled<Circle, PrimitiveStyle<Rgb565>> {
    let x = 20 + (frame as i32 * 8) % 190;
    Circle::new(Point::new(x, 212), 14).into_styled(PrimitiveStyle::with_fill(Rgb565::GREEN))
}

/// The cube, turned by `turn` degrees about the vertical axis.
pub fn cube(b: &mut Segment<'_, '_>, turn: i32) -> Result<(), SceneError> {
    b.rotate(Axis::Y, Angle::from_degrees(turn))?;
    let p = Point3::from_int;
    for f in [
        [p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1)],
        [p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1)],
        [p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1)],
        [p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1)],
        [p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1)],
        [p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1)],
    ] {
        b.face(&f, Rgb888::new(0xe0, 0x50, 0x40))?;
    }
    b.label(p(1, 1, 1), "HUD: cube", Rgb888::WHITE).map(|_| ())
}

/// The 2D UI as a display list: a background, a title bar, a toolbar.
pub fn ui_list(bytes: &mut [u8]) -> Option<DisplayList<'_>> {
    let px = |x, y| Vertex::from_px(x, y);
    let mut w = Writer::new(bytes, W, H).ok()?;
    w.clear(Rgb888::new(0x10, 0x18, 0x28)).ok()?;
    w.color(Rgb888::new(0x30, 0x40, 0x70)).ok()?;
    w.poly([px(0, 0)?, px(240, 0)?, px(240, 28)?, px(0, 28)?])
        .ok()?;
    w.color(Rgb888::new(0x28, 0x30, 0x48)).ok()?;
    w.poly([px(8, 204)?, px(232, 204)?, px(224, 234)?, px(16, 234)?])
        .ok()?;
    DisplayList::new_checked(w.finish()).ok()
}

/// The panel's content, frame after frame.
pub struct Ui<'m> {
    list: DisplayList<'m>,
    scene: Scene<'m, 4, 16>,
    clock: Clock,
    dot: Dot,
    pass: FramePass<Rgb565>,
    dirty: DirtyRows<'m>,
    scratch: &'m mut [u64],
    band: &'m mut [u32],
    table: TableMemory<'m>,
    edges: &'m mut [Edge],
    frame: u32,
}

impl<'m> Ui<'m> {
    /// The first frame's content, in `mem`. The first step sends every
    /// row, since what the panel shows is not known.
    pub fn new(mem: &'m mut Memory) -> Result<Self, Error<Infallible>> {
        let list = ui_list(&mut mem.list).ok_or(Error::Setup)?;
        let (near, far) = (Q16::from_int(1), Q16::from_int(100));
        let persp = Perspective::from_fov(Angle::from_degrees(50), W, near, far);
        let window = Viewport::centred(W, H);
        let (persp, window) = (
            persp.map_err(SceneError::from)?,
            window.map_err(SceneError::from)?,
        );
        let mut pipeline = Pipeline::new(persp, window);
        pipeline.set_light(Light::new([1, 2, 3], 70).map_err(SceneError::from)?);
        let mut scene = Scene::new(mem.storage.as_memory(), pipeline)?;
        let eye = View::look_at(Point3::from_int(4, 3, 7), Point3::from_int(0, 0, 0));
        scene.set_view(&eye.map_err(SceneError::from)?)?;
        let dirty = DirtyRows::new(&mut mem.dirty, H).ok_or(Error::Setup)?;
        Ok(Ui {
            list,
            scene,
            clock: DrawableLayer::new(clock(0)),
            dot: DrawableLayer::new(dot(0)),
            pass: FramePass::new((W, H), Rgb565::BLACK),
            dirty,
            scratch: &mut mem.scratch,
            band: &mut mem.band,
            table: TableMemory {
                polygons: &mut mem.polygons,
                index: &mut mem.index,
                edges: &mut mem.table_edges,
                lines: &mut [],
            },
            edges: &mut mem.edges,
            frame: 0,
        })
    }

    /// The 3D scene, as last stepped (for tests that render it whole).
    #[allow(dead_code)]
    pub fn scene(&mut self) -> &mut Scene<'m, 4, 16> {
        &mut self.scene
    }

    /// Changes the content to the next frame and sends the rows that
    /// changed to `panel`; returns the rows sent. After a step that fails,
    /// the next one sends every row: the panel may not have the last.
    pub fn step<P>(&mut self, panel: &mut P) -> Result<u32, Error<P::Error>>
    where
        P: PackedBandTarget<Color = Rgb565> + ?Sized,
    {
        let frame = self.frame;
        // The application's changes: the cube turns, the clock and the dot.
        self.scene.invalidate(0)?;
        let mut turn = |b: &mut Segment<'_, '_>| cube(b, 9 * frame as i32);
        let procs: &mut [&mut dyn Procedure<4, 16>] = &mut [&mut turn];
        self.scene
            .update_marking(procs, DEFAULT_FONT, &mut self.dirty, self.scratch)?;
        self.clock.set(clock(frame));
        self.dot.set(dot(frame));
        // One frame through the layers, changed rows only.
        let table = TableMemory {
            polygons: &mut *self.table.polygons,
            index: &mut *self.table.index,
            edges: &mut *self.table.edges,
            lines: &mut [],
        };
        let mut controller = Controller::new(Rasterizer::new(self.edges));
        let mut ui = controller.bands(&self.list, table)?;
        let mut view = self
            .scene
            .bands(Resolve::default(), Rgb565::BLACK, DEFAULT_FONT)?;
        let layers: &mut [&mut dyn PackedLayer<Rgb565>] =
            &mut [&mut ui, &mut view, &mut self.clock, &mut self.dot];
        let sent = self
            .pass
            .draw_marked_packed(layers, &mut self.dirty, ROWS, self.band, panel)?;
        self.dirty.clear();
        self.frame += 1;
        Ok(sent)
    }
}
