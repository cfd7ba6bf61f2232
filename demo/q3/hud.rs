//! The HUD, laid out as Quake 3's status bar on a virtual 640 × 480 screen scaled to the
//! window (`cg_draw.c`): first the 3D icons (`CG_Draw3DModel`: a head and the armour, each a
//! scene of its own without the world (`RDF_NOWORLDMODEL`), in its own viewport, with the depth
//! buffer cleared inside it), then the 2D pictures: health, armour and ammo numbers in big
//! characters, the crosshair, and the frame number at the top right with a drop shadow
//! (`CG_DrawStringExt`), all from the character set texture through `RB_StretchPic`.

use glam::{Mat3, Vec3};

use super::back_end::{Backend, EntityKind, RefEntity, Scene, SurfaceRef, ViewParms, DrawSurf};
use super::light_grid::EntityLight;
use super::lights::sun_direction;
use super::script::axis;
use super::shaders::{ShaderId, Shaders};

/// The virtual screen.
const VIRTUAL: [f32; 2] = [640.0, 480.0];
/// Q3's status bar: icon size, big number size, the bar's top.
const ICON_SIZE: f32 = 48.0;
const CHAR_WIDTH: f32 = 32.0;
const CHAR_HEIGHT: f32 = 48.0;
const BAR_Y: f32 = 432.0;
const BIGCHAR: f32 = 16.0;
/// Number colour (Q3's `colors[0]`, full health).
const NUMBER_COLOUR: [u8; 4] = [255, 176, 0, 255];

/// The HUD's shaders and models.
pub struct Hud {
    pub charset: ShaderId,
    pub crosshair: ShaderId,
    pub head_skin: ShaderId,
    pub armour_skin: ShaderId,
    pub head_model: usize,
    pub armour_model: usize,
}

/// The values shown.
pub const HEALTH: u32 = 100;
pub const ARMOUR: u32 = 50;
pub const AMMO: u32 = 25;

/// The icons' places on the virtual screen: (x, y, model, skin, distance, yaw in degrees).
fn icons(hud: &Hud, time: f32) -> [(f32, f32, usize, ShaderId, f32, f32); 2] {
    [
        // CG_DrawHead: facing the viewer, swinging 20° either way.
        (185.0 + 3.0 * CHAR_WIDTH + 4.0, BAR_Y, hud.head_model, hud.head_skin, 10.0 / 0.268, 180.0 + 20.0 * time.sin()),
        // The armour model, spinning as items do.
        (370.0 + 3.0 * CHAR_WIDTH + 4.0, BAR_Y, hud.armour_model, hud.armour_skin, 80.0, (time * 176.0) % 360.0),
    ]
}

/// Pixels per virtual unit, horizontally and vertically.
fn scale(screen: [i32; 2]) -> [f32; 2] {
    [screen[0] as f32 / VIRTUAL[0], screen[1] as f32 / VIRTUAL[1]]
}

/// The pixel viewport (GL's, from the bottom) of an icon at virtual (`x`, `y`).
fn icon_viewport(screen: [i32; 2], x: f32, y: f32) -> [i32; 4] {
    let [sx, sy] = scale(screen);
    let (w, h) = ((ICON_SIZE * sx).round() as i32, (ICON_SIZE * sy).round() as i32);
    [(x * sx).round() as i32, screen[1] - (y * sy).round() as i32 - h, w, h]
}

impl Hud {
    /// Draws the 3D icons, each as its own view (fov 30 × 30, near 4, far 2048).
    pub fn draw_icons(&self, b: &mut Backend, scene: &Scene, shaders: &Shaders) {
        for (x, y, model, skin, distance, yaw) in icons(self, b.time) {
            let viewport = icon_viewport(b.screen, x, y);
            let view = ViewParms::new(Vec3::ZERO, Mat3::IDENTITY, [30.0; 2], viewport, 2048.0);
            let entity_axis = axis(yaw, 0.0);
            let entity = RefEntity {
                kind: EntityKind::Model { model, frame: 0, old_frame: 0, backlerp: 0.0 },
                origin: Vec3::new(distance, 0.0, 0.0),
                axis: entity_axis,
                shader: skin,
                light: EntityLight::without_world(&entity_axis, sun_direction()),
                depth_hack: false,
            };
            let entities = [entity];
            let icon = Scene { level: scene.level, models: scene.models, entities: &entities, dlights: &[] };
            b.render_view(view, &[DrawSurf::new(shaders, skin, 0, false, SurfaceRef::Entity(0))], &icon);
        }
    }

    /// Draws `text` at virtual (x, y) with characters `w` × `h` in `rgba`.
    fn string(&self, b: &mut Backend, x: f32, y: f32, [w, h]: [f32; 2], text: &str, rgba: [u8; 4]) {
        let [sx, sy] = scale(b.screen);
        for (i, c) in text.bytes().enumerate() {
            if c == b' ' {
                continue;
            }
            let (col, row) = (f32::from(c & 15) * 0.0625, f32::from(c >> 4) * 0.0625);
            let rect = [(x + i as f32 * w) * sx, y * sy, w * sx, h * sy];
            b.stretch_pic(rect, [col, row, col + 0.0625, row + 0.0625], self.charset, rgba);
        }
    }

    /// Draws the 2D part: numbers, crosshair, frame number.
    pub fn draw_2d(&self, b: &mut Backend, frame: u64) {
        for (x, value) in [(0.0, AMMO), (185.0, HEALTH), (370.0, ARMOUR)] {
            // CG_DrawField: right-aligned in 3 characters.
            let text = format!("{value:>3}");
            self.string(b, x + 2.0, BAR_Y, [CHAR_WIDTH, CHAR_HEIGHT], &text, NUMBER_COLOUR);
        }
        let [sx, sy] = scale(b.screen);
        let size = 24.0;
        b.stretch_pic([(320.0 - size / 2.0) * sx, (240.0 - size / 2.0) * sy, size * sx, size * sy], [0.0, 0.0, 1.0, 1.0], self.crosshair, [255; 4]);
        let text = format!("FRAME {:05}", frame % 100_000);
        let x = 635.0 - text.len() as f32 * BIGCHAR;
        self.string(b, x + 2.0, 4.0, [BIGCHAR; 2], &text, [0, 0, 0, 255]);
        self.string(b, x, 2.0, [BIGCHAR; 2], &text, [255; 4]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn icons_sit_in_the_status_bar() {
        assert_eq!(icon_viewport([640, 480], 285.0, BAR_Y), [285, 0, 48, 48]);
        assert_eq!(icon_viewport([320, 240], 285.0, BAR_Y), [143, 0, 24, 24]);
        let [x, y, w, h] = icon_viewport([320, 240], 470.0, BAR_Y);
        assert_eq!((x, y, w, h), (235, 0, 24, 24));
    }
}
