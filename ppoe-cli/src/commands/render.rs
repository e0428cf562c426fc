//! `ppoe render`: pictures of any robot and its tool-pose distribution for the cases of a
//! JSON file.

use crate::args::{ChainArgs, NoiseArgs, SurfaceArgs};
use crate::frames::{self, Sink};
use crate::picture;
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormat {
    Png,
    Svg,
    Gif,
    Html,
}

/// The arguments of `ppoe render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    chain: ChainArgs,
    /// The input JSON file (the input of `ppoe eval`; default or `-`: standard input).
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    #[command(flatten)]
    noise: NoiseArgs,
    /// png or svg: one picture per case (ppoe-render-<i>.<ext>), each written as it is
    /// computed; gif: one animation of all cases (ppoe-render.gif); html: one interactive
    /// view of all cases (ppoe-render.html). gif and html are streamed (memory does not
    /// grow with the number of cases); each case is computed twice (to fit the view, to
    /// write it).
    #[arg(long, value_enum, default_value_t = ImageFormat::Png)]
    format: ImageFormat,
    /// The output directory.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    #[command(flatten)]
    surface: SurfaceArgs,
}

/// `ppoe render`: one picture per case, or one animation.
pub fn run(a: &RenderArgs) -> anyhow::Result<()> {
    let fmt = a.format;
    let name = move |i: usize| match fmt {
        ImageFormat::Svg => format!("ppoe-render-{i}.svg"),
        _ => format!("ppoe-render-{i}.png"),
    };
    // The picture writers write atomically themselves.
    let write = move |p: &Path, f: &picture::Frame| match fmt {
        ImageFormat::Svg => picture::write_svg(p, f),
        _ => picture::write_png(p, f),
    };
    let sink = match fmt {
        ImageFormat::Gif => Sink::Gif {
            dir: &a.out,
            name: "ppoe-render.gif",
        },
        ImageFormat::Html => Sink::Html {
            dir: &a.out,
            name: "ppoe-render.html",
        },
        _ => Sink::Each {
            dir: &a.out,
            name: &name,
            write: &write,
        },
    };
    frames::run(
        &a.chain,
        a.input.as_deref(),
        &a.noise,
        &a.surface,
        &sink,
        crate::exaggerate::Exaggeration::Auto,
    )
}
