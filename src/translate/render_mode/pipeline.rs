//! The CPU geometry pipeline of selection and feedback (OpenGL 1.5 sections 2.11 to 2.14,
//! 3.5.4 and 3.5.5 as far as they decide what reaches rasterization): transformation to eye and
//! clip coordinates, clipping against the view volume and the user clip planes (section
//! 2.12), perspective division, the viewport, then polygon culling and polygon mode. What comes
//! out is the list of [`Shape`]s the rasterizer would have drawn, in window coordinates.

use glam::{Mat4, Vec4};

use crate::translate::gl::{self, GLenum};
use crate::translate::viewport::ViewportState;

/// One vertex as the vertex pipeline assembled it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CpuVertex {
    /// Object-space position (x, y, z, w).
    pub position: [f32; 4],
    /// The vertex colour, lit when lighting is enabled (see the module doc of [`super`]); the
    /// colour of points, lines and front-facing polygons.
    pub color: [f32; 4],
    /// The colour of back-facing polygons: the back face's lit colour with two-sided lighting
    /// (section 2.14.1), otherwise equal to `color`.
    pub back_color: [f32; 4],
    /// Texture coordinates of unit 0 as issued (or generated); the texture matrix of unit 0 is
    /// applied here.
    pub texcoord: [f32; 4],
    /// The edge flag (`glEdgeFlag`); only polygons, independent triangles and quads use it.
    pub edge_flag: bool,
}

/// A primitive handed to selection or feedback: one `glBegin`/`glEnd` (or array draw) of
/// `mode` (`GL_POINTS` … `GL_POLYGON`), its vertices in order. Incomplete trailing vertices
/// are ignored as section 2.6.1 says.
#[derive(Clone, Copy, Debug)]
pub struct CpuPrimitive<'a> {
    /// `GL_POINTS`, `GL_LINES`, `GL_LINE_STRIP`, `GL_LINE_LOOP`, `GL_TRIANGLES`,
    /// `GL_TRIANGLE_STRIP`, `GL_TRIANGLE_FAN`, `GL_QUADS`, `GL_QUAD_STRIP` or `GL_POLYGON`.
    pub mode: GLenum,
    /// The vertices.
    pub vertices: &'a [CpuVertex],
}

/// Rasterization state that decides what feedback and selection see (section 3.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterRules {
    /// `glCullFace` mode when `GL_CULL_FACE` is enabled, `None` when it is disabled.
    pub cull: Option<GLenum>,
    /// `glFrontFace`: `GL_CCW` or `GL_CW`.
    pub front_face: GLenum,
    /// `glPolygonMode` of front and back faces: `GL_POINT`, `GL_LINE` or `GL_FILL`.
    pub mode: [GLenum; 2],
    /// `glShadeModel(GL_FLAT)`: each line and polygon takes its provoking vertex's colour.
    pub flat_shading: bool,
}

impl Default for RasterRules {
    /// The initial state: no culling, counter-clockwise front faces, both faces filled,
    /// smooth shading.
    fn default() -> RasterRules {
        RasterRules { cull: None, front_face: gl::GL_CCW, mode: [gl::GL_FILL; 2], flat_shading: false }
    }
}

/// The transformations and clip planes a primitive goes through.
#[derive(Clone, Copy, Debug)]
pub struct Transforms<'a> {
    /// Modelview matrix.
    pub modelview: Mat4,
    /// Projection matrix.
    pub projection: Mat4,
    /// Texture matrix of unit 0.
    pub texture: Mat4,
    /// Viewport and depth range.
    pub viewport: &'a ViewportState,
    /// Enabled user clip planes, in eye coordinates.
    pub clip_planes: &'a [[f32; 4]],
}

/// A vertex in window coordinates with its attributes, as feedback reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindowVertex {
    /// Window x, y, z and the clip-coordinate w (section 5.3).
    pub window: [f32; 4],
    /// Colour.
    pub color: [f32; 4],
    /// Texture coordinates of unit 0 after the texture matrix.
    pub texcoord: [f32; 4],
}

/// What rasterization would draw.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A point.
    Point(WindowVertex),
    /// A line segment; `reset` when the line stipple restarts with it (`GL_LINE_RESET_TOKEN`).
    Line { ends: [WindowVertex; 2], reset: bool },
    /// A filled polygon (at least three vertices).
    Polygon(Vec<WindowVertex>),
}

/// One point, segment or polygon of a primitive, by vertex index (section 2.6.1).
enum Part {
    Point(usize),
    /// A segment, whether it restarts the line stipple, and its provoking vertex.
    Line { ends: [usize; 2], reset: bool, provoking: usize },
    /// Corners with the edge flag of the edge each starts, and the provoking vertex.
    Polygon { corners: Vec<(usize, bool)>, provoking: usize },
}

/// Splits a primitive into points, segments and polygons. Edge flags count only for
/// independent triangles, quads and polygons (section 2.6.2); elsewhere every edge is a
/// boundary. Odd triangles of a strip are reordered so all keep the strip's orientation.
fn assemble(prim: &CpuPrimitive) -> Vec<Part> {
    let n = prim.vertices.len();
    let flag = |k: usize| prim.vertices[k].edge_flag;
    let line = |a: usize, b: usize, reset: bool, provoking: usize| Part::Line { ends: [a, b], reset, provoking };
    let flagged = |idx: &[usize]| Part::Polygon { corners: idx.iter().map(|&k| (k, flag(k))).collect(), provoking: idx[idx.len() - 1] };
    let plain = |idx: &[usize], provoking: usize| Part::Polygon { corners: idx.iter().map(|&k| (k, true)).collect(), provoking };
    match prim.mode {
        gl::GL_POINTS => (0..n).map(Part::Point).collect(),
        gl::GL_LINES => (0..n / 2).map(|i| line(2 * i, 2 * i + 1, true, 2 * i + 1)).collect(),
        gl::GL_LINE_STRIP | gl::GL_LINE_LOOP if n >= 2 => {
            let mut parts: Vec<Part> = (0..n - 1).map(|i| line(i, i + 1, i == 0, i + 1)).collect();
            if prim.mode == gl::GL_LINE_LOOP {
                parts.push(line(n - 1, 0, false, 0));
            }
            parts
        }
        gl::GL_TRIANGLES => (0..n / 3).map(|i| flagged(&[3 * i, 3 * i + 1, 3 * i + 2])).collect(),
        gl::GL_TRIANGLE_STRIP => (0..n.saturating_sub(2))
            .map(|i| plain(&if i % 2 == 0 { [i, i + 1, i + 2] } else { [i + 1, i, i + 2] }, i + 2))
            .collect(),
        gl::GL_TRIANGLE_FAN => (1..n.saturating_sub(1)).map(|i| plain(&[0, i, i + 1], i + 1)).collect(),
        gl::GL_QUADS => (0..n / 4).map(|i| flagged(&[4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3])).collect(),
        gl::GL_QUAD_STRIP => (0..(n / 2).saturating_sub(1))
            .map(|i| plain(&[2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2], 2 * i + 3))
            .collect(),
        gl::GL_POLYGON if n >= 3 => {
            vec![Part::Polygon { corners: (0..n).map(|k| (k, flag(k))).collect(), provoking: 0 }]
        }
        _ => Vec::new(),
    }
}

/// A vertex during clipping: clip and eye coordinates plus the attributes to interpolate.
#[derive(Clone, Copy, Debug)]
struct ClipVertex {
    clip: Vec4,
    eye: Vec4,
    color: Vec4,
    back_color: Vec4,
    texcoord: Vec4,
}

impl ClipVertex {
    fn lerp(&self, other: &ClipVertex, t: f32) -> ClipVertex {
        ClipVertex {
            clip: self.clip.lerp(other.clip, t),
            eye: self.eye.lerp(other.eye, t),
            color: self.color.lerp(other.color, t),
            back_color: self.back_color.lerp(other.back_color, t),
            texcoord: self.texcoord.lerp(other.texcoord, t),
        }
    }
}

/// Signed distance of `v` to clip plane `plane`: 0..6 are the view-volume planes
/// (−w ≤ x, y, z ≤ w), then the user planes; non-negative is inside.
fn distance(v: &ClipVertex, plane: usize, user: &[[f32; 4]]) -> f32 {
    let c = v.clip;
    match plane {
        0 => c.w + c.x,
        1 => c.w - c.x,
        2 => c.w + c.y,
        3 => c.w - c.y,
        4 => c.w + c.z,
        5 => c.w - c.z,
        _ => Vec4::from_array(user[plane - 6]).dot(v.eye),
    }
}

/// Clips a segment (section 2.12); `None` when nothing is left.
fn clip_line(a: ClipVertex, b: ClipVertex, user: &[[f32; 4]]) -> Option<[ClipVertex; 2]> {
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for plane in 0..6 + user.len() {
        let (da, db) = (distance(&a, plane, user), distance(&b, plane, user));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        if da < 0.0 {
            t0 = t0.max(da / (da - db));
        } else if db < 0.0 {
            t1 = t1.min(da / (da - db));
        }
    }
    (t0 <= t1).then(|| [a.lerp(&b, t0), a.lerp(&b, t1)])
}

/// Clips a polygon (Sutherland–Hodgman). Each vertex carries the edge flag of the edge that
/// starts at it; edges created along a clip plane are not boundary edges.
fn clip_polygon(mut poly: Vec<(ClipVertex, bool)>, user: &[[f32; 4]]) -> Vec<(ClipVertex, bool)> {
    for plane in 0..6 + user.len() {
        if poly.is_empty() {
            break;
        }
        let mut out = Vec::with_capacity(poly.len() + 2);
        for (i, &(a, flag)) in poly.iter().enumerate() {
            let (b, _) = poly[(i + 1) % poly.len()];
            let (da, db) = (distance(&a, plane, user), distance(&b, plane, user));
            if da >= 0.0 {
                out.push((a, flag));
                if db < 0.0 {
                    out.push((a.lerp(&b, da / (da - db)), false));
                }
            } else if db >= 0.0 {
                out.push((a.lerp(&b, da / (da - db)), flag));
            }
        }
        poly = out;
    }
    poly
}

impl Transforms<'_> {
    fn clip_vertex(&self, v: &CpuVertex) -> ClipVertex {
        let eye = self.modelview * Vec4::from_array(v.position);
        ClipVertex {
            clip: self.projection * eye,
            eye,
            color: Vec4::from_array(v.color),
            back_color: Vec4::from_array(v.back_color),
            texcoord: self.texture * Vec4::from_array(v.texcoord),
        }
    }

    /// Perspective division and viewport (equations 2.12, 2.13).
    fn window_vertex(&self, v: &ClipVertex) -> WindowVertex {
        let c = v.clip;
        let w = if c.w == 0.0 { f32::MIN_POSITIVE } else { c.w };
        let [x, y, z] = self.viewport.to_window([c.x / w, c.y / w, c.z / w]);
        WindowVertex { window: [x, y, z, c.w], color: v.color.to_array(), texcoord: v.texcoord.to_array() }
    }

    /// Runs `prim` through the pipeline and returns what rasterization would draw.
    pub fn shapes(&self, prim: &CpuPrimitive, rules: &RasterRules) -> Vec<Shape> {
        let v: Vec<ClipVertex> = prim.vertices.iter().map(|x| self.clip_vertex(x)).collect();
        // With flat shading every vertex takes the provoking vertex's colours (table 2.8).
        let vertex = |k: usize, provoking: usize| {
            let source = if rules.flat_shading { v[provoking] } else { v[k] };
            ClipVertex { color: source.color, back_color: source.back_color, ..v[k] }
        };
        let mut out = Vec::new();
        for part in assemble(prim) {
            match part {
                Part::Point(k) => {
                    let p = v[k];
                    if (0..6 + self.clip_planes.len()).all(|plane| distance(&p, plane, self.clip_planes) >= 0.0) {
                        out.push(Shape::Point(self.window_vertex(&p)));
                    }
                }
                Part::Line { ends: [a, b], reset, provoking } => {
                    if let Some([a, b]) = clip_line(vertex(a, provoking), vertex(b, provoking), self.clip_planes) {
                        out.push(Shape::Line { ends: [self.window_vertex(&a), self.window_vertex(&b)], reset });
                    }
                }
                Part::Polygon { corners, provoking } => {
                    let poly = corners.iter().map(|&(k, flag)| (vertex(k, provoking), flag)).collect();
                    self.polygon(&mut out, rules, poly);
                }
            }
        }
        out
    }

    /// Clips one polygon, then applies culling and the polygon mode (sections 3.5.1, 3.5.4).
    /// The window-space facing also picks the front or back colours (section 2.14.1).
    fn polygon(&self, out: &mut Vec<Shape>, rules: &RasterRules, poly: Vec<(ClipVertex, bool)>) {
        let clipped = clip_polygon(poly, self.clip_planes);
        if clipped.len() < 3 {
            return;
        }
        let mut win: Vec<WindowVertex> = clipped.iter().map(|(v, _)| self.window_vertex(v)).collect();
        let area: f32 = (0..win.len())
            .map(|i| {
                let (a, b) = (win[i].window, win[(i + 1) % win.len()].window);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum();
        let front = if rules.front_face == gl::GL_CW { area < 0.0 } else { area > 0.0 };
        let culled = match rules.cull {
            Some(gl::GL_FRONT) => front,
            Some(gl::GL_BACK) => !front,
            Some(gl::GL_FRONT_AND_BACK) => true,
            _ => false,
        };
        if culled {
            return;
        }
        if !front {
            for (w, (v, _)) in win.iter_mut().zip(&clipped) {
                w.color = v.back_color.to_array();
            }
        }
        let flags = clipped.iter().map(|(_, f)| *f);
        match rules.mode[usize::from(!front)] {
            gl::GL_POINT => out.extend(win.iter().zip(flags).filter(|(_, f)| *f).map(|(w, _)| Shape::Point(*w))),
            gl::GL_LINE => out.extend(
                flags
                    .enumerate()
                    .filter(|(_, f)| *f)
                    .map(|(i, _)| Shape::Line { ends: [win[i], win[(i + 1) % win.len()]], reset: true }),
            ),
            _ => out.push(Shape::Polygon(win)),
        }
    }
}
