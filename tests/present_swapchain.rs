//! The Vulkan swapchain presenter on an Xvfb window: a Vulkan device of its own (the first
//! one that can present to the window: lavapipe on CI), an image holding a known pattern in
//! OpenGL's bottom-up row order, presented, then the window read back with `XGetImage` and
//! compared pixel by pixel; again after the window is resized; through [`Presenter`] with and
//! without the device (Xlib read-back); and with the display closed under it. Fails when Xvfb is
//! not installed; skipped when no Vulkan device can present to it (then the Xlib presenter is
//! the path, see tests/present_xlib.rs).

#[path = "x11/mod.rs"]
mod x11;

use std::time::{Duration, Instant};

use ash::vk;
use glrt::frame::{Surface, Target, XDrawable};
use glrt::render::present::swapchain::{self, Gpu, Presented, Source, SwapchainPresenter};
use glrt::render::{FrameImage, Presenter};
use x11_dl::xlib::{self, Xlib};

/// A test image, rows bottom to top (as OpenGL reads them).
fn pattern(w: u32, h: u32) -> Vec<u8> {
    let mut v = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let checker = if (x / 4 + y / 4) % 2 == 0 { 250 } else { 20 };
            v.extend_from_slice(&[(x * 255 / (w - 1)) as u8, (y * 255 / (h - 1)) as u8, checker, 255]);
        }
    }
    v
}

/// `rgba` (rows bottom to top) as the RGB rows a window shows (top to bottom).
fn as_shown(rgba: &[u8], w: u32, h: u32) -> Vec<[u8; 3]> {
    (0..h).rev().flat_map(|y| (0..w).map(move |x| y * w + x)).map(|i| {
        let p = &rgba[i as usize * 4..];
        [p[0], p[1], p[2]]
    })
    .collect()
}

/// An instance with the presentation extensions and a device that can present to `window`.
fn gpu_for(window: XDrawable) -> Option<Gpu> {
    // Safety: plain Vulkan set-up; objects live until the process ends (the test is short).
    unsafe {
        let entry = ash::Entry::load().ok()?;
        let available = entry.enumerate_instance_extension_properties(None).ok()?;
        let extensions: Vec<_> = swapchain::instance_extensions(&available).iter().map(|n| n.as_ptr()).collect();
        if extensions.is_empty() {
            return None;
        }
        let app = vk::ApplicationInfo::default().api_version(vk::API_VERSION_1_2);
        let info = vk::InstanceCreateInfo::default().application_info(&app).enabled_extension_names(&extensions);
        let instance = entry.create_instance(&info, None).ok()?;
        let xlib_fns = ash::khr::xlib_surface::Instance::new(&entry, &instance);
        for physical in instance.enumerate_physical_devices().ok()? {
            let families = instance.get_physical_device_queue_family_properties(physical);
            let Some(family) = families.iter().position(|f| f.queue_flags.contains(vk::QueueFlags::GRAPHICS)) else { continue };
            let visual = {
                let x = Xlib::open().ok()?;
                let mut attrs: xlib::XWindowAttributes = std::mem::zeroed();
                (x.XGetWindowAttributes)(window.display.cast(), window.drawable, &mut attrs);
                (x.XVisualIDFromVisual)(attrs.visual)
            };
            if !xlib_fns.get_physical_device_xlib_presentation_support(physical, family as u32, window.display, visual as vk::VisualID) {
                continue;
            }
            let priorities = [1.0];
            let queues = [vk::DeviceQueueCreateInfo::default().queue_family_index(family as u32).queue_priorities(&priorities)];
            let dev_ext = [swapchain::DEVICE_EXTENSION.as_ptr()];
            let info = vk::DeviceCreateInfo::default().queue_create_infos(&queues).enabled_extension_names(&dev_ext);
            let Ok(device) = instance.create_device(physical, &info, None) else { continue };
            let queue = device.get_device_queue(family as u32, 0);
            let name = instance.get_physical_device_properties(physical).device_name_as_c_str().map(|c| c.to_owned());
            eprintln!("presenting with {name:?}");
            return Some(Gpu { entry, instance, physical, device, queue_family: family as u32, queue });
        }
        None
    }
}

/// Memory of `kind` for `reqs`.
fn memory(gpu: &Gpu, reqs: vk::MemoryRequirements, kind: vk::MemoryPropertyFlags) -> vk::DeviceMemory {
    // Safety: plain Vulkan calls on live objects.
    unsafe {
        let props = gpu.instance.get_physical_device_memory_properties(gpu.physical);
        let index = (0..props.memory_type_count)
            .find(|&i| reqs.memory_type_bits & (1 << i) != 0 && props.memory_types[i as usize].property_flags.contains(kind))
            .expect("memory type");
        let info = vk::MemoryAllocateInfo::default().allocation_size(reqs.size).memory_type_index(index);
        gpu.device.allocate_memory(&info, None).expect("allocate")
    }
}

/// An R8G8B8A8 image holding `rgba` (row 0 first), left in `COLOR_ATTACHMENT_OPTIMAL` like a
/// renderer's colour target.
fn source_image(gpu: &Gpu, [w, h]: [u32; 2], rgba: &[u8]) -> vk::Image {
    let d = &gpu.device;
    // Safety: plain Vulkan calls on live objects, waited for before returning.
    unsafe {
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(vk::Format::R8G8B8A8_UNORM)
            .extent(vk::Extent3D { width: w, height: h, depth: 1 })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::COLOR_ATTACHMENT);
        let image = d.create_image(&info, None).unwrap();
        let mem = memory(gpu, d.get_image_memory_requirements(image), vk::MemoryPropertyFlags::DEVICE_LOCAL);
        d.bind_image_memory(image, mem, 0).unwrap();
        let buffer = d.create_buffer(&vk::BufferCreateInfo::default().size(rgba.len() as u64).usage(vk::BufferUsageFlags::TRANSFER_SRC), None).unwrap();
        let host = vk::MemoryPropertyFlags::HOST_VISIBLE | vk::MemoryPropertyFlags::HOST_COHERENT;
        let bmem = memory(gpu, d.get_buffer_memory_requirements(buffer), host);
        d.bind_buffer_memory(buffer, bmem, 0).unwrap();
        let ptr = d.map_memory(bmem, 0, vk::WHOLE_SIZE, vk::MemoryMapFlags::empty()).unwrap();
        std::ptr::copy_nonoverlapping(rgba.as_ptr(), ptr.cast(), rgba.len());
        let pool = d.create_command_pool(&vk::CommandPoolCreateInfo::default().queue_family_index(gpu.queue_family), None).unwrap();
        let alloc = vk::CommandBufferAllocateInfo::default().command_pool(pool).command_buffer_count(1);
        let cmd = d.allocate_command_buffers(&alloc).unwrap()[0];
        d.begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default()).unwrap();
        let range = vk::ImageSubresourceRange::default().aspect_mask(vk::ImageAspectFlags::COLOR).level_count(1).layer_count(1);
        let to_dst = vk::ImageMemoryBarrier::default()
            .image(image)
            .old_layout(vk::ImageLayout::UNDEFINED)
            .new_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
            .dst_access_mask(vk::AccessFlags::TRANSFER_WRITE)
            .subresource_range(range);
        d.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::TOP_OF_PIPE, vk::PipelineStageFlags::TRANSFER, vk::DependencyFlags::empty(), &[], &[], &[to_dst]);
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers::default().aspect_mask(vk::ImageAspectFlags::COLOR).layer_count(1))
            .image_extent(vk::Extent3D { width: w, height: h, depth: 1 });
        d.cmd_copy_buffer_to_image(cmd, buffer, image, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[region]);
        let to_attachment = vk::ImageMemoryBarrier::default()
            .image(image)
            .old_layout(vk::ImageLayout::TRANSFER_DST_OPTIMAL)
            .new_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
            .src_access_mask(vk::AccessFlags::TRANSFER_WRITE)
            .dst_access_mask(vk::AccessFlags::COLOR_ATTACHMENT_WRITE)
            .subresource_range(range);
        d.cmd_pipeline_barrier(cmd, vk::PipelineStageFlags::TRANSFER, vk::PipelineStageFlags::ALL_COMMANDS, vk::DependencyFlags::empty(), &[], &[], &[to_attachment]);
        d.end_command_buffer(cmd).unwrap();
        let cmds = [cmd];
        d.queue_submit(gpu.queue, &[vk::SubmitInfo::default().command_buffers(&cmds)], vk::Fence::null()).unwrap();
        d.queue_wait_idle(gpu.queue).unwrap();
        d.destroy_command_pool(pool, None);
        d.destroy_buffer(buffer, None);
        d.free_memory(bmem, None);
        image
    }
}

/// Waits (up to 5 s) until the window shows `want`; the last read otherwise.
fn wait_for(x: &Xlib, dpy: *mut xlib::Display, win: u64, [w, h]: [u32; 2], want: &[[u8; 3]]) -> Vec<[u8; 3]> {
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let got = x11::read_rgb(x, dpy, win, w, h);
        if got == want || Instant::now() > deadline {
            return got;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn first_difference(got: &[[u8; 3]], want: &[[u8; 3]], w: u32) -> String {
    match got.iter().zip(want).position(|(a, b)| a != b) {
        Some(i) => format!("first difference at ({}, {}): got {:?}, want {:?}", i as u32 % w, i as u32 / w, got[i], want[i]),
        None => "same".into(),
    }
}

#[test]
fn swapchain_shows_the_rendered_image_and_follows_resizes() {
    let server = x11::Xvfb::start(24);
    let x = Xlib::open().expect("libX11");
    let dpy = server.open(&x);
    let win = x11::mapped_window(&x, dpy, 64, 48);
    let window = XDrawable { display: dpy.cast(), drawable: win };
    let Some(gpu) = gpu_for(window) else {
        eprintln!("skipped: no Vulkan device presents to Xvfb windows here");
        return;
    };
    // Safety: the display is live, the device outlives the presenter.
    let mut presenter = unsafe { SwapchainPresenter::new(&gpu, window, [64, 48], 1) }.expect("swapchain");
    eprintln!("swapchain {:?}", presenter.format());
    for (size, frames) in [([64u32, 48u32], 2), ([80, 60], 2)] {
        let [w, h] = size;
        unsafe { (x.XResizeWindow)(dpy, win, w, h) };
        unsafe { (x.XSync)(dpy, xlib::False) };
        presenter.resize(size, 1);
        let rgba = pattern(w, h);
        let image = source_image(&gpu, size, &rgba);
        let source = Source { image, layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, size, bottom_up: true };
        for _ in 0..frames {
            // Safety: the image's upload was waited for; the queue is ours.
            assert_eq!(unsafe { presenter.present(&source) }, Ok(Presented::Shown));
        }
        unsafe { gpu.device.queue_wait_idle(gpu.queue) }.unwrap();
        assert_eq!(presenter.format().map(|f| f.1), Some(size), "swapchain extent follows the window");
        assert_eq!(presenter.present_mode(), Some(vk::PresentModeKHR::FIFO), "swap interval 1");
        let want = as_shown(&rgba, w, h);
        let got = wait_for(&x, dpy, win, size, &want);
        assert!(got == want, "{w}x{h}: {}", first_difference(&got, &want, w));
    }
    // Swap interval 0: the swapchain is recreated without vertical sync.
    presenter.resize([80, 60], 0);
    let image = source_image(&gpu, [80, 60], &pattern(80, 60));
    let source = Source { image, layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, size: [80, 60], bottom_up: true };
    assert_eq!(unsafe { presenter.present(&source) }, Ok(Presented::Shown));
    let mode = presenter.present_mode();
    assert!(matches!(mode, Some(vk::PresentModeKHR::IMMEDIATE | vk::PresentModeKHR::MAILBOX)), "swap interval 0: {mode:?}");
    drop(presenter);

    // Through `Presenter`: the swapchain when the device is given, Xlib from a read-back
    // without it; each shows its frame.
    let target = Target { size: [80, 60], surface: Surface::Window(window), swap_interval: 0, samples: 1, alpha: true };
    for (given, path) in [(Some(&gpu), "vulkan"), (None, "xlib")] {
        let rgba: Vec<u8> = pattern(80, 60).chunks(4).rev().flatten().copied().collect();
        let image = source_image(&gpu, [80, 60], &rgba);
        let source = Source { image, layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, size: [80, 60], bottom_up: true };
        let mut frame = TestFrame { source, rgba: rgba.clone(), reads: 0 };
        // Safety: the display and the device are live.
        let mut presenter = unsafe { Presenter::new(target, given) };
        assert_eq!(presenter.path(), path);
        assert!(unsafe { presenter.show(&mut frame) });
        assert_eq!(frame.reads, usize::from(path == "xlib"), "only Xlib reads the frame back");
        unsafe { gpu.device.queue_wait_idle(gpu.queue) }.unwrap();
        let want = as_shown(&rgba, 80, 60);
        let got = wait_for(&x, dpy, win, [80, 60], &want);
        assert!(got == want, "{path}: {}", first_difference(&got, &want, 80));
    }
    let offscreen = Target { size: [80, 60], surface: Surface::Offscreen, swap_interval: 0, samples: 1, alpha: true };
    assert_eq!(unsafe { Presenter::new(offscreen, Some(&gpu)) }.path(), "offscreen");

    // The application closes its display (glrt hears of it through the GLX layer's hook):
    // the presenter stops, and dropping it does not touch the closed connection.
    let mut presenter = unsafe { Presenter::new(target, Some(&gpu)) };
    assert_eq!(presenter.path(), "vulkan");
    let rgba = pattern(80, 60);
    let image = source_image(&gpu, [80, 60], &rgba);
    let source = Source { image, layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL, size: [80, 60], bottom_up: true };
    let mut frame = TestFrame { source, rgba, reads: 0 };
    unsafe { glrt::gl_entry::glx::connection(dpy.cast()) }.expect("connection");
    unsafe { (x.XCloseDisplay)(dpy) };
    assert!(!unsafe { presenter.show(&mut frame) }, "nothing shown on a closed display");
    assert_eq!(presenter.path(), "none");
    drop(presenter);
}

/// A rendered frame: its image and the pixels a read-back returns.
struct TestFrame {
    source: Source,
    rgba: Vec<u8>,
    reads: usize,
}

impl FrameImage for TestFrame {
    fn source(&self) -> Source {
        self.source
    }
    fn read_rgba(&mut self) -> Option<Vec<u8>> {
        self.reads += 1;
        Some(self.rgba.clone())
    }
}
