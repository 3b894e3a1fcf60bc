//! The GPU context: adapter choice and device. Prefers a hardware adapter; falls back to a
//! software one (Mesa's lavapipe) so the same code runs in CI without a GPU.
//!
//! wgpu reports validation and out-of-memory errors asynchronously and, by default, panics on
//! them. Here every operation runs inside error scopes ([`GpuContext::scoped`]) that turn them
//! into [`GpuError`]s, and an uncaptured-error handler records anything that escapes a scope
//! (e.g. raised on another thread) so that the next scoped operation reports it instead of
//! the process panicking.

use crate::error::{GpuError, Result};
use std::sync::{Arc, Mutex};

/// Which adapters may be used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AdapterChoice {
    /// Hardware first, software (lavapipe) if there is no other.
    Any,
    /// Hardware only.
    HardwareOnly,
}

/// An open GPU device with its queue. Cloning shares the device.
#[derive(Clone)]
pub struct GpuContext {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    pub(crate) limits: wgpu::Limits,
    /// Errors that escaped every error scope (first one kept), reported by the next operation.
    uncaptured: Arc<Mutex<Option<GpuError>>>,
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
        let uncaptured: Arc<Mutex<Option<GpuError>>> = Arc::default();
        let sink = Arc::clone(&uncaptured);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert(GpuError::from_wgpu("running a GPU operation", e));
            }
        }));
        Ok(GpuContext {
            device,
            queue,
            info,
            limits,
            uncaptured,
        })
    }

    /// Runs `f` inside validation, out-of-memory and internal error scopes: an error wgpu
    /// raises meanwhile (or one recorded earlier by the uncaptured-error handler) is returned
    /// as a [`GpuError`] naming `during`, instead of wgpu's default panic.
    pub(crate) fn scoped<T>(&self, during: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
        let scopes = [
            self.device.push_error_scope(wgpu::ErrorFilter::Internal),
            self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory),
            self.device.push_error_scope(wgpu::ErrorFilter::Validation),
        ];
        let out = f();
        // Scopes pop in reverse order of their pushes; keep the first error.
        let mut caught = None;
        for scope in scopes.into_iter().rev() {
            if let Some(e) = pollster::block_on(scope.pop()) {
                caught.get_or_insert(GpuError::from_wgpu(during, e));
            }
        }
        if let Some(e) = caught {
            return Err(e);
        }
        if let Some(e) = self.uncaptured.lock().ok().and_then(|mut s| s.take()) {
            return Err(e);
        }
        out
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
