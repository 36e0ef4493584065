mod common;
use common::{fixture, mandelbulb_frame};
use fractal_runtime::{KernelSources, RenderJob, Renderer, WgpuRenderer};
use std::time::Instant;
use wgpu::util::DeviceExt;

#[test]
#[ignore]
fn scratch_compare() {
    let mut r = WgpuRenderer::new().unwrap();
    let baseline = std::fs::read_to_string("/work/shared/baseline/mandelbulb.wgsl").unwrap();
    let device = r.wgpu_device().clone();
    let queue = r.queue().clone();
    let (w, h) = (1920u32, 1080u32);
    let bytes = (w * h * 4) as u64;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(baseline.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let rb = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&[w, h]),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let bg = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: params.as_entire_binding() },
        ],
    });
    let raw = || {
        let start = Instant::now();
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut p = enc.begin_compute_pass(&Default::default());
            p.set_pipeline(&pipeline);
            p.set_bind_group(0, &bg, &[]);
            p.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        enc.copy_buffer_to_buffer(&out, 0, &rb, 0, bytes);
        queue.submit([enc.finish()]);
        let s = rb.slice(..);
        s.map_async(wgpu::MapMode::Read, |_| {});
        device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
        let v: Vec<u32> = s
            .get_mapped_range()
            .unwrap()
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        rb.unmap();
        (start.elapsed().as_secs_f64() * 1e3, v)
    };
    let source = fixture("mandelbulb_render.wgsl");
    let frame = mandelbulb_frame(w, h);
    let job = RenderJob::new(KernelSources::default().with_wgsl(&source), &frame);
    let (_, base_img) = raw();
    let fix_img = r.render(&job).unwrap();
    let same = base_img.iter().zip(&fix_img.pixels).filter(|(a, b)| a == b).count();
    eprintln!("identical pixels: {same} of {}", base_img.len());
    let base_src =
        std::fs::read_to_string("/work/shared/baseline/mandelbulb.wgsl").unwrap().replace("fn main(", "fn render(");
    let layout = fractal_dsl::back::FrameLayout { lights: 0, params: 0 };
    let mut slots = vec![[0.0f32; 4]; 4];
    slots[0] = [f32::from_bits(w), f32::from_bits(h), 0.0, 0.0];
    let bframe = fractal_runtime::Frame::from_slots(layout, w, h, slots).unwrap();
    let bjob = RenderJob::new(KernelSources::default().with_wgsl(&base_src), &bframe);
    let bimg = r.render(&bjob).unwrap();
    assert_eq!(bimg.pixels, base_img);
    let (mut a, mut b, mut c) = (vec![], vec![], vec![]);
    for _ in 0..7 {
        a.push(raw().0);
        let s = Instant::now();
        r.render(&bjob).unwrap();
        c.push(s.elapsed().as_secs_f64() * 1e3);
        let s = Instant::now();
        r.render(&job).unwrap();
        b.push(s.elapsed().as_secs_f64() * 1e3);
    }
    a.sort_by(f64::total_cmp);
    b.sort_by(f64::total_cmp);
    c.sort_by(f64::total_cmp);
    let f = |v: &[f64]| format!("min {:.0} median {:.0}", v[0], v[3]);
    eprintln!("baseline raw: {}\nbaseline via plumbing: {}\nfixture via plumbing: {}", f(&a), f(&c), f(&b));
}
