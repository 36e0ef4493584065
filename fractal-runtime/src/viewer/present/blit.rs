//! The full-screen pass that draws a frame's pixel buffer to the window (or to the texture that stands in for it),
//! stretched by the rule of module `stretch`; the UI is drawn over it in the same pass (module `gpu`). Its uniform
//! and the bind group are kept from frame to frame and rewritten in place (`Queue::write_buffer` lands at the next
//! submission, in queue order), so a frame allocates nothing on the device.

const BLIT_WGSL: &str = r#"
struct Blit {
    src_size: vec2<u32>,
    dst_size: vec2<u32>,
    decode_srgb: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<storage, read> pixels: array<u32>;
@group(0) @binding(1) var<uniform> blit: Blit;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle that covers the whole target.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn source_index(d: u32, dst: u32, src: u32) -> u32 {
    return min(((2u * d + 1u) * src) / (2u * dst), src - 1u);
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let x = source_index(u32(position.x), blit.dst_size.x, blit.src_size.x);
    let y = source_index(u32(position.y), blit.dst_size.y, blit.src_size.y);
    var rgb = unpack4x8unorm(pixels[y * blit.src_size.x + x]).rgb;
    // The kernels write display-encoded colour; an sRGB target would encode it again.
    if blit.decode_srgb == 1u {
        rgb = srgb_to_linear(rgb);
    }
    return vec4<f32>(rgb, 1.0);
}
"#;

/// Words of the blit uniform.
const UNIFORM_WORDS: usize = 8;

/// The blit pipeline for one target format and what it binds, kept from frame to frame.
pub struct Blit {
    pipeline: wgpu::RenderPipeline,
    format: wgpu::TextureFormat,
    uniform: wgpu::Buffer,
    /// The bind group and the pixel buffer it binds; made again when either buffer is.
    group: Option<(wgpu::Buffer, wgpu::BindGroup)>,
}

impl Blit {
    /// The pipeline for targets of `format`, and its buffers. Call inside an error scope.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Blit {
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("blit"),
            size: (UNIFORM_WORDS * 4) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Blit { pipeline: pipeline(device, format), format, uniform, group: None }
    }

    /// Writes this frame's uniform (which lands at the next submission) and returns the bind group that draws
    /// `pixels`, `src` pixels in size, over a target of `window` pixels. Call inside an error scope.
    pub fn prepare(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        (pixels, src): (&wgpu::Buffer, (u32, u32)),
        window: (u32, u32),
    ) -> wgpu::BindGroup {
        let decode_srgb = self.format.is_srgb() as u32;
        let uniform: [u32; UNIFORM_WORDS] = [src.0, src.1, window.0, window.1, decode_srgb, 0, 0, 0];
        queue.write_buffer(&self.uniform, 0, bytemuck::cast_slice(&uniform));
        if let Some((bound, group)) = &self.group {
            if bound == pixels {
                return group.clone();
            }
        }
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("blit"),
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: pixels.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.uniform.as_entire_binding() },
            ],
        });
        self.group = Some((pixels.clone(), group.clone()));
        group
    }

    /// Records the pass that draws `group`'s pixels over `view` and then what `over` records in the same pass (the
    /// UI), writing timestamps 2 and 3 of `timestamps` where it begins and ends.
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        view: &wgpu::TextureView,
        group: &wgpu::BindGroup,
        timestamps: Option<&wgpu::QuerySet>,
        over: impl FnOnce(&mut wgpu::RenderPass<'static>),
    ) {
        // 'static, as egui-wgpu's painter takes the pass: the encoder is not touched until the pass ends.
        let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("blit"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::BLACK), store: wgpu::StoreOp::Store },
            })],
            timestamp_writes: timestamps.map(|query_set| wgpu::RenderPassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: Some(2),
                end_of_pass_write_index: Some(3),
            }),
            ..Default::default()
        });
        let mut pass = pass.forget_lifetime();
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
        over(&mut pass);
    }
}

fn pipeline(device: &wgpu::Device, format: wgpu::TextureFormat) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("blit"),
        source: wgpu::ShaderSource::Wgsl(BLIT_WGSL.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("blit"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
