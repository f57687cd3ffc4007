//! The `scanvert` command-line program.
//!
//! ```text
//! scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats] [--band-rows N]
//! scanvert asm SCENE.dl --out LIST.scvl
//! scanvert disasm LIST.scvl [--out SCENE.dl]
//! scanvert checksum SCENE...
//! ```
//!
//! `SCENE` is either form of the display list, told apart by the magic
//! number. Every error exits with a non-zero status and a message naming
//! the file and the line (text) or byte offset (binary); no output file is
//! written on an error.

use crate::dual_port::DualPortRam;
use crate::refresh::RefreshController;
use crate::text::{self, Assembled};
use crate::timing::VideoTiming;
use scanvert::controller::{
    edges_3d, needs_3d, Controller, Needs3d, RenderError, Stats, Storage3d,
};
use scanvert::display_list::{Command, DisplayList, MAGIC};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::scene::label::Label;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreMemory};
use scanvert::visible::sweep::{Active, Cover, Resolve};
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};
use std::fmt;
use std::path::{Path, PathBuf};

const USAGE: &str = "\
usage:
  scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats] [--band-rows N]
  scanvert asm SCENE.dl --out LIST.scvl
  scanvert disasm LIST.scvl [--out SCENE.dl]
  scanvert checksum SCENE...
  scanvert demo [--out DIR] [--frames N] [--no-speed]

SCENE is a display list in text form or binary form (told apart by its magic number).
--band-rows N renders through the library's band path, N >= 1 rows at a time, with
no whole frame in the library: each band is shipped into the simulator's RAM; the
image is the same, pixel for pixel.
demo animates 3D bars over a map with labels through the simulated display
(double-buffered), writes DIR/frame-NN.png (default: demo/, 8 frames) and
prints the segments regenerated, trapezoids per frame and frames/s.";

/// Exit status for bad input (a scene that cannot be read or rendered).
pub const EXIT_INPUT: u8 = 1;
/// Exit status for a bad command line.
pub const EXIT_USAGE: u8 = 2;
/// Exit status for a failure to write the output.
pub const EXIT_IO: u8 = 3;

/// A failure of the program, with its exit status.
#[derive(Debug)]
pub struct CliError {
    /// Exit status.
    pub status: u8,
    /// What to tell the user.
    pub message: String,
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

fn usage(msg: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_USAGE,
        message: format!("{msg}\n{USAGE}"),
    }
}

pub(crate) fn input(path: &Path, msg: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_INPUT,
        message: format!("{}: {msg}", path.display()),
    }
}

pub(crate) fn io(path: &Path, e: impl fmt::Display) -> CliError {
    CliError {
        status: EXIT_IO,
        message: format!("{}: {e}", path.display()),
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
    /// Reads and checks `path`, in either form.
    pub fn load(path: &Path) -> Result<Scene, CliError> {
        let raw = std::fs::read(path).map_err(|e| input(path, e))?;
        Scene::from_bytes(path, raw)
    }

    /// Checks `raw` (text or binary) read from `path`.
    pub fn from_bytes(path: &Path, raw: Vec<u8>) -> Result<Scene, CliError> {
        let path = path.to_path_buf();
        if raw.starts_with(&MAGIC) {
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

/// Edge slots this list needs: its largest polygon's vertex count. Memory
/// follows the scene, not the format's worst case.
pub fn edges_needed(list: &DisplayList<'_>) -> usize {
    list.commands()
        .map(|(_, c)| match c {
            Command::Poly(v) => v.len(),
            Command::Poly3(v) => v.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0)
}

/// The outcome of rendering a scene through the simulated hardware.
#[derive(Debug)]
pub struct Rendered {
    /// The RAM after the graphic controller wrote the frame.
    pub ram: DualPortRam,
    /// What the controller did.
    pub stats: Stats,
}

/// Runs the graphic controller on `scene` into a fresh (black) dual-port RAM.
///
/// A scene with a 3D layer (`poly3`, or the 3D scene commands) gets its
/// memory too, sized from the scene by [`needs_3d`]: as many trapezoid
/// slots as its polygons are cut into, a face each, an active entry per
/// trapezoid (the most that can overlap a row), a run per column, and the
/// label slots and text its labels need.
pub fn render_scene(scene: &Scene) -> Result<Rendered, CliError> {
    let list = scene.list();
    let mut edges = vec![Edge::EMPTY; edges_needed(&list)];
    let mut slots = vec![EdgeSlot::EMPTY; edges_3d(&list)];
    // `None`: a scene command fails; rendering reports where.
    let need = needs_3d(&list, &mut slots).unwrap_or(Needs3d {
        poly3: 1,
        rows: list.height() as usize,
        runs: list.width() as usize,
        ..Needs3d::default()
    });
    let mut labels = vec![Label::EMPTY; need.labels];
    let mut text = vec![0u8; need.text];
    let mut traps = vec![Trapezoid::EMPTY; need.trapezoids];
    let mut faces = vec![Face::EMPTY; need.faces];
    let mut segments = [Segment::EMPTY; 1];
    let mut rows = vec![0u16; need.rows];
    let mut active = vec![Active::EMPTY; need.trapezoids];
    let mut cover = vec![Cover::EMPTY; need.trapezoids];
    let mut runs = vec![Run::EMPTY; need.runs];
    let mut controller = Controller::new(Rasterizer::new(&mut edges));
    if need.any() {
        controller = controller.with_labels(&mut labels, &mut text);
        controller = controller.with_3d(Storage3d {
            store: StoreMemory {
                trapezoids: &mut traps,
                faces: &mut faces,
                segments: &mut segments,
                rows: &mut rows,
                edges: &mut slots,
            },
            active: &mut active,
            cover: &mut cover,
            runs: &mut runs,
            resolve: Resolve::default(),
        });
    }
    let mut ram = DualPortRam::new(list.width(), list.height());
    let stats = controller
        .render(&list, &mut ram.write_port())
        .map_err(|e| scene.render_error(e))?;
    Ok(Rendered { ram, stats })
}

/// Renders `scene` as [`render_scene`] does, but through the library's
/// band path, `rows` rows at a time: the controller fills one band buffer
/// of `rows × width` pixels at a time and each band is shipped into a
/// fresh (black) dual-port RAM, row by row as spans of equal colour. The
/// memory is sized from the scene as for [`render_scene`], with an edge
/// table for every polygon after the last `clear`.
pub fn render_scene_bands(scene: &Scene, rows: u16) -> Result<Rendered, CliError> {
    use scanvert::pixelcolor::{Rgb565, RgbColor};
    use scanvert::port::band::{BandTarget, BandsError};
    use scanvert::port::{Span, SpanTarget};
    use scanvert::raster::table::{needs_table, TableMemory, TablePolygon};
    let list = scene.list();
    let mut edges = vec![Edge::EMPTY; edges_needed(&list)];
    let mut slots = vec![EdgeSlot::EMPTY; edges_3d(&list)];
    let need = needs_3d(&list, &mut slots).unwrap_or(Needs3d {
        poly3: 1,
        rows: list.height() as usize,
        runs: list.width() as usize,
        ..Needs3d::default()
    });
    let t = needs_table(&list);
    let mut polygons = vec![TablePolygon::EMPTY; t.polygons];
    let mut table_index = vec![0u32; 2 * t.polygons];
    let mut table_edges = vec![Edge::EMPTY; t.edges];
    let mut labels = vec![Label::EMPTY; need.labels];
    let mut text = vec![0u8; need.text];
    let mut traps = vec![Trapezoid::EMPTY; need.trapezoids];
    let mut faces = vec![Face::EMPTY; need.faces];
    let mut segments = [Segment::EMPTY; 1];
    let mut index = vec![0u16; need.rows];
    let mut active = vec![Active::EMPTY; need.trapezoids];
    let mut cover = vec![Cover::EMPTY; need.trapezoids];
    let mut runs = vec![Run::EMPTY; need.runs];
    let mut controller = Controller::new(Rasterizer::new(&mut edges));
    if need.any() {
        controller = controller.with_labels(&mut labels, &mut text);
        controller = controller.with_3d(Storage3d {
            store: StoreMemory {
                trapezoids: &mut traps,
                faces: &mut faces,
                segments: &mut segments,
                rows: &mut index,
                edges: &mut slots,
            },
            active: &mut active,
            cover: &mut cover,
            runs: &mut runs,
            resolve: Resolve::default(),
        });
    }
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
    let table = TableMemory {
        polygons: &mut polygons,
        index: &mut table_index,
        edges: &mut table_edges,
    };
    let stats = controller
        .render_bands(&list, table, rows, &mut band, &mut Ship(&mut ram))
        .map_err(|e| match e {
            BandsError::Render(e) => input(
                &scene.path,
                format_args!("{}: {e}", scene.locate(e.offset())),
            ),
            BandsError::Band(e) => usage(e),
            BandsError::Ship { error, .. } => match error {},
        })?;
    Ok(Rendered { ram, stats })
}

/// Writes `bytes` to `path` through a temporary file, so that a failed
/// write leaves no partial output.
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".partial");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, bytes)
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io(path, e)
        })
}

struct Args {
    positional: Vec<String>,
    out: Option<PathBuf>,
    timing: Option<String>,
    stats: bool,
    frames: Option<usize>,
    no_speed: bool,
    band_rows: Option<u16>,
}

fn parse(args: &[String]) -> Result<Args, CliError> {
    let mut a = Args {
        positional: Vec::new(),
        out: None,
        timing: None,
        stats: false,
        frames: None,
        no_speed: false,
        band_rows: None,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
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
            "--no-speed" => a.no_speed = true,
            "--timing" => {
                let v = it.next().ok_or_else(|| usage("--timing needs a mode"))?;
                a.timing = Some(v.clone());
            }
            "--stats" => a.stats = true,
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

fn timing_for(name: Option<&str>, w: u16, h: u16) -> Result<VideoTiming, CliError> {
    let t = match name.unwrap_or("auto") {
        "auto" => VideoTiming::for_frame(w, h),
        "reference" => VideoTiming::REFERENCE_640X480,
        "vga" => VideoTiming::VGA_640X480_60,
        "256" => VideoTiming::TV_256X256,
        other => return Err(usage(format_args!("unknown timing {other}"))),
    };
    Ok(t)
}

fn one_input(a: &Args, cmd: &str) -> Result<PathBuf, CliError> {
    match a.positional.as_slice() {
        [p] => Ok(PathBuf::from(p)),
        [] => Err(usage(format_args!("{cmd}: missing input file"))),
        _ => Err(usage(format_args!("{cmd}: one input file expected"))),
    }
}

/// Runs the program on `args` (without the program name); returns what to
/// print on standard output.
pub fn run(args: &[String]) -> Result<String, CliError> {
    let Some((cmd, rest)) = args.split_first() else {
        return Err(usage("missing command"));
    };
    let a = parse(rest)?;
    match cmd.as_str() {
        "render" => {
            let path = one_input(&a, "render")?;
            let out = a
                .out
                .clone()
                .ok_or_else(|| usage("render: --out IMAGE.png is required"))?;
            let scene = Scene::load(&path)?;
            let list = scene.list();
            let timing = timing_for(a.timing.as_deref(), list.width(), list.height())?;
            let mut r = match a.band_rows {
                Some(n) => render_scene_bands(&scene, n)?,
                None => render_scene(&scene)?,
            };
            let frame = RefreshController::new(timing).read_frame(&mut r.ram);
            let png = crate::image::encode_png(&frame).map_err(|e| io(&out, e))?;
            write_atomic(&out, &png)?;
            Ok(if a.stats {
                let s = r.stats;
                format!(
                    "{}: {}x{}, {} commands, {} polygons, {} spans, {} pixels, {} clears\n",
                    path.display(),
                    list.width(),
                    list.height(),
                    s.commands,
                    s.polygons,
                    s.spans,
                    s.pixels,
                    s.clears
                ) + &if s.poly3 + s.faces + s.culled + s.clipped_away + s.labels > 0 {
                    format!(
                        "{}: {} poly3, {} faces ({} culled, {} clipped away), {} labels, {} trapezoids, {} runs, {} intersecting spans\n",
                        path.display(),
                        s.poly3,
                        s.faces,
                        s.culled,
                        s.clipped_away,
                        s.labels,
                        s.trapezoids,
                        s.visible.runs,
                        s.visible.intersecting
                    )
                } else {
                    String::new()
                }
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
            let scene = Scene::load(&path)?;
            write_atomic(&out, &scene.bytes)?;
            Ok(String::new())
        }
        "disasm" => {
            let path = one_input(&a, "disasm")?;
            let scene = Scene::load(&path)?;
            let txt = text::disassemble(&scene.list());
            match &a.out {
                Some(out) => write_atomic(out, txt.as_bytes()).map(|()| String::new()),
                None => Ok(txt),
            }
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
                    "checksum {stem} {:08x}\n",
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
            crate::demo::run(&dir, a.frames.unwrap_or(8), !a.no_speed)
        }
        "help" | "--help" | "-h" => Ok(format!("{USAGE}\n")),
        other => Err(usage(format_args!("unknown command {other}"))),
    }
}
