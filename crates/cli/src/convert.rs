//! `semsim convert IN OUT`: point cloud format conversion between every format semsim reads
//! and writes (a multi-scan E57 or ROS 2 bag is placed by its scans' poses and merged).

use crate::scan_input::ScanReadArgs;
use anyhow::Context;
use clap::{Args, ValueEnum};
use cloud::{CloudFormat, PcdEncoding, PlyEncoding};
use std::path::PathBuf;

/// Arguments of `semsim convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// Input cloud (.pcd .ply .xyz .txt .3d .e57 .las .laz .mcap).
    input: PathBuf,
    /// Output cloud; the format follows the extension (.pcd .ply .xyz .txt .3d .e57 .las .laz).
    output: PathBuf,
    /// Encoding of the output (PCD: ascii, binary, binary-compressed; PLY: ascii, binary-le, binary-be).
    #[arg(long, value_enum)]
    encoding: Option<Encoding>,
    /// Voxel-downsample to this edge length in metres (centroid per voxel) before writing.
    #[arg(long, value_name = "M")]
    voxel: Option<f64>,
    #[command(flatten)]
    read: ScanReadArgs,
}

/// Where the output goes: a format of the cloud crate, or one of interop's.
enum Output {
    Cloud(CloudFormat),
    /// E57, LAS or LAZ.
    Interop,
}

#[derive(Clone, Copy, ValueEnum)]
enum Encoding {
    Ascii,
    Binary,
    BinaryCompressed,
    BinaryLe,
    BinaryBe,
}

/// Runs the conversion.
pub fn run(a: ConvertArgs) -> anyhow::Result<()> {
    let format = output_format(&a)?;
    pipeline::refuse_overwriting_inputs(
        std::slice::from_ref(&a.output),
        std::slice::from_ref(&a.input),
    )?;
    let (mut cloud, notes) = interop::read_cloud(&a.input, &a.read.options())?;
    cloud::io::print_notes(&notes);
    if let Some(v) = a.voxel {
        cloud = cloud::voxel_downsample(&cloud, v)?;
    }
    if !interop::keeps_organized_shape(&a.output) && cloud.organized.is_some() {
        let before = cloud.len();
        cloud = cloud.without_invalid();
        if cloud.len() < before {
            eprintln!(
                "note: {} missing returns dropped: {} keeps no organised shape",
                before - cloud.len(),
                a.output.display()
            );
        }
    }
    match format {
        Output::Cloud(f) => cloud::write_cloud_as(&a.output, &cloud, f)
            .with_context(|| format!("writing {}", a.output.display()))?,
        Output::Interop => interop::write_cloud(&a.output, &cloud)
            .with_context(|| format!("writing {}", a.output.display()))?,
    }
    println!(
        "{} -> {}: {} points",
        a.input.display(),
        a.output.display(),
        cloud.len()
    );
    Ok(())
}

fn output_format(a: &ConvertArgs) -> anyhow::Result<Output> {
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if matches!(ext.as_str(), "e57" | "las" | "laz") {
        if a.encoding.is_some() {
            return Err(crate::exit::bad_input(format!(
                "{}: --encoding applies only to .pcd and .ply",
                a.output.display()
            )));
        }
        return Ok(Output::Interop);
    }
    let format = CloudFormat::from_path(&a.output)?;
    Ok(Output::Cloud(match (format, a.encoding) {
        (f, None) => f,
        (CloudFormat::Pcd(_), Some(Encoding::Ascii)) => CloudFormat::Pcd(PcdEncoding::Ascii),
        (CloudFormat::Pcd(_), Some(Encoding::Binary)) => CloudFormat::Pcd(PcdEncoding::Binary),
        (CloudFormat::Pcd(_), Some(Encoding::BinaryCompressed)) => CloudFormat::Pcd(PcdEncoding::BinaryCompressed),
        (CloudFormat::Ply(_), Some(Encoding::Ascii)) => CloudFormat::Ply(PlyEncoding::Ascii),
        (CloudFormat::Ply(_), Some(Encoding::BinaryLe | Encoding::Binary)) => CloudFormat::Ply(PlyEncoding::BinaryLittleEndian),
        (CloudFormat::Ply(_), Some(Encoding::BinaryBe)) => CloudFormat::Ply(PlyEncoding::BinaryBigEndian),
        (_, Some(_)) => {
            return Err(crate::exit::bad_input(format!(
                "{}: --encoding applies only to .pcd (ascii, binary, binary-compressed) and .ply (ascii, binary-le, binary-be)",
                a.output.display()
            )))
        }
    }))
}
