//! The `scanvert` command-line program.
//!
//! ```text
//! scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats] [--band-rows N]
//!                  [--resolve auto|crossing|bisect|paint] [--race MHZ [--fifo K] [--ring runs|scanvideo]]
//! scanvert asm SCENE.dl --out LIST.scvl
//! scanvert disasm LIST.scvl [--out SCENE.dl]
//! scanvert checksum SCENE...
//! scanvert demo [--out DIR] [--frames N] [--size WxH] [--no-speed]
//!               [--race MHZ [--fifo K] [--ring runs|scanvideo] [--timing auto|reference|vga|256]]
//! scanvert help [COMMAND]        # or: scanvert COMMAND --help
//! ```
//!
//! A usage error prints one line, the error, then the usage of that
//! command alone (its lines of `scanvert help COMMAND`). A command takes
//! only the options its usage lists.
//!
//! `SCENE` is either form of the display list, told apart by the magic
//! number, in a file of at most [`INPUT_LIMIT`] bytes (binary) or
//! [`TEXT_LIMIT`] (text). Every error exits with a non-zero status and a
//! message naming the file and the line (text) or byte offset (binary);
//! no output file is written on an error.
//!
//! Output files are written through a new temporary file next to them,
//! renamed into place; a destination that is not a regular file (a link, a
//! directory, a device, a fifo) is refused (see `write_output`).

use crate::dual_port::DualPortRam;
use crate::error::{input, io, shown};
pub use crate::error::{CliError, EXIT_INPUT, EXIT_IO, EXIT_USAGE};
use crate::memory::ListMemory;
use crate::output::write_output;
use crate::refresh::RefreshController;
use crate::text::{self, escape_for_terminal, Assembled};
use crate::timing::VideoTiming;
use scanvert::controller::{RenderError, RenderStats};
use scanvert::display_list::{DisplayList, MAGIC};
use scanvert::visible::Resolve;
use std::fmt;
use std::path::{Path, PathBuf};

const USAGE: &str = "\
usage:
  scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats] [--band-rows N]
                  [--resolve auto|crossing|bisect|paint] [--race MHZ [--fifo K] [--ring runs|scanvideo]]
  scanvert asm SCENE.dl --out LIST.scvl
  scanvert disasm LIST.scvl [--out SCENE.dl]
  scanvert import MODEL --out LIST.dl [--size WxH] [--color #rrggbb]
  scanvert checksum SCENE...
  scanvert demo [--out DIR] [--frames N] [--size WxH] [--no-speed]
                [--race MHZ [--fifo K] [--ring runs|scanvideo] [--timing auto|reference|vga|256]]
  scanvert help [COMMAND]

SCENE is a display list in text form (at most 80 MiB) or binary form (at most
16 MiB), told apart by its magic number. render draws it through the simulated
display hardware into a PNG; --timing picks the video timing of the simulated
monitor, whose visible area is the image (auto, the default: the frame's own
size); --band-rows N renders through the library's band path, N >= 1 rows at a
time (the image is the same, pixel for pixel).
asm and disasm convert between the two forms. import writes a text list that
shows a Wavefront OBJ or STL model (ASCII or binary) whole. demo animates 3D bars over a map with
labels through the simulated display (double-buffered), writes DIR/frame-NN.png
(default: demo/, 8 frames) and prints the segments regenerated, trapezoids per frame
and frames/s.
`scanvert help COMMAND` or `scanvert COMMAND --help` explains a command's options.
Exit status: 0 done, 1 bad input, 2 bad command line, 3 output not written.";

const HELP_RENDER: &str = "\
usage: scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats]
                      [--band-rows N] [--resolve auto|crossing|bisect|paint]
                      [--race MHZ [--fifo K] [--ring runs|scanvideo]]

Renders SCENE, a display list in text or binary form, through the simulated display
hardware: the graphic controller draws the frame into the frame-buffer RAM, and the
refresh controller reads it out as a monitor would, in step with the sync signals it
generates. The PNG is what the monitor shows.

options:
  --out, -o IMAGE.png  the image to write (required), not SCENE itself. It is
                       written to a new file next to it and renamed; an existing
                       regular file is replaced and keeps its mode, anything else
                       (a link, a directory, a device) is refused.
  --timing MODE        the refresh timing the simulated monitor uses (pixel clock,
                       porches, sync pulses), and with it the visible area it shows,
                       which is the size of the image:
                         auto       the default: a mode whose visible area is the
                                    frame (the reference design's at 640x480, the TV
                                    mode's at 256x256, else a custom mode at 25 MHz)
                         reference  the reference design: 640x480 visible, 25 MHz
                                    pixel clock, 59.98 Hz
                         vga        standard VGA: 640x480 visible, 25.175 MHz, 60 Hz
                         256        a TV-like raster: 256x256 visible, 5 MHz, 50 Hz
                       Where the visible area is smaller than the frame, the image
                       is cropped to the frame's top-left part, and a warning says
                       so; where it is larger, the rest of the image is black.
  --band-rows N        render through the library's band path, N rows at a time (N at
                       least 1; more rows than the frame is one band), with no whole
                       frame in the library: each band is shipped into the simulated
                       RAM. The image is the same, pixel for pixel
  --resolve MODE       how the 3D layer's visible surfaces are resolved; every mode
                       draws the same pixels (the nearest plane at each pixel centre):
                         auto      the default: paint where the frame's trapezoids
                                   are 14 rows tall or more on average and the
                                   target is memory (the bands of --band-rows),
                                   else crossing (the simulated write port takes a
                                   cycle for every pixel written, so a whole frame
                                   written through it takes crossing)
                         crossing  the scan-line sweep, intersecting spans split at
                                   the planes' crossing pixel
                         bisect    the sweep, intersecting spans halved
                         paint     far to near into the frame, nearer faces over
                                   farther ones, depths compared only between faces
                                   whose depth ranges overlap: fewer instructions
                                   where faces seldom pass through each other
                                   (with --band-rows, each band painted in turn)
  --stats              print what the graphic controller did: commands, polygons,
                       spans, pixels, clears; for 3D scenes also poly3s, faces
                       (culled, clipped away), labels, trapezoids and runs, and
                       how the visible surfaces were resolved
  --race MHZ           race the beam with no frame RAM: the refresh controller reads
                       each line from a ring of run-length rows that the graphic
                       controller, its CPU at MHZ megahertz (0.000001 to 100000, e.g.
                       168 or 12.5), composes one row at a time as colour runs just
                       before the beam needs it; each row's time comes from a cost
                       model of its work fitted to the instructions counted on a
                       Cortex-M4. A line whose row is not ready when the beam reaches
                       it is a deadline miss, shown pure red (#ff0000). Prints
                       `deadline misses: M of N lines`, then the ring's memory
                       (`ring: K rows of at most R runs (4 bytes a run): B bytes`),
                       and exits 0 whether or not lines were missed. Without
                       --timing, a frame that fits in 640x480 is raced on the
                       reference design's raster (32 us lines, 521 a frame), in
                       its top-left corner, the timing the racing figures of
                       docs/performance.md are given at, and the image is the
                       frame; a larger frame is raced in auto's mode
  --fifo K             with --race: the ring's rows, 1 to 65535 (default: 2); the
                       graphic controller runs at most K rows ahead of the beam
  --ring FORMAT        with --race: the format of the ring's rows, which the refresh
                       controller decodes: runs (the default: colour runs, 4 bytes
                       each) or scanvideo (the Raspberry Pi Pico's pico_scanvideo
                       composable scan-line tokens, in 32-bit words)
  --help, -h           this help";

const HELP_ASM: &str = "\
usage: scanvert asm SCENE.dl --out LIST.scvl

Assembles a display list in text form into the binary form the firmware reads (a
binary input is checked and written unchanged). Faults are reported with their line.

options:
  --out, -o LIST.scvl  the binary list to write (required), not SCENE.dl itself; an
                       existing regular file is replaced and keeps its mode,
                       anything else is refused
  --help, -h           this help";

const HELP_DISASM: &str = "\
usage: scanvert disasm LIST.scvl [--out SCENE.dl]

Writes a display list (either form) in text form: one command a line, each value
as the shortest decimal that assembles to the same bits (`perspective 50`, not
49.998779296875), label texts in double quotes where they need them. Assembling the
text gives the same bytes back.

options:
  --out, -o SCENE.dl   the text file to write, not LIST.scvl itself; without it,
                       standard output. An existing regular file is replaced and
                       keeps its mode, anything else is refused
  --help, -h           this help";

const HELP_IMPORT: &str = "\
usage: scanvert import MODEL --out LIST.dl [--size WxH] [--color #rrggbb]

Reads a Wavefront OBJ model (polygons of any size, v/vt/vn and negative indices;
materials ignored) or an STL model (ASCII or binary; by the extension .obj or .stl,
else by its contents) and writes a display list in text form that shows the whole
model: the frame, a perspective and a view fitted to its bounding box, a light, the
colour, then a `v` line a vertex and an `f` line a face. STL's repeated corners are
welded into shared vertices (equal coordinates), so a model as OBJ and as STL gives
the same picture. Faces counter-clockwise seen from outside show their outside. The
model is centred on the origin and scaled to a half-diagonal of 10 units. A malformed
model, or one with no face, is an error (exit 1) and no list is written.

options:
  --out, -o LIST.dl    the text list to write (required), not MODEL itself; an
                       existing regular file is replaced and keeps its mode,
                       anything else is refused
  --size WxH           the frame, each side 16 to 2047 (default: 320x240)
  --color #rrggbb      the model's colour (default: #c0c0c0)
  --help, -h           this help";

const HELP_CHECKSUM: &str = "\
usage: scanvert checksum SCENE...

Renders each SCENE into the frame-buffer RAM and prints `checksum NAME XXXXXXXX`, the
checksum of the frame that the firmware image prints for the same list (NAME is the
file name without its extension).

options:
  --help, -h           this help";

const HELP_DEMO: &str = "\
usage: scanvert demo [--out DIR] [--frames N] [--size WxH] [--no-speed]
                    [--race MHZ [--fifo K] [--ring runs|scanvideo] [--timing auto|reference|vga|256]]

Animates 40 bars over a map of 80 tiles, with place names and values as labels, at
512x256 (or --size) through the simulated display (double-buffered): first the threshold that
highlights bars changes, so only the bars are rebuilt, then the camera moves. Then six
more frames show the segment attributes on the last one, with no procedure run: the
bars highlighted, the names hidden, the bars placed higher, and each undone. Prints
per frame the segments regenerated and the trapezoids, then the frames per second on
this host.

options:
  --out, -o DIR        where the frames go, as DIR/frame-NN.png (default: demo); each
                       is written to a new file and renamed, and an existing frame
                       that is not a regular file is refused
  --frames N           how many frames, 1 to 100 (default: 8)
  --size WxH           the frame's size, each side 16 to 2047 (default: 512x256),
                       as 320x240; not with --race
  --no-speed           skip measuring the frames per second
  --race MHZ           show every frame by racing the beam with no frame RAM, as
                       `scanvert render --race` does (`scanvert help render`), in the
                       mode of --timing (default: the reference design's raster,
                       the frame in its top-left corner); prints a line
                       `frame NN: deadline misses: M of N lines` a frame instead,
                       then the ring's memory for the largest frame
  --fifo K             with --race: the ring's rows (default: 2)
  --ring FORMAT        with --race: the ring's rows as runs (default) or scanvideo
                       tokens, as for `scanvert render`
  --timing MODE        with --race: the video timing of the simulated monitor, as
                       for `scanvert render` (default: as for `scanvert render
                       --race`, the reference design's raster)
  --help, -h           this help";

/// The help of `command`, or `None` for a command that does not exist.
fn command_help(command: &str) -> Option<&'static str> {
    Some(match command {
        "render" => HELP_RENDER,
        "asm" => HELP_ASM,
        "disasm" => HELP_DISASM,
        "import" => HELP_IMPORT,
        "checksum" => HELP_CHECKSUM,
        "demo" => HELP_DEMO,
        _ => return None,
    })
}

/// A usage error: the message, on one line (escaped). [`run_reporting`]
/// adds the usage of the command it is about.
fn usage(msg: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_USAGE,
        message: escape_for_terminal(&msg.to_string()),
    }
}

/// The usage of `command` alone: the lines of its help up to the first
/// blank one. For no command, or one that does not exist, a line naming
/// the commands.
fn usage_of(command: Option<&str>) -> &'static str {
    match command {
        Some("help" | "--help" | "-h") => "usage: scanvert help [COMMAND]",
        Some(c) => match command_help(c) {
            Some(h) => h.split("\n\n").next().unwrap_or(h),
            None => USAGE_COMMANDS,
        },
        None => USAGE_COMMANDS,
    }
}

const USAGE_COMMANDS: &str = "usage: scanvert render|asm|disasm|import|checksum|demo|help ... (`scanvert help` shows each command's usage)";

/// The options each command takes, besides `--help`: exactly those its
/// usage lists (`-o` is `--out`).
fn options_of(command: &str) -> &'static [&'static str] {
    match command {
        "render" => &[
            "--out",
            "--timing",
            "--stats",
            "--band-rows",
            "--resolve",
            "--race",
            "--fifo",
            "--ring",
        ],
        "asm" | "disasm" => &["--out"],
        "import" => &["--out", "--size", "--color"],
        "demo" => &[
            "--out",
            "--frames",
            "--size",
            "--no-speed",
            "--race",
            "--fifo",
            "--ring",
            "--timing",
        ],
        _ => &[],
    }
}

/// `#rrggbb`.
fn parse_color(v: &str) -> Option<scanvert::pixelcolor::Rgb888> {
    let hex = v.strip_prefix('#')?;
    if hex.len() != 6 || !hex.bytes().all(|c| c.is_ascii_hexdigit()) {
        return None;
    }
    let n = u32::from_str_radix(hex, 16).ok()?;
    Some(scanvert::pixelcolor::Rgb888::new(
        (n >> 16) as u8,
        (n >> 8) as u8,
        n as u8,
    ))
}

/// The largest binary input, in bytes: 16 MiB. A scene is far smaller
/// (the largest binary polygon is 256 KiB); the limit keeps a mistaken
/// input (`/dev/zero`, a disk image) from filling the memory.
pub const INPUT_LIMIT: u64 = 16 << 20;

/// The largest text input, in bytes: 80 MiB, five times
/// [`INPUT_LIMIT`]. `disasm` writes at most five characters for a byte of
/// list (`push` and its newline for the one-byte command; every other
/// command takes fewer), so the text of any binary list the program reads
/// is read back by `asm`.
pub const TEXT_LIMIT: u64 = 5 * INPUT_LIMIT;

fn too_large(path: &Path, binary: bool) -> CliError {
    match binary {
        true => input(path, "binary input larger than the 16 MiB limit"),
        false => input(path, "text input larger than the 80 MiB limit"),
    }
}

/// The contents of the input file `path`, refused as soon as they exceed
/// their limit ([`INPUT_LIMIT`] for a binary list, told by its magic
/// number, [`TEXT_LIMIT`] for text): a regular file by its size, before
/// reading more than its magic number; anything else (a device, a pipe)
/// after at most `TEXT_LIMIT + 1` bytes, never holding more than the
/// limit in memory.
pub fn read_input(path: &Path) -> Result<Vec<u8>, CliError> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| input(path, e))?;
    let size = file.metadata().map_err(|e| input(path, e))?;
    let mut reader = file.take(TEXT_LIMIT + 1);
    let mut bytes = Vec::new();
    let mut chunk = vec![0u8; 1 << 16];
    let mut checked = false;
    loop {
        let n = match reader.read(&mut chunk) {
            Ok(0) => return Ok(bytes),
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(input(path, e)),
        };
        bytes.extend_from_slice(&chunk[..n]);
        let binary = bytes.starts_with(&MAGIC);
        if !checked && (bytes.len() >= MAGIC.len() || binary) {
            // A regular file is judged by its size once its form is known.
            checked = true;
            let limit = if binary { INPUT_LIMIT } else { TEXT_LIMIT };
            if size.is_file() && size.len() > limit {
                return Err(too_large(path, binary));
            }
        }
        let limit = if binary { INPUT_LIMIT } else { TEXT_LIMIT };
        if bytes.len() as u64 > limit {
            return Err(too_large(path, binary));
        }
    }
}

/// A scene read from a file: the binary list, and the line table when it
/// came from text.
#[derive(Debug)]
pub struct Scene {
    path: PathBuf,
    bytes: Vec<u8>,
    text: Option<Assembled>,
}

impl Scene {
    /// Reads and checks `path`, in either form, at most [`INPUT_LIMIT`]
    /// bytes of it.
    pub fn load(path: &Path) -> Result<Scene, CliError> {
        let raw = read_input(path)?;
        Scene::from_bytes(path, raw)
    }

    /// Checks `raw` (binary, at most [`INPUT_LIMIT`] bytes, or text, at
    /// most [`TEXT_LIMIT`]) read from `path`.
    pub fn from_bytes(path: &Path, raw: Vec<u8>) -> Result<Scene, CliError> {
        let binary = raw.starts_with(&MAGIC);
        let limit = if binary { INPUT_LIMIT } else { TEXT_LIMIT };
        if raw.len() as u64 > limit {
            return Err(too_large(path, binary));
        }
        let path = path.to_path_buf();
        if binary {
            DisplayList::new_checked(&raw).map_err(|e| input(&path, e))?;
            Ok(Scene {
                path,
                bytes: raw,
                text: None,
            })
        } else {
            let asm = text::assemble_bytes(&raw).map_err(|e| input(&path, e))?;
            Ok(Scene {
                path,
                bytes: asm.bytes.clone(),
                text: Some(asm),
            })
        }
    }

    /// The checked list.
    pub fn list(&self) -> DisplayList<'_> {
        // Checked in `from_bytes`; the bytes are not changed after.
        DisplayList::new_checked(&self.bytes).expect("checked when loaded")
    }

    /// "line N" for text, "byte offset N" for binary.
    fn locate(&self, offset: usize) -> String {
        match self.text.as_ref().and_then(|t| t.line_of(offset)) {
            Some(line) => format!("line {line}"),
            None => format!("byte offset {offset}"),
        }
    }

    fn render_error<E: fmt::Debug>(&self, e: RenderError<E>) -> CliError {
        input(&self.path, format_args!("{}: {e}", self.locate(e.offset())))
    }
}

/// The outcome of rendering a scene through the simulated hardware.
#[derive(Debug)]
pub struct Rendered {
    /// The RAM after the graphic controller wrote the frame.
    pub ram: DualPortRam,
    /// What the controller did.
    pub stats: RenderStats,
}

/// Runs the graphic controller on `scene` into a fresh (black) dual-port RAM.
///
/// The memory follows the scene, not the format's worst case
/// ([`ListMemory::for_list`]): edge storage for its largest polygon and,
/// with a 3D layer (`poly3`, or the 3D scene commands), as many trapezoid
/// slots as its polygons are cut into, a face each, an active entry per
/// trapezoid (the most that can overlap a row), a run per column, and the
/// label slots and text its labels need. A scene that would need more than
/// a pool can address is refused, naming the line, before any of it is
/// allocated.
pub fn render_scene(scene: &Scene) -> Result<Rendered, CliError> {
    render_scene_with(scene, Resolve::default())
}

/// [`render_scene`] with the 3D layer resolved by `resolve` (the same
/// pixels in every mode).
pub fn render_scene_with(scene: &Scene, resolve: Resolve) -> Result<Rendered, CliError> {
    let list = scene.list();
    let mut memory = ListMemory::for_list(&list).map_err(|e| scene.render_error(e))?;
    let mut ram = DualPortRam::new(list.width(), list.height());
    let stats = memory
        .controller()
        .with_resolve(resolve)
        .render(&list, &mut ram.write_port())
        .map_err(|e| scene.render_error(e))?;
    Ok(Rendered { ram, stats })
}

/// Renders `scene` as [`render_scene`] does, but through the library's
/// band path, `rows` rows at a time: the controller fills one band buffer
/// of `rows × width` pixels at a time and each band is shipped into a
/// fresh (black) dual-port RAM, row by row as spans of equal colour. The
/// memory is [`ListMemory::for_bands`]: the list's, with an edge table for
/// its 2D commands after the last `clear`.
pub fn render_scene_bands(scene: &Scene, rows: u16) -> Result<Rendered, CliError> {
    render_scene_bands_with(scene, rows, Resolve::default())
}

/// [`render_scene_bands`] with the 3D layer resolved by `resolve`
/// ([`Resolve::Paint`] paints each band in turn).
pub fn render_scene_bands_with(
    scene: &Scene,
    rows: u16,
    resolve: Resolve,
) -> Result<Rendered, CliError> {
    use scanvert::controller::PrepareError;
    use scanvert::pixelcolor::{Rgb565, RgbColor};
    use scanvert::port::band::{BandTarget, BandsError};
    use scanvert::port::{Span, SpanTarget};
    let list = scene.list();
    let mut memory = ListMemory::for_bands(&list).map_err(|e| scene.render_error(e))?;
    /// Ships each band into the RAM's write port.
    struct Ship<'r>(&'r mut DualPortRam);
    impl BandTarget for Ship<'_> {
        type Color = Rgb565;
        type Error = core::convert::Infallible;
        fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), Self::Error> {
            let w = self.0.width() as usize;
            let mut port = self.0.write_port();
            for (r, row) in px.chunks_exact(w).take(rows as usize).enumerate() {
                let mut x0 = 0;
                while x0 < w {
                    let c = row[x0];
                    let x1 = x0 + row[x0..].iter().take_while(|&&p| p == c).count();
                    port.fill_span(
                        Span {
                            y: y + r as u16,
                            x0: x0 as u16,
                            x1: x1 as u16,
                        },
                        c,
                    )?;
                    x0 = x1;
                }
            }
            Ok(())
        }
    }
    let mut ram = DualPortRam::new(list.width(), list.height());
    let mut band = vec![Rgb565::BLACK; rows.min(list.height()) as usize * list.width() as usize];
    let (controller, table) = memory.band_parts();
    let mut controller = controller.with_resolve(resolve);
    let stats = controller
        .render_bands(&list, table, rows, &mut band, &mut Ship(&mut ram))
        .map_err(|e| match e {
            BandsError::Render(PrepareError::Render(e)) => scene.render_error(e),
            BandsError::Render(e) => input(
                &scene.path,
                format_args!("{}: {e}", scene.locate(e.offset())),
            ),
            BandsError::Band(e) => usage(e),
            BandsError::Ship { error, .. } => match error {},
        })?;
    Ok(Rendered { ram, stats })
}

/// A failure to prepare `scene`'s bands, naming the line (or offset).
pub(crate) fn prepare_error(scene: &Scene, e: scanvert::controller::PrepareError) -> CliError {
    match e {
        scanvert::controller::PrepareError::Render(e) => scene.render_error(e),
        e => input(
            &scene.path,
            format_args!("{}: {e}", scene.locate(e.offset())),
        ),
    }
}

struct Args {
    positional: Vec<String>,
    out: Option<PathBuf>,
    timing: Option<String>,
    stats: bool,
    frames: Option<usize>,
    size: Option<crate::demo::Size>,
    no_speed: bool,
    help: bool,
    band_rows: Option<u16>,
    resolve: Option<Resolve>,
    race: Option<crate::race::CpuClock>,
    fifo: Option<u16>,
    ring: Option<crate::race::RowFormat>,
    color: Option<scanvert::pixelcolor::Rgb888>,
    /// The options given, by their long names, in order.
    given: Vec<&'static str>,
}

fn parse(args: &[String]) -> Result<Args, CliError> {
    let mut a = Args {
        positional: Vec::new(),
        out: None,
        timing: None,
        stats: false,
        frames: None,
        size: None,
        no_speed: false,
        help: false,
        band_rows: None,
        resolve: None,
        race: None,
        fifo: None,
        ring: None,
        color: None,
        given: Vec::new(),
    };
    // Every option of some command: which a command takes is checked
    // once the command is known (`options_of`).
    const OPTIONS: [&str; 13] = [
        "--out",
        "--frames",
        "--size",
        "--no-speed",
        "--timing",
        "--stats",
        "--resolve",
        "--race",
        "--fifo",
        "--ring",
        "--help",
        "--band-rows",
        "--color",
    ];
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let long = match arg.as_str() {
            "-o" => "--out",
            "-h" => "--help",
            s => s,
        };
        if let Some(&name) = OPTIONS.iter().find(|&&o| o == long) {
            a.given.push(name);
        }
        match arg.as_str() {
            "--out" | "-o" => {
                let v = it.next().ok_or_else(|| usage("--out needs a file name"))?;
                a.out = Some(PathBuf::from(v));
            }
            "--frames" => {
                let v = it.next().ok_or_else(|| usage("--frames needs a count"))?;
                let n = v
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (1..=100).contains(n))
                    .ok_or_else(|| usage("--frames needs a count from 1 to 100"))?;
                a.frames = Some(n);
            }
            "--size" => {
                let v = it.next().map(String::as_str).unwrap_or_default();
                a.size = Some(crate::demo::Size::parse(v).ok_or_else(|| {
                    usage("--size needs WxH, each side from 16 to 2047 (e.g. 320x240)")
                })?);
            }
            "--no-speed" => a.no_speed = true,
            "--color" => {
                let v = it.next().map(String::as_str).unwrap_or_default();
                a.color = Some(
                    parse_color(v).ok_or_else(|| usage("--color needs #rrggbb (e.g. #c0c0c0)"))?,
                );
            }
            "--timing" => {
                let v = it.next().ok_or_else(|| usage("--timing needs a mode"))?;
                a.timing = Some(v.clone());
            }
            "--stats" => a.stats = true,
            "--resolve" => {
                let v = it.next().ok_or_else(|| {
                    usage("--resolve needs a mode: auto, crossing, bisect or paint")
                })?;
                a.resolve = Some(match v.as_str() {
                    "auto" => Resolve::Auto,
                    "crossing" => Resolve::Crossing,
                    "bisect" => Resolve::Bisect,
                    "paint" => Resolve::Paint,
                    _ => {
                        return Err(usage(format_args!(
                            "--resolve: unknown mode '{v}' (auto, crossing, bisect or paint)"
                        )))
                    }
                });
            }
            "--race" => {
                let v = it.next().map(String::as_str).unwrap_or_default();
                a.race = Some(
                    crate::race::parse_mhz(v)
                        .ok_or_else(|| usage(crate::race::mhz_range_message("--race")))?,
                );
            }
            "--fifo" => {
                let v = it.next().map(String::as_str).unwrap_or_default();
                let k = v.parse::<u16>().ok().filter(|&k| k >= 1);
                a.fifo =
                    Some(k.ok_or_else(|| usage("--fifo needs a count of rows from 1 to 65535"))?);
            }
            "--ring" => {
                let v = it.next().map(String::as_str).unwrap_or_default();
                a.ring = Some(match v {
                    "runs" => crate::race::RowFormat::Runs,
                    "scanvideo" => crate::race::RowFormat::Scanvideo,
                    _ => return Err(usage("--ring needs a format: runs or scanvideo")),
                });
            }
            "--help" | "-h" => a.help = true,
            "--band-rows" => {
                // Any count ≥ 1; more rows than the frame has is one band.
                let n = it
                    .next()
                    .map(|v| v.strip_prefix('+').unwrap_or(v))
                    .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
                    .filter(|d| d.bytes().any(|b| b != b'0'))
                    .ok_or_else(|| usage("--band-rows needs a number of rows, at least 1"))?;
                a.band_rows = Some(n.parse::<u16>().unwrap_or(u16::MAX));
            }
            s if s.starts_with('-') && s.len() > 1 => {
                return Err(usage(format_args!("unknown option {s}")))
            }
            _ => a.positional.push(arg.clone()),
        }
    }
    Ok(a)
}

/// The mode a race shows a `w × h` frame in, and the size to cut the
/// monitor's image to: with `--timing`, that mode and no cut; without,
/// the reference design's raster with the image cut to the frame when the
/// frame fits in it (the timing the racing figures are given at), else
/// auto's mode.
fn race_timing(
    name: Option<&str>,
    w: u16,
    h: u16,
) -> Result<(VideoTiming, Option<(u16, u16)>), CliError> {
    let reference = VideoTiming::REFERENCE_640X480;
    match name {
        Some(name) => Ok((timing_for(name, w, h)?, None)),
        None if w <= reference.width() && h <= reference.height() => Ok((reference, Some((w, h)))),
        None => Ok((VideoTiming::for_frame(w, h), None)),
    }
}

fn timing_for(name: &str, w: u16, h: u16) -> Result<VideoTiming, CliError> {
    let t = match name {
        "auto" => VideoTiming::for_frame(w, h),
        "reference" => VideoTiming::REFERENCE_640X480,
        "vga" => VideoTiming::VGA_640X480_60,
        "256" => VideoTiming::TV_256X256,
        other => return Err(usage(format_args!("unknown timing {other}"))),
    };
    Ok(t)
}

/// The `--stats` lines of the simulated write port: its busy time at its
/// clock, the cycle model and what it predicts (see [`crate::dual_port`]).
fn write_port_stats(path: &Path, ram: &DualPortRam) -> String {
    let name = shown(path);
    let w = ram.write_counters();
    let m = ram.cycle_model();
    let reference = m == crate::dual_port::CycleModel::REFERENCE;
    let rate = |r: Option<f64>| r.map_or_else(|| "n/a".to_string(), |r| format!("{r:.0}"));
    format!(
        "{name}: write port at {} MHz: {} cycles ({} polygon set-ups, {} spans, {} cycles waiting for the edge stepper, {} clear cycles), {:.3} us simulated\n\
         {name}: write port model: {} cycles a polygon's set-up ({}), {} cycles a span for the edge stepper overlapped with the writes ({}), 1 cycle a pixel\n\
         {name}: write port rates predicted by the model: {} pixels/s, {} polygons/s, {} clears/s\n",
        f64::from(w.clock.hz()) / 1e6,
        w.cycles,
        w.polygons,
        w.spans,
        w.stepper_wait_cycles,
        w.clear_cycles,
        w.time_ps() as f64 / 1e6,
        m.setup_cycles(),
        if reference {
            "calibrated on W1's 54,945 polygons/s"
        } else {
            "set by the caller"
        },
        m.row_cycles(),
        if reference { "assumed" } else { "set by the caller" },
        rate(w.pixels_per_second()),
        rate(w.polygons_per_second()),
        rate(w.clears_per_second()),
    )
}

/// Whether `a` and `b` name one file that exists (through links, or as
/// two hard links): the same device and inode on Unix, the same canonical
/// path elsewhere.
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        match (a.canonicalize(), b.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        }
    }
}

/// `--out` of `cmd` must not be its input: replacing the scene with its
/// own image (or a list with its text) loses the scene. Checked before
/// anything is read or written.
fn not_the_input(cmd: &str, input: &Path, out: &Path) -> Result<(), CliError> {
    if same_file(input, out) {
        return Err(usage(format_args!(
            "{cmd}: --out {} is the input file; refusing to replace it",
            out.display()
        )));
    }
    Ok(())
}

fn one_input(a: &Args, cmd: &str) -> Result<PathBuf, CliError> {
    match a.positional.as_slice() {
        [p] => Ok(PathBuf::from(p)),
        [] => Err(usage(format_args!("{cmd}: missing input file"))),
        _ => Err(usage(format_args!("{cmd}: one input file expected"))),
    }
}

/// Runs the program on `args` (without the program name); returns what to
/// print on standard output. Warnings go to standard error, each a line
/// `scanvert: warning: …`.
pub fn run(args: &[String]) -> Result<String, CliError> {
    run_reporting(args, &mut |w| eprintln!("scanvert: {w}"))
}

/// [`run`], handing each warning (a line starting `warning: `) to `warn`
/// instead of printing it.
///
/// A usage error (exit status [`EXIT_USAGE`]) is one line, then the usage
/// of the command it is about.
pub fn run_reporting(args: &[String], warn: &mut dyn FnMut(&str)) -> Result<String, CliError> {
    run_command(args, warn).map_err(|mut e| {
        if e.status == EXIT_USAGE {
            e.message = format!(
                "{}\n{}",
                e.message,
                usage_of(args.first().map(String::as_str))
            );
        }
        e
    })
}

fn run_command(args: &[String], warn: &mut dyn FnMut(&str)) -> Result<String, CliError> {
    let Some((cmd, rest)) = args.split_first() else {
        return Err(usage("missing command"));
    };
    if matches!(cmd.as_str(), "help" | "--help" | "-h") {
        return match rest {
            [] => Ok(format!("{USAGE}\n")),
            [command] => command_help(command)
                .map(|h| format!("{h}\n"))
                .ok_or_else(|| usage(format_args!("help: unknown command {command}"))),
            _ => Err(usage("help: one command expected")),
        };
    }
    let a = parse(rest)?;
    if a.help {
        if let Some(h) = command_help(cmd) {
            return Ok(format!("{h}\n"));
        }
    }
    if command_help(cmd).is_some() {
        let takes = options_of(cmd);
        if let Some(o) = a
            .given
            .iter()
            .find(|o| **o != "--help" && !takes.contains(o))
        {
            return Err(usage(format_args!("{cmd}: {o} is not an option of {cmd}")));
        }
    }
    match cmd.as_str() {
        "render" => {
            let path = one_input(&a, "render")?;
            let out = a
                .out
                .clone()
                .ok_or_else(|| usage("render: --out IMAGE.png is required"))?;
            not_the_input("render", &path, &out)?;
            let scene = Scene::load(&path)?;
            let list = scene.list();
            let mode = a.timing.as_deref().unwrap_or("auto");
            if a.fifo.is_some() && a.race.is_none() {
                return Err(usage("render: --fifo goes with --race"));
            }
            if a.ring.is_some() && a.race.is_none() {
                return Err(usage("render: --ring goes with --race"));
            }
            if let Some(cpu) = a.race {
                if a.band_rows.is_some() || a.stats || a.resolve.is_some() {
                    return Err(usage(
                        "render: --race composes one row at a time and prints its misses; --band-rows, --resolve and --stats do not go with it",
                    ));
                }
                let format = a.ring.unwrap_or_default();
                let (timing, cut) = race_timing(a.timing.as_deref(), list.width(), list.height())?;
                return crate::race::render(&scene, &timing, cut, cpu, a.fifo, format, &out, warn);
            }
            let timing = timing_for(mode, list.width(), list.height())?;
            let resolve = a.resolve.unwrap_or_default();
            let mut r = match a.band_rows {
                Some(n) => render_scene_bands_with(&scene, n, resolve)?,
                None => render_scene_with(&scene, resolve)?,
            };
            // The image is the mode's visible area, read from the RAM's
            // top-left corner (see `refresh`): a smaller area crops.
            let (tw, th) = (timing.width(), timing.height());
            if tw < list.width() || th < list.height() {
                warn(&format!(
                    "warning: timing {mode} shows {tw}×{th} of the {}×{} frame; the image is cropped",
                    list.width(),
                    list.height()
                ));
            }
            let frame = RefreshController::new(timing).read_frame(&mut r.ram);
            let png = crate::image::encode_png(&frame).map_err(|e| io(&out, e))?;
            write_output(&out, &png)?;
            Ok(if a.stats {
                let s = r.stats;
                format!(
                    "{}: {}x{}, {} commands, {} polygons, {} spans, {} pixels, {} clears\n",
                    shown(&path),
                    list.width(),
                    list.height(),
                    s.commands,
                    s.polygons,
                    s.spans,
                    s.pixels,
                    s.clears
                ) + &if s.poly3 + s.faces + s.culled + s.clipped_away + s.labels > 0 {
                    format!(
                        "{}: {} poly3, {} faces ({} culled, {} clipped away), {} labels, {} trapezoids, {} runs, {} intersecting spans, resolved by {}\n",
                        shown(&path),
                        s.poly3,
                        s.faces,
                        s.culled,
                        s.clipped_away,
                        s.labels,
                        s.trapezoids,
                        s.visible.runs,
                        s.visible.intersecting,
                        match s.visible.mode {
                            Resolve::Paint => "painting far to near",
                            Resolve::Bisect => "bisection",
                            _ => "crossing points",
                        }
                    )
                } else {
                    String::new()
                } + &write_port_stats(&path, &r.ram)
            } else {
                String::new()
            })
        }
        "asm" => {
            let path = one_input(&a, "asm")?;
            let out = a
                .out
                .clone()
                .ok_or_else(|| usage("asm: --out LIST.scvl is required"))?;
            not_the_input("asm", &path, &out)?;
            let scene = Scene::load(&path)?;
            write_output(&out, &scene.bytes)?;
            Ok(String::new())
        }
        "disasm" => {
            let path = one_input(&a, "disasm")?;
            if let Some(out) = &a.out {
                not_the_input("disasm", &path, out)?;
            }
            let scene = Scene::load(&path)?;
            let txt = text::disassemble(&scene.list());
            match &a.out {
                Some(out) => write_output(out, txt.as_bytes()).map(|()| String::new()),
                None => Ok(txt),
            }
        }
        "import" => {
            let path = one_input(&a, "import")?;
            let out = a
                .out
                .clone()
                .ok_or_else(|| usage("import: --out LIST.dl is required"))?;
            not_the_input("import", &path, &out)?;
            let size = a.size.unwrap_or(crate::demo::Size {
                width: 320,
                height: 240,
            });
            let bytes = std::fs::read(&path).map_err(|e| crate::error::input(&path, e))?;
            let format = crate::import::format_of(&path.to_string_lossy(), &bytes);
            let model =
                crate::import::read(format, &bytes).map_err(|e| crate::error::input(&path, e))?;
            let color = a
                .color
                .unwrap_or(scanvert::pixelcolor::Rgb888::new(0xc0, 0xc0, 0xc0));
            let text = crate::import::list(&model, size.width, size.height, color);
            // What is written must assemble: checked before writing.
            text::assemble(&text).map_err(|e| crate::error::input(&path, e))?;
            write_output(&out, text.as_bytes())?;
            Ok(String::new())
        }
        "checksum" => {
            if a.positional.is_empty() {
                return Err(usage("checksum: missing input file"));
            }
            let mut s = String::new();
            for p in &a.positional {
                let path = PathBuf::from(p);
                let scene = Scene::load(&path)?;
                let r = render_scene(&scene)?;
                let stem = path
                    .file_stem()
                    .map(|s| s.to_string_lossy())
                    .unwrap_or_default();
                s += &format!(
                    "checksum {} {:08x}\n",
                    escape_for_terminal(&stem),
                    scanvert::port::checksum::frame_checksum(r.ram.contents())
                );
            }
            Ok(s)
        }
        "demo" => {
            if !a.positional.is_empty() {
                return Err(usage("demo: takes no input file"));
            }
            let dir = a.out.clone().unwrap_or_else(|| PathBuf::from("demo"));
            if a.fifo.is_some() && a.race.is_none() {
                return Err(usage("demo: --fifo goes with --race"));
            }
            if a.ring.is_some() && a.race.is_none() {
                return Err(usage("demo: --ring goes with --race"));
            }
            if a.race.is_some() && a.size.is_some() {
                return Err(usage("demo: --size does not go with --race"));
            }
            if a.timing.is_some() && a.race.is_none() {
                return Err(usage("demo: --timing goes with --race"));
            }
            if let Some(cpu) = a.race {
                let (w, h) = (crate::demo::WIDTH, crate::demo::HEIGHT);
                let (timing, cut) = race_timing(a.timing.as_deref(), w, h)?;
                let (frames, format) = (a.frames.unwrap_or(8), a.ring.unwrap_or_default());
                return crate::race::demo(&dir, frames, &timing, cut, cpu, a.fifo, format);
            }
            let size = a.size.unwrap_or(crate::demo::DEFAULT_SIZE);
            crate::demo::run_at(size, &dir, a.frames.unwrap_or(8), !a.no_speed)
        }
        other => Err(usage(format_args!("unknown command {other}"))),
    }
}
