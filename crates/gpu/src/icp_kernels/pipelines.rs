//! The ICP kernels compiled: `icp.wgsl`'s two entry points on one bind group layout, and the
//! small buffers every dispatch shares.

use super::buffers::buffer;
use super::run::Params;
use super::K;
use crate::context::GpuContext;

#[allow(clippy::type_complexity)]
/// Compiles the kernels on `ctx`: the bind group layout, the search and the sum pipelines,
/// and the parameter, totals and read-back buffers.
pub(super) fn compile(
    ctx: &GpuContext,
) -> (
    wgpu::BindGroupLayout,
    wgpu::ComputePipeline,
    wgpu::ComputePipeline,
    wgpu::Buffer,
    wgpu::Buffer,
    wgpu::Buffer,
) {
    let d = &ctx.device;
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("icp.wgsl"),
        source: wgpu::ShaderSource::Wgsl(include_str!("icp.wgsl").into()),
    });
    let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let ro = wgpu::BufferBindingType::Storage { read_only: true };
    let rw = wgpu::BufferBindingType::Storage { read_only: false };
    let mut entries = vec![entry(0, wgpu::BufferBindingType::Uniform)];
    entries.extend((1..=6).map(|b| entry(b, ro)));
    entries.extend((7..=10).map(|b| entry(b, rw)));
    let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("icp"),
        entries: &entries,
    });
    let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("icp"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = |name: &str| {
        d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(name),
            layout: Some(&pl),
            module: &module,
            entry_point: Some(name),
            compilation_options: Default::default(),
            cache: None,
        })
    };
    let search = pipeline("search_reduce");
    let sum = pipeline("sum_partials");
    let params = buffer(
        d,
        "params",
        std::mem::size_of::<Params>() as u64,
        wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    );
    let totals = buffer(
        d,
        "totals",
        (K * 4) as u64,
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    );
    let readback = buffer(
        d,
        "readback",
        (K * 4) as u64,
        wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
    );
    (layout, search, sum, params, totals, readback)
}
