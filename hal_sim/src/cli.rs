//! The `scanvert` command-line program.
//!
//! ```text
//! scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats]
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
use crate::memory::ListMemory;
use crate::refresh::RefreshController;
use crate::text::{self, Assembled};
use crate::timing::VideoTiming;
use scanvert::controller::{RenderError, RenderStats};
use scanvert::display_list::{DisplayList, MAGIC};
use std::fmt;
use std::path::{Path, PathBuf};

const USAGE: &str = "\
usage:
  scanvert render SCENE --out IMAGE.png [--timing auto|reference|vga|256] [--stats]
  scanvert asm SCENE.dl --out LIST.scvl
  scanvert disasm LIST.scvl [--out SCENE.dl]
  scanvert checksum SCENE...
  scanvert demo [--out DIR] [--frames N] [--no-speed]

SCENE is a display list in text form or binary form (told apart by its magic number).
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
    let list = scene.list();
    let mut memory = ListMemory::for_list(&list).map_err(|e| scene.render_error(e))?;
    let mut ram = DualPortRam::new(list.width(), list.height());
    let stats = memory
        .controller()
        .render(&list, &mut ram.write_port())
        .map_err(|e| scene.render_error(e))?;
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
}

fn parse(args: &[String]) -> Result<Args, CliError> {
    let mut a = Args {
        positional: Vec::new(),
        out: None,
        timing: None,
        stats: false,
        frames: None,
        no_speed: false,
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
            let mut r = render_scene(&scene)?;
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
