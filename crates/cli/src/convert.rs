//! `semsim convert IN OUT`: point cloud format conversion.

use anyhow::Context;
use clap::{Args, ValueEnum};
use cloud::{CloudFormat, PcdEncoding, PlyEncoding};
use std::path::PathBuf;

/// Arguments of `semsim convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// Input cloud (.pcd .ply .xyz .txt .3d).
    input: PathBuf,
    /// Output cloud; the format follows the extension.
    output: PathBuf,
    /// Encoding of the output (PCD: ascii, binary, binary-compressed; PLY: ascii, binary-le, binary-be).
    #[arg(long, value_enum)]
    encoding: Option<Encoding>,
    /// Voxel-downsample to this edge length in metres (centroid per voxel) before writing.
    #[arg(long, value_name = "M")]
    voxel: Option<f64>,
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
    let mut cloud = cloud::read_cloud(&a.input)?;
    if let Some(v) = a.voxel {
        cloud = cloud::voxel_downsample(&cloud, v)?;
    }
    let organised_only = !matches!(format, CloudFormat::Pcd(_));
    if organised_only && cloud.organized.is_some() {
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
    cloud::write_cloud_as(&a.output, &cloud, format)
        .with_context(|| format!("writing {}", a.output.display()))?;
    println!(
        "{} -> {}: {} points",
        a.input.display(),
        a.output.display(),
        cloud.len()
    );
    Ok(())
}

fn output_format(a: &ConvertArgs) -> anyhow::Result<CloudFormat> {
    let format = CloudFormat::from_path(&a.output)?;
    Ok(match (format, a.encoding) {
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
    })
}
