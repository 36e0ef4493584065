//! wgpu calls whose failures are values, not panics: error scopes around a call ([`capture`]), the errors a device
//! raises outside any scope kept for the next check ([`Uncaptured`]), and blocking reads of mappable buffers.

use std::sync::{mpsc, Arc, Mutex};

use crate::device::Backend;
use crate::error::RenderError;

/// A device error of the wgpu backend.
pub fn device_error(message: impl ToString) -> RenderError {
    RenderError::Device { backend: Backend::Wgpu, message: message.to_string() }
}

/// The errors a device raised outside any error scope (wgpu would otherwise panic on them), kept until the next
/// [`Uncaptured::check`].
#[derive(Clone, Default)]
pub struct Uncaptured(Arc<Mutex<Vec<String>>>);

impl Uncaptured {
    /// Collects `device`'s errors raised outside any scope.
    pub fn install(device: &wgpu::Device) -> Uncaptured {
        let uncaptured = Uncaptured::default();
        let sink = Arc::clone(&uncaptured.0);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut errors) = sink.lock() {
                errors.push(e.to_string());
            }
        }));
        uncaptured
    }

    /// Turns a scoped error, or any error that escaped the scopes, into a device error.
    pub fn check(&self, scoped: Option<wgpu::Error>) -> Result<(), RenderError> {
        let mut messages: Vec<String> = scoped.into_iter().map(|e| e.to_string()).collect();
        if let Ok(mut escaped) = self.0.lock() {
            messages.append(&mut escaped);
        }
        if messages.is_empty() {
            Ok(())
        } else {
            Err(device_error(messages.join("\n")))
        }
    }
}

/// Copies `bytes` of `source` into `readback` (a MAP_READ | COPY_DST buffer of at least `bytes`), waits for the device
/// and returns them as u32 words.
pub fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
    readback: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u32>, String> {
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_buffer_to_buffer(source, 0, readback, 0, bytes);
    queue.submit([encoder.finish()]);
    let data = map_read(device, readback, bytes)?;
    Ok(data.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}

/// Waits for the device and returns the first `bytes` of a MAP_READ buffer, which is unmapped again afterwards.
pub fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, String> {
    let slice = buffer.slice(..bytes);
    let (sender, receiver) = mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
    receiver.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
    let data = slice.get_mapped_range().map_err(|e| e.to_string())?.to_vec();
    buffer.unmap();
    Ok(data)
}

/// Runs `f` inside validation, out-of-memory and internal error scopes and returns the first error they caught, so a
/// kernel, buffer or surface the driver refuses is an error value rather than a panic.
pub fn capture<T>(device: &wgpu::Device, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = f();
    // Scopes pop innermost first.
    let errors = [validation.pop(), memory.pop(), internal.pop()].map(pollster::block_on);
    (value, errors.into_iter().flatten().next())
}
