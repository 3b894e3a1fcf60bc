//! The GPU context: adapter choice and device. Prefers a hardware adapter; falls back to a
//! software one (Mesa's lavapipe) so the same code runs in CI without a GPU.

use crate::error::{GpuError, Result};

/// Which adapters may be used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdapterChoice {
    /// Hardware first, software (lavapipe) if there is no other.
    Any,
    /// Hardware only.
    HardwareOnly,
}

/// An open GPU device with its queue.
pub struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    pub(crate) limits: wgpu::Limits,
}

impl GpuContext {
    /// Opens the best adapter allowed by `choice`.
    pub fn new(choice: AdapterChoice) -> Result<GpuContext> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
        });
        let mut adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        adapters.sort_by_key(|a| rank(&a.get_info()));
        let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
        let adapter = adapters
            .into_iter()
            .find(|a| {
                choice == AdapterChoice::Any || a.get_info().device_type != wgpu::DeviceType::Cpu
            })
            .ok_or_else(|| {
                GpuError::NoAdapter(if names.is_empty() {
                    "no Vulkan adapter".into()
                } else {
                    format!("only software adapters: {}", names.join(", "))
                })
            })?;
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("semsim-gpu"),
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device {
            adapter: info.name.clone(),
            msg: e.to_string(),
        })?;
        Ok(GpuContext {
            device,
            queue,
            info,
            limits,
        })
    }

    /// The adapter's name and kind, e.g. `NVIDIA H100 (discrete GPU)` or `llvmpipe (software)`.
    pub fn adapter_name(&self) -> String {
        let kind = match self.info.device_type {
            wgpu::DeviceType::DiscreteGpu => "discrete GPU",
            wgpu::DeviceType::IntegratedGpu => "integrated GPU",
            wgpu::DeviceType::VirtualGpu => "virtual GPU",
            wgpu::DeviceType::Cpu => "software",
            wgpu::DeviceType::Other => "other",
        };
        format!("{} ({kind}, {:?})", self.info.name, self.info.backend)
    }

    /// True for a software adapter (lavapipe).
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

fn rank(info: &wgpu::AdapterInfo) -> u8 {
    match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}
