//! OpenGL 2.0 programs on the Vulkan raster renderer (the shader interface of
//! `translate::glsl`): frames built by hand whose draws carry a `ProgramDraw` with SPIR-V
//! compiled here from Vulkan GLSL 4.50 written to the contract. A fragment-only program next
//! to the fixed-function vertex stage, vertex stages reading generic attributes and the
//! built-in block, points, lines and polygon modes placed by a vertex stage, and the
//! per-fragment operations around program stages; then programs written in GLSL 1.10 and
//! linked by `translate::glsl::link`. Runs on Mesa lavapipe.

use crate::lavapipe;

use std::sync::Arc;

use std::collections::HashMap;
use glrt::frame::FrameSink;
use glrt::frame::pixels::PixelBuffer;
use glrt::frame::program::{ProgramDraw, SamplerKind, ShaderProgram};
use glrt::frame::state::{Blend, BlendFactor, CompareFunc, Line, PolygonMode, Stencil, StencilFaces, StencilOp};
use glrt::frame::texture::{DepthMode, Sampler, TexImage, TexelFormat, TextureContent, TextureKind, TextureRef};
use glrt::frame::{Attrib, Clear, Draw, Frame, RasterState, Topology};
use glrt::render::frame::Renderer;
use glrt::translate::glsl::{self, CompiledShader, LinkedProgram, Stage, UniformStorage};
use glrt::translate::{dispatch, gl};

/// Window size of every test.
const SIZE: i32 = 32;

/// The built-in block's declaration, as programs include it.
const BUILTINS: &str = include_str!("../../shaders/glsl_builtins.glsl");
/// Byte offset of `glrt_ModelViewProjectionMatrix` in the built-in block (two `mat4`s).
const MVP_OFFSET: usize = 128;

/// SPIR-V of Vulkan GLSL 4.50 `source` for `stage`.
fn spirv(stage: glslang::ShaderStage, source: &str) -> Arc<[u32]> {
    let compiler = glslang::Compiler::acquire().expect("glslang");
    let source = glslang::ShaderSource::from(source);
    let options = glslang::CompilerOptions {
        target: glslang::Target::Vulkan { version: glslang::VulkanVersion::Vulkan1_1, spirv_version: glslang::SpirvVersion::SPIRV1_3 },
        ..Default::default()
    };
    let input = glslang::ShaderInput::new(&source, stage, &options, None::<&[(&str, Option<&str>)]>, None).expect("shader input");
    let shader = glslang::Shader::new(compiler, input).unwrap_or_else(|e| panic!("test shader: {e}"));
    Arc::from(shader.compile().expect("SPIR-V"))
}

/// SPIR-V of a vertex stage: `source` after the built-in block.
fn vertex(source: &str) -> Arc<[u32]> {
    spirv(glslang::ShaderStage::Vertex, &format!("#version 450\n{BUILTINS}\n{source}"))
}

/// SPIR-V of a fragment stage.
fn fragment(source: &str) -> Arc<[u32]> {
    spirv(glslang::ShaderStage::Fragment, &format!("#version 450\n{source}"))
}

/// A vertex stage that places `gl_Vertex` with `glrt_ModelViewProjectionMatrix`, colours with
/// generic attribute 1 (its alpha scaled by the w of generic attribute 3), and gives points
/// the size in the first float of the uniform block.
const PLACE: &str = r#"
layout(location = 0) in vec4 in_vertex;
layout(location = 10) in vec4 in_color;     // generic 1
layout(location = 12) in vec4 in_missing;   // generic 3: the draw has none, so (0, 0, 0, 1)
layout(set = 1, binding = 1, std430) readonly buffer Uniforms { float point_size; } uni;
layout(location = 14) out vec4 v_color;
void main() {
    gl_Position = glrt_ModelViewProjectionMatrix * in_vertex;
    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;
    gl_PointSize = uni.point_size;
    v_color = vec4(in_color.rgb + in_missing.xyz, in_color.a * in_missing.w);
}
"#;

/// The fragment stage of [`PLACE`].
const PASS: &str = r#"
layout(location = 14) in vec4 v_color;
layout(location = 0) out vec4 color;
void main() { color = clamp(v_color, 0.0, 1.0); }
"#;

/// The built-in block with `mvp` (column-major) as the modelview-projection matrix.
fn builtins(mvp: [f32; 16]) -> Arc<[u8]> {
    let mut bytes = vec![0u8; 16 << 10];
    for (i, v) in mvp.iter().enumerate() {
        bytes[MVP_OFFSET + 4 * i..MVP_OFFSET + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
    Arc::from(bytes)
}

const IDENTITY: [f32; 16] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

fn floats(values: &[f32]) -> Arc<[u8]> {
    Arc::from(values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>())
}

/// A program draw of `program` with these blocks and slot textures.
fn run(program: &Arc<ShaderProgram>, builtins: Arc<[u8]>, uniforms: Arc<[u8]>, textures: Vec<Option<TextureRef>>) -> Arc<ProgramDraw> {
    Arc::new(ProgramDraw { program: program.clone(), builtins, uniforms, textures, point_size_from_shader: true, two_side: false })
}

fn program(id: u64, vertex: Option<Arc<[u32]>>, fragment: Option<Arc<[u32]>>, samplers: Vec<SamplerKind>, attributes: Vec<u32>) -> Arc<ShaderProgram> {
    Arc::new(ShaderProgram { id, vertex, fragment, samplers, attributes })
}

/// The state of a `SIZE`² window with depth writes on and no tests.
fn state() -> RasterState {
    RasterState { viewport: [0, 0, SIZE, SIZE], ..RasterState::default() }
}

/// Window position (pixel units, y up) to normalised device coordinates, at NDC depth `z`.
fn ndc(x: f32, y: f32, z: f32) -> [f32; 4] {
    [x / SIZE as f32 * 2.0 - 1.0, y / SIZE as f32 * 2.0 - 1.0, z, 1.0]
}

/// A draw of `topology` through `program` with `positions`, their generic attribute 1
/// `color`, and identity matrices.
fn draw(topology: Topology, positions: Vec<[f32; 4]>, indices: Vec<u32>, color: [f32; 4], state: RasterState, program: Option<Arc<ProgramDraw>>) -> Draw {
    let mut d = Draw { vertex_count: positions.len(), topology, indices, state: Arc::new(state), program, ..Draw::default() };
    d.vertices.position = positions;
    d.vertices.color = Attrib { values: vec![color] };
    d.vertices.generic = vec![Attrib::default(), Attrib { values: vec![color; d.vertex_count] }];
    d
}

/// The window rectangle `x0, y0` – `x1, y1` at NDC depth `z` as two triangles.
fn rect([x0, y0, x1, y1]: [f32; 4], z: f32, color: [f32; 4], state: RasterState, program: Option<Arc<ProgramDraw>>) -> Draw {
    let positions = vec![ndc(x0, y0, z), ndc(x1, y0, z), ndc(x1, y1, z), ndc(x0, y1, z)];
    draw(Topology::Triangles, positions, vec![0, 1, 2, 0, 2, 3], color, state, program)
}

/// A frame clearing colour to black, depth to 1 and stencil to 0, then drawing `draws`.
fn frame(draws: Vec<Draw>) -> Frame {
    Frame { number: 0, draws, clears: vec![clear_all()], size: [SIZE as u32; 2], ..Frame::default() }
}

/// A clear before the first draw: colour to black, depth to 1, stencil to 0.
pub fn clear_all() -> Clear {
    Clear {
        before_draw: 0,
        color: Some([0.0, 0.0, 0.0, 0.0]),
        depth: Some(1.0),
        stencil: Some(0),
        accum: None,
        scissor: None,
        color_mask: [true; 4],
        depth_mask: true,
        stencil_mask: 0xff,
        draw_buffers: Default::default(),
        framebuffer: Default::default(),
    }
}

/// The window's pixels as RGBA8, rows bottom to top.
fn render(renderer: &mut Renderer, frame: &Frame) -> Vec<[u8; 4]> {
    let pixels = renderer.read_pixels(frame, PixelBuffer::Color, [0, 0, SIZE, SIZE]).expect("pixels");
    pixels.iter().map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
}

fn at(pixels: &[[u8; 4]], x: i32, y: i32) -> [u8; 4] {
    pixels[(y * SIZE + x) as usize]
}

fn assert_near(actual: [u8; 4], expected: [u8; 4], what: &str) {
    let close = actual.iter().zip(expected).all(|(&a, e)| a.abs_diff(e) <= 2);
    assert!(close, "{what}: {actual:?}, expected {expected:?}");
}

fn renderer() -> Renderer {
    lavapipe::renderer_with(Renderer::without_outputs)
}

/// A 1×1 RGBA texture of `texel`.
fn texture(id: u32, texel: [u8; 4]) -> TextureRef {
    let image = TexImage { width: 1, height: 1, depth: 1, border: 0, texels: texel.to_vec(), ..TexImage::default() };
    let content = TextureContent { kind: TextureKind::D2, format: TexelFormat::Rgba, faces: vec![vec![Some(Arc::new(image))]], sampler: Sampler::default() };
    TextureRef { id, version: 1, content: Arc::new(content) }
}

#[test]
fn a_fragment_program_reads_its_uniforms_and_sampler_slots_after_the_fixed_function_vertex_stage() {
    let frag = fragment(
        r#"
        layout(set = 1, binding = 1, std430) readonly buffer Uniforms { vec4 tint; } uni;
        layout(set = 1, binding = 2) uniform sampler2D slot0;
        layout(set = 1, binding = 3) uniform sampler2D slot1;      // no texture: (0, 0, 0, 1)
        layout(set = 1, binding = 4) uniform samplerCube slot2;    // no texture: (0, 0, 0, 1)
        layout(location = 0) out vec4 color;
        void main() {
            vec4 none = texture(slot1, vec2(0.5)) + texture(slot2, vec3(1.0, 0.0, 0.0));
            color = vec4((uni.tint * texture(slot0, vec2(0.5))).rgb + none.rgb, none.a * 0.25);
        }
    "#,
    );
    let p = program(1, None, Some(frag), vec![SamplerKind::D2, SamplerKind::D2, SamplerKind::Cube], Vec::new());
    let run = run(&p, builtins(IDENTITY), floats(&[1.0, 0.5, 1.0, 1.0]), vec![Some(texture(5, [128, 255, 64, 255])), None, None]);
    let mut r = renderer();
    let f = frame(vec![rect([8.0, 8.0, 24.0, 24.0], 0.0, [1.0; 4], state(), Some(run))]);
    let pixels = render(&mut r, &f);
    assert_near(at(&pixels, 16, 16), [128, 128, 64, 128], "inside the fixed-function quad");
    assert_near(at(&pixels, 4, 4), [0, 0, 0, 0], "outside");
    assert_eq!(r.raster().program_count(), 1);
}

#[test]
fn a_depth_texture_in_a_sampler_slot_holds_its_depth_in_red_whatever_its_mode() {
    let frag = fragment(
        r#"
        layout(set = 1, binding = 2) uniform sampler2D depth;
        layout(location = 0) out vec4 color;
        void main() { color = vec4(texture(depth, vec2(0.5)).r, 0.0, 0.0, 1.0); }
    "#,
    );
    let p = program(10, None, Some(frag), vec![SamplerKind::D2Shadow], Vec::new());
    let image = TexImage { width: 1, height: 1, depth: 1, border: 0, texels: vec![64, 64, 64, 255], depth_values: vec![0.25], ..TexImage::default() };
    let sampler = Sampler { depth_mode: DepthMode::Alpha, ..Sampler::default() };
    let content = TextureContent { kind: TextureKind::D2, format: TexelFormat::Depth, faces: vec![vec![Some(Arc::new(image))]], sampler };
    let depth = TextureRef { id: 11, version: 1, content: Arc::new(content) };
    let run = run(&p, builtins(IDENTITY), floats(&[0.0]), vec![Some(depth)]);
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![rect([0.0, 0.0, 32.0, 32.0], 0.0, [1.0; 4], state(), Some(run))]));
    assert_near(at(&pixels, 16, 16), [64, 0, 0, 255], "depth 0.25 in red (GL_ALPHA mode puts it in alpha for fixed function)");
}

#[test]
fn a_vertex_program_places_vertices_with_the_builtins_and_reads_generic_attributes() {
    let p = program(2, Some(vertex(PLACE)), Some(fragment(PASS)), Vec::new(), vec![1, 3]);
    // Scales x and y by one half about the window centre.
    let mut half = IDENTITY;
    half[0] = 0.5;
    half[5] = 0.5;
    let run = run(&p, builtins(half), floats(&[1.0]), Vec::new());
    let mut r = renderer();
    let f = frame(vec![rect([0.0, 0.0, 32.0, 32.0], 0.0, [1.0, 0.5, 0.0, 0.5], state(), Some(run))]);
    let pixels = render(&mut r, &f);
    assert_near(at(&pixels, 16, 16), [255, 128, 0, 128], "generic attribute 1, with 3's default w");
    assert_near(at(&pixels, 9, 9), [255, 128, 0, 128], "inside the scaled quad");
    assert_near(at(&pixels, 6, 6), [0, 0, 0, 0], "outside the scaled quad");
    assert_near(at(&pixels, 25, 16), [0, 0, 0, 0], "outside on the right");
}

#[test]
fn points_and_lines_from_a_vertex_program_have_the_shader_size_and_line_width() {
    let p = program(3, Some(vertex(PLACE)), Some(fragment(PASS)), Vec::new(), vec![1, 3]);
    let size5 = run(&p, builtins(IDENTITY), floats(&[5.0]), Vec::new());
    let white = [1.0; 4];
    let point = draw(Topology::Points, vec![ndc(8.5, 24.5, 0.0)], vec![0], white, state(), Some(size5.clone()));
    let wide = RasterState { line: Line { width: 3.0, ..Line::default() }, ..state() };
    let line = draw(Topology::Lines, vec![ndc(4.0, 8.5, 0.0), ndc(28.0, 8.5, 0.0)], vec![0, 1], white, wide, Some(size5.clone()));
    let edges = RasterState { polygon_mode: [PolygonMode::Line; 2], ..state() };
    let triangle = vec![ndc(16.5, 16.5, 0.0), ndc(28.5, 16.5, 0.0), ndc(16.5, 28.5, 0.0)];
    let outline = draw(Topology::Triangles, triangle, vec![0, 1, 2], white, edges, Some(size5));
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![point, line, outline]));
    let lit = |x, y| at(&pixels, x, y)[0] > 200;
    // The 5-pixel point covers columns and rows 6 to 10.
    assert!((6..=10).all(|x| lit(x, 24)) && (22..=26).all(|y| lit(8, y)), "the point is 5 pixels wide");
    assert!(!lit(5, 24) && !lit(11, 24) && !lit(8, 21) && !lit(8, 27), "and no wider");
    // The 3-pixel horizontal line covers rows 7 to 9.
    assert!((7..=9).all(|y| lit(16, y)), "the line is 3 pixels wide");
    assert!(!lit(16, 6) && !lit(16, 10), "and no wider");
    // GL_LINE polygon mode: the edges, not the inside.
    assert!(lit(22, 16) && lit(16, 22), "the triangle's edges are drawn");
    assert!(!lit(19, 19), "the triangle is not filled");
}

#[test]
fn quads_in_line_mode_from_a_vertex_program_show_their_outline_only() {
    let p = program(12, Some(vertex(PLACE)), Some(fragment(PASS)), Vec::new(), vec![1, 3]);
    let run = run(&p, builtins(IDENTITY), floats(&[1.0]), Vec::new());
    let edges = RasterState { polygon_mode: [PolygonMode::Line; 2], ..state() };
    let mut quad = rect([4.5, 4.5, 27.5, 27.5], 0.0, [1.0; 4], edges, Some(run));
    // The quad's two triangles (0, 1, 2) and (0, 2, 3): the diagonal 0–2 is no boundary edge.
    quad.edge_masks = vec![0b011, 0b110];
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![quad]));
    let lit = |x, y| at(&pixels, x, y)[0] > 200;
    assert!(lit(16, 4) && lit(27, 16) && lit(16, 27) && lit(4, 16), "the four sides");
    assert!(!lit(16, 16) && !lit(10, 10), "no diagonal, no fill");
}

#[test]
fn depth_stencil_and_blending_apply_around_program_stages() {
    let p = program(4, Some(vertex(PLACE)), Some(fragment(PASS)), Vec::new(), vec![1, 3]);
    let run = run(&p, builtins(IDENTITY), floats(&[1.0]), Vec::new());
    let always_one = Stencil { func: CompareFunc::Always, reference: 1, value_mask: 0xff, fail: StencilOp::Keep, depth_fail: StencilOp::Keep, depth_pass: StencilOp::Replace, write_mask: 0xff };
    // Red at depth 0.5 marks stencil 1 on the left half.
    let marking = RasterState { depth_test: Some(CompareFunc::Less), stencil: Some(StencilFaces::both(always_one)), ..state() };
    let red = rect([0.0, 0.0, 16.0, 32.0], 0.0, [1.0, 0.0, 0.0, 1.0], marking, Some(run.clone()));
    // Green behind it (depth 0.75) over the whole bottom half: hidden on the left.
    let behind = RasterState { depth_test: Some(CompareFunc::Less), ..state() };
    let green = rect([0.0, 0.0, 32.0, 16.0], 0.5, [0.0, 1.0, 0.0, 1.0], behind, Some(run.clone()));
    // Blue added everywhere stencil is 1.
    let equal_one = Stencil { func: CompareFunc::Equal, depth_pass: StencilOp::Keep, ..always_one };
    let add = Blend { src_rgb: BlendFactor::One, dst_rgb: BlendFactor::One, src_alpha: BlendFactor::One, dst_alpha: BlendFactor::One, ..Blend::default() };
    let adding = RasterState { stencil: Some(StencilFaces::both(equal_one)), blend: Some(add), ..state() };
    let blue = rect([0.0, 0.0, 32.0, 32.0], 0.0, [0.0, 0.0, 1.0, 1.0], adding, Some(run));
    let mut r = renderer();
    let f = frame(vec![red, green, blue]);
    let pixels = render(&mut r, &f);
    assert_near(at(&pixels, 8, 8), [255, 0, 255, 255], "red with blue added, green failed the depth test");
    assert_near(at(&pixels, 8, 24), [255, 0, 255, 255], "red with blue added");
    assert_near(at(&pixels, 24, 8), [0, 255, 0, 255], "green where nothing was nearer; no stencil, no blue");
    assert_near(at(&pixels, 24, 24), [0, 0, 0, 0], "untouched");
    let depth = r.read_pixels(&f, PixelBuffer::Depth, [8, 8, 17, 1]).expect("depth");
    assert!((depth[0][0] - 0.5).abs() < 1e-3 && (depth[16][0] - 0.75).abs() < 1e-3, "depths written by the program draws: {depth:?}");
}

#[test]
fn program_modules_are_freed_when_no_draw_uses_them() {
    let p = program(5, Some(vertex(PLACE)), Some(fragment(PASS)), Vec::new(), vec![1, 3]);
    let run = run(&p, builtins(IDENTITY), floats(&[1.0]), Vec::new());
    let mut r = renderer();
    let mut f = frame(vec![rect([0.0, 0.0, 32.0, 32.0], 0.0, [1.0; 4], state(), Some(run))]);
    r.present(f.clone());
    assert_eq!((r.raster().program_count(), r.raster().pipeline_count()), (1, 1));
    f.draws.clear();
    for number in 1..=12 {
        r.present(Frame { number, ..f.clone() });
    }
    assert_eq!((r.raster().program_count(), r.raster().pipeline_count()), (0, 0), "the program and its pipeline went");
}


/// The executable of GLSL 1.10 `vertex` and `fragment` sources (either may be absent) linked
/// with `color_in` bound to generic attribute 3, numbered `id`, with its link result.
fn link(id: u64, vertex: Option<&str>, fragment: Option<&str>) -> (Arc<ShaderProgram>, LinkedProgram) {
    let shaders: Vec<CompiledShader> = [(Stage::Vertex, vertex), (Stage::Fragment, fragment)]
        .into_iter()
        .filter_map(|(stage, source)| source.map(|s| glsl::compile(stage, s)))
        .inspect(|s| assert!(s.ok, "compile: {}", s.log))
        .collect();
    let bindings = HashMap::from([("color_in".to_string(), 3)]);
    let linked = glsl::link(&shaders.iter().collect::<Vec<_>>(), &bindings);
    assert!(linked.ok, "link: {}", linked.log);
    let executable = ShaderProgram { id, ..linked.executable.clone().expect("an executable") };
    (Arc::new(executable), linked)
}

/// The uniform block of `linked` with the vec4 uniforms `values` set.
fn uniform_block(linked: &LinkedProgram, values: &[(&str, [f32; 4])]) -> Arc<[u8]> {
    let mut bytes = vec![0u8; linked.uniform_block_size as usize];
    for (name, value) in values {
        let uniform = linked.uniforms.iter().find(|u| u.name == *name).unwrap_or_else(|| panic!("uniform {name}"));
        let UniformStorage::Block { offset, .. } = uniform.storage else { panic!("{name} is in the block") };
        let at = offset as usize;
        bytes[at..at + 16].copy_from_slice(&value.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>());
    }
    Arc::from(bytes)
}

/// The sampler slot of the sampler uniform `name`.
fn slot(linked: &LinkedProgram, name: &str) -> usize {
    match linked.uniforms.iter().find(|u| u.name == name).map(|u| u.storage) {
        Some(UniformStorage::Sampler { first_slot }) => first_slot as usize,
        other => panic!("{name}: {other:?}"),
    }
}

/// A program draw of a linked GLSL program (no built-in state is read: zero bytes).
fn glsl_run(program: &Arc<ShaderProgram>, uniforms: Arc<[u8]>, textures: Vec<Option<TextureRef>>) -> Arc<ProgramDraw> {
    run(program, Arc::from(vec![0u8; 16 << 10]), uniforms, textures)
}

#[test]
fn a_glsl_program_with_an_attribute_a_uniform_and_a_sampler_draws() {
    let (p, linked) = link(
        6,
        Some("attribute vec4 color_in; varying vec4 color; void main() { gl_Position = ftransform(); color = color_in; }"),
        Some("uniform vec4 tint; uniform sampler2D tex; varying vec4 color;\nvoid main() { gl_FragColor = color * tint * texture2D(tex, vec2(0.5)); }"),
    );
    assert_eq!(p.attributes, vec![3]);
    let mut textures = vec![None; p.samplers.len()];
    textures[slot(&linked, "tex")] = Some(texture(9, [255, 128, 255, 255]));
    let run = glsl_run(&p, uniform_block(&linked, &[("tint", [1.0, 1.0, 0.5, 1.0])]), textures);
    let mut quad = rect([0.0, 0.0, 32.0, 32.0], 0.0, [1.0; 4], state(), Some(run));
    quad.vertices.generic = vec![Attrib::default(), Attrib::default(), Attrib::default(), Attrib { values: vec![[0.5, 1.0, 1.0, 1.0]] }];
    // ftransform() uses the draw's matrices: x and y scaled by one half.
    quad.modelview = glam::Mat4::from_scale(glam::Vec3::new(0.5, 0.5, 1.0));
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![quad]));
    assert_near(at(&pixels, 16, 16), [128, 128, 128, 255], "attribute × uniform × texture");
    assert_near(at(&pixels, 4, 16), [0, 0, 0, 0], "outside the scaled quad");
}

#[test]
fn a_glsl_fragment_shader_colours_fixed_function_geometry() {
    let (p, linked) = link(7, None, Some("uniform vec4 scale; void main() { gl_FragColor = gl_Color * scale; }"));
    let run = glsl_run(&p, uniform_block(&linked, &[("scale", [0.5, 1.0, 1.0, 1.0])]), Vec::new());
    // The colour reaches the fixed-function vertex stage as gl_Color.
    let quad = rect([8.0, 8.0, 24.0, 24.0], 0.0, [1.0, 0.25, 0.0, 1.0], state(), Some(run));
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![quad]));
    assert_near(at(&pixels, 16, 16), [128, 64, 0, 255], "gl_Color × uniform");
    assert_near(at(&pixels, 4, 4), [0, 0, 0, 0], "outside");
}

#[test]
fn glsl_points_take_the_size_the_vertex_shader_writes() {
    let vs = "void main() { gl_Position = ftransform(); gl_PointSize = 4.0; gl_FrontColor = vec4(0.0, 1.0, 0.0, 1.0); }";
    let (p, _) = link(8, Some(vs), None);
    let run = run(&p, builtins_with_program_point_size(vs), Arc::from(vec![0u8; 16]), Vec::new());
    let point = draw(Topology::Points, vec![ndc(16.0, 16.0, 0.0)], vec![0], [1.0; 4], state(), Some(run));
    let mut r = renderer();
    let pixels = render(&mut r, &frame(vec![point]));
    let lit = |x, y| at(&pixels, x, y) == [0, 255, 0, 255];
    assert!((14..18).all(|x| lit(x, 16)) && (14..18).all(|y| lit(16, y)), "4 pixels across, fixed-function fragment stage");
    assert!(!lit(13, 16) && !lit(18, 16) && !lit(16, 13) && !lit(16, 18), "and no more");
}

/// The built-in state block translate packs for a draw of a program whose vertex shader is
/// `vs`, with `GL_VERTEX_PROGRAM_POINT_SIZE` on (points take the shader's size) and a point
/// size of 1 in the state.
fn builtins_with_program_point_size(vs: &str) -> Arc<[u8]> {
    let (mut ctx, sink) = glrt::translate::Context::with_recording();
    let source = std::ffi::CString::new(vs).unwrap();
    unsafe {
        let shader = dispatch::glCreateShader(&mut ctx, gl::GL_VERTEX_SHADER);
        dispatch::glShaderSource(&mut ctx, shader, 1, &source.as_ptr(), std::ptr::null());
        dispatch::glCompileShader(&mut ctx, shader);
        let program = dispatch::glCreateProgram(&mut ctx);
        dispatch::glAttachShader(&mut ctx, program, shader);
        dispatch::glLinkProgram(&mut ctx, program);
        dispatch::glUseProgram(&mut ctx, program);
        dispatch::glEnable(&mut ctx, gl::GL_VERTEX_PROGRAM_POINT_SIZE);
        dispatch::glBegin(&mut ctx, gl::GL_POINTS);
        dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
        dispatch::glEnd(&mut ctx);
        assert_eq!(dispatch::glGetError(&mut ctx), gl::GL_NO_ERROR);
    }
    ctx.end_frame();
    let frames = sink.frames.lock();
    frames[0].draws[0].program.as_ref().expect("the draw runs the program").builtins.clone()
}
