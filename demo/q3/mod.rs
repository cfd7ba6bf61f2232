//! `--q3`: a small level drawn exactly as ioquake3's OpenGL 1 renderer draws one, GL call for
//! GL call in its patterns (`tr_backend.c`, `tr_shade.c`, `tr_surface.c`, `tr_sky.c`), so that
//! captures of it stand in for a Quake-3-class game in tests and benchmarks.
//!
//! At start-up the level ([`level`]) is cut into surfaces, its lightmaps are baked from point
//! lights, the sun and the sky with traced occlusion and packed into 128 × 128 pages
//! ([`lightmaps`]), a light grid is baked for the models ([`light_grid`]), the images are made
//! ([`images`]) and the shaders registered ([`shaders`]). Each frame, with a fixed time step
//! and no randomness ([`script`]):
//! 1. the view of the level: the sky box first (depth range 1..1, no depth writes) when the
//!    courtyard's opening is in view; the visible surfaces sorted by shader and batched into
//!    client arrays drawn inside `glLockArraysEXT` with `glDrawElements`: floors and concrete as
//!    base × lightmap on two texture units (`glActiveTextureARB`/`glClientActiveTextureARB`,
//!    `GL_MODULATE`), brick walls the same plus a detail pass (`GL_DST_COLOR, GL_SRC_COLOR`),
//!    metal walls as a base pass plus a lightmap pass (`GL_DST_COLOR, GL_ZERO`, `GL_EQUAL`
//!    depth, no depth writes), light panels plus an additive glow pass (`GL_ONE, GL_ONE`), and
//!    an additive dynamic-light pass (`GL_ONE, GL_ONE`, `GL_EQUAL`) of a radial texture over
//!    the surfaces near the flying rocket; two walking players, the spinning armour and the
//!    rocket as models whose vertices are blended on the CPU and whose vertex colours come
//!    from the light grid; the view weapon in depth range 0..0.3; then the blended shaders:
//!    the water (alpha), the armour's additive shell, the smoke puffs (alpha sprites) and the
//!    rocket's flame (an additive sprite);
//! 2. the HUD ([`hud`]): a head and the armour as 3D icons in their own viewports after a
//!    depth clear, then numbers, crosshair and text in 2D.
//!
//! GL errors are checked at the start of every frame (`RE_BeginFrame`); one is fatal.

mod back_end;
mod front_end;
mod gl_state;
mod hud;
mod images;
mod level;
mod light_grid;
mod lightmaps;
mod lights;
mod models;
mod script;
mod shade;
mod shaders;
mod sky;
mod tess;

use glam::{Mat3, Vec3};

use crate::gl::*;
use back_end::{Backend, Counts, EntityKind, RefEntity, Scene, ViewParms};
use gl_state::{Api, GlState};
use images::{CLAMPED, Images, WORLD};
use level::{Level, Material};
use light_grid::{Dlight, LightGrid};
use shaders::{AlphaGen, Bundle, Cull, RgbGen, Script, ShaderId, Shaders, Sort, Stage, StateBits, TcMod};
use tess::Tess;

/// Horizontal field of view of the main view (Q3's default `cg_fov`).
const FOV_X: f32 = 90.0;
/// Far plane (Q3 fits it to the visible bounds each frame; fixed here).
const Z_FAR: f32 = 4096.0;
/// The rocket's dynamic light (Q3's rocket: radius 200, orange).
const ROCKET_LIGHT: (f32, Vec3) = (200.0, Vec3::new(1.0, 0.75, 0.0));

/// Indexes of the models.
const PLAYER: usize = 0;
const ARMOUR: usize = 1;
const HEAD: usize = 2;
const ROCKET: usize = 3;
const WEAPON: usize = 4;

/// Shaders of the entities.
struct EntityShaders {
    players: [ShaderId; 2],
    armour: ShaderId,
    shell: ShaderId,
    rocket: ShaderId,
    weapon: ShaderId,
    smoke: ShaderId,
    flame: ShaderId,
}

/// Everything `--q3` keeps between frames.
pub struct Q3 {
    mt: Multitexture,
    lock: LockArrays,
    images: Images,
    shaders: Shaders,
    level: Level,
    /// The shader of each level surface.
    shader_of: Vec<ShaderId>,
    grid: LightGrid,
    models: Vec<models::Mesh>,
    entity_shaders: EntityShaders,
    hud: hud::Hud,
    dlight_image: GLuint,
    state: GlState,
    tess: Tess,
    screen: [i32; 2],
    verbose: bool,
}

/// The world shader of `material` with lightmap page `lightmap`.
fn world_script(material: Material, lightmap: GLuint, images: &WorldImages) -> Script {
    let detail = Stage::new(Bundle::map(images.detail).with(TcMod::Scale(4.0, 4.0)), RgbGen::Identity, AlphaGen::Identity, StateBits::DETAIL);
    let glow = Stage::new(Bundle::map(images.glow), RgbGen::Wave { base: 0.85, amplitude: 0.15, frequency: 0.5 }, AlphaGen::Identity, StateBits::ADD);
    let lightmap_pass = Stage { state: StateBits::FILTER.equal(), ..Stage::lightmap(lightmap) };
    match material {
        Material::Floor => Script::opaque("textures/q3demo/floor", vec![Stage::base(images.floor), Stage::lightmap(lightmap)]),
        Material::Concrete => Script::opaque("textures/q3demo/concrete", vec![Stage::base(images.concrete), Stage::lightmap(lightmap)]),
        Material::Brick => Script::opaque("textures/q3demo/brick", vec![Stage::base(images.brick), Stage::lightmap(lightmap), detail]),
        Material::Metal => Script::opaque("textures/q3demo/metal", vec![Stage::base(images.metal), lightmap_pass]),
        Material::Panel => Script::opaque("textures/q3demo/light", vec![Stage::base(images.panel), Stage::lightmap(lightmap), glow]),
        Material::Water => Script::blended(
            "textures/q3demo/water",
            Cull::TwoSided,
            vec![Stage::new(Bundle::map(images.water).with(TcMod::Scroll(0.05, 0.03)), RgbGen::Identity, AlphaGen::Const(150), StateBits::BLEND)],
        ),
        Material::Sky => Script {
            sort: Sort::Environment,
            sky: Some(images.sky),
            ..Script::opaque("textures/q3demo/sky", vec![Stage::new(Bundle::map(images.clouds).with(TcMod::Scroll(0.02, 0.01)), RgbGen::Identity, AlphaGen::Identity, StateBits::ADD)])
        },
    }
}

/// The world's images.
struct WorldImages {
    floor: GLuint,
    brick: GLuint,
    metal: GLuint,
    concrete: GLuint,
    panel: GLuint,
    glow: GLuint,
    detail: GLuint,
    water: GLuint,
    sky: [GLuint; 6],
    clouds: GLuint,
}

impl Q3 {
    /// Bakes the level's light, uploads the images and sets Q3's default state; needs
    /// `GL_ARB_multitexture` and `GL_EXT_compiled_vertex_array` (as Q3's renderer would use).
    pub fn new(api: &GlApi, width: i32, height: i32, verbose: bool) -> Result<Q3, String> {
        let (Some(mt), Some(lock)) = (api.multitexture, api.lock_arrays) else {
            return Err("--q3 needs GL_ARB_multitexture and GL_EXT_compiled_vertex_array".into());
        };
        let gl = &api.gl;
        let start = std::time::Instant::now();
        let mut level = Level::new();
        let pages = lightmaps::bake(&mut level);
        let grid = LightGrid::bake(&level);
        let baked = start.elapsed();
        let mut images = Images::default();
        let world = WorldImages {
            floor: images.create(gl, &images::floor_tiles(), WORLD),
            brick: images.create(gl, &images::bricks(), WORLD),
            metal: images.create(gl, &images::metal(), WORLD),
            concrete: images.create(gl, &images::concrete(), WORLD),
            panel: images.create(gl, &images::panel(), WORLD),
            glow: images.create(gl, &images::glow(), WORLD),
            detail: images.create(gl, &images::detail(), WORLD),
            water: images.create(gl, &images::water(), WORLD),
            sky: std::array::from_fn(|side| images.create(gl, &images::sky_side(side), CLAMPED)),
            clouds: images.create(gl, &images::clouds(), WORLD),
        };
        let lightmap_pages = lightmaps::upload(gl, &mut images, &pages);
        let mut shaders = Shaders::default();
        // World shaders are registered as the level's surfaces name them, one per lightmap page.
        let mut registered: Vec<((Material, usize), ShaderId)> = Vec::new();
        let shader_of = level
            .surfaces
            .iter()
            .map(|s| {
                let key = (s.material, if s.material.lightmapped() { s.lightmap_page } else { 0 });
                if let Some(&(_, id)) = registered.iter().find(|(k, _)| *k == key) {
                    return id;
                }
                let id = shaders.register(world_script(s.material, lightmap_pages.get(key.1).copied().unwrap_or(0), &world));
                registered.push((key, id));
                id
            })
            .collect();
        let skin = |shaders: &mut Shaders, images: &mut Images, name, image: &images::Rgba| {
            let image = images.create(gl, image, WORLD);
            shaders.register(Script::vertex_lit(name, image))
        };
        let players = [
            skin(&mut shaders, &mut images, "models/players/red", &images::suit([200, 40, 30])),
            skin(&mut shaders, &mut images, "models/players/blue", &images::suit([40, 70, 210])),
        ];
        let armour = skin(&mut shaders, &mut images, "models/powerups/armor", &images::armour());
        let head_skin = skin(&mut shaders, &mut images, "models/players/head", &images::face());
        let metal = images.create(gl, &images::gunmetal(), WORLD);
        let rocket = shaders.register(Script::vertex_lit("models/ammo/rocket", metal));
        let weapon = shaders.register(Script::vertex_lit("models/weapons/rocketl", metal));
        let shell_image = images.create(gl, &images::shell(), WORLD);
        let shell = shaders.register(Script {
            deform: Some(shaders::Deform { base: 2.0, amplitude: 1.0, frequency: 1.0 }),
            ..Script::blended("powerups/regen", Cull::FrontSided, vec![Stage::new(Bundle::map(shell_image).with(TcMod::Scroll(0.0, 0.5)), RgbGen::Identity, AlphaGen::Identity, StateBits::ADD)])
        });
        let sprite = |image, state| vec![Stage::new(Bundle::map(image), RgbGen::Vertex, AlphaGen::Vertex, state)];
        let smoke_image = images.create(gl, &images::smoke(), CLAMPED);
        let smoke = shaders.register(Script { entity_mergable: true, ..Script::blended("smokePuff", Cull::TwoSided, sprite(smoke_image, StateBits::BLEND)) });
        let flame_image = images.create(gl, &images::flare(), CLAMPED);
        let flame = shaders.register(Script::blended("rocketFlare", Cull::TwoSided, sprite(flame_image, StateBits::ADD)));
        let picture = |shaders: &mut Shaders, images: &mut Images, name, image: &images::Rgba| {
            let image = images.create(gl, image, CLAMPED);
            shaders.register(Script::blended(name, Cull::TwoSided, sprite(image, StateBits::PICTURE)))
        };
        let charset = picture(&mut shaders, &mut images, "gfx/2d/bigchars", &images::charset());
        let crosshair = picture(&mut shaders, &mut images, "gfx/2d/crosshaira", &images::crosshair());
        let dlight_image = images.create(gl, &images::dlight(), CLAMPED);
        let models = vec![models::player(), models::armour(), models::head(), models::rocket(), models::weapon()];
        let api_now = Api { gl, mt: &mt, lock: &lock };
        let state = GlState::set_default(api_now);
        if verbose {
            let triangles: usize = level.surfaces.iter().map(|s| s.indexes.len() / 3).sum();
            println!(
                "q3: {} surfaces, {triangles} triangles, {} lightmap pages, light baked in {} ms",
                level.surfaces.len(),
                pages.len(),
                baked.as_millis()
            );
            for s in shaders.iter() {
                println!("q3 shader {}: {:?}, {} stages{}", s.name, s.iterator, s.stages.len(), if s.multitexture { ", lightmap on unit 1" } else { "" });
            }
        }
        Ok(Q3 {
            mt,
            lock,
            images,
            shaders,
            level,
            shader_of,
            grid,
            models,
            entity_shaders: EntityShaders { players, armour, shell, rocket, weapon, smoke, flame },
            hud: hud::Hud { charset, crosshair, head_skin, armour_skin: armour, head_model: HEAD, armour_model: ARMOUR },
            dlight_image,
            state,
            tess: Tess::new(),
            screen: [width, height],
            verbose,
        })
    }

    /// The entities of frame `m` (`CG_AddPacketEntities`, local entities, the view weapon).
    fn entities(&self, m: &script::Moment, dlights: &[Dlight]) -> Vec<RefEntity> {
        let s = &self.entity_shaders;
        let model = |model, frame, old_frame, backlerp| EntityKind::Model { model, frame, old_frame, backlerp };
        let lit = |kind, origin: Vec3, axis: Mat3, shader, depth_hack| RefEntity { kind, origin, axis, shader, light: self.grid.entity_light(origin, &axis, dlights), depth_hack };
        let mut out = Vec::new();
        for (p, &shader) in m.players.iter().zip(&s.players) {
            out.push(lit(model(PLAYER, p.frame, p.old_frame, p.backlerp), p.origin, script::axis(p.yaw, 0.0), shader, false));
        }
        let armour_axis = script::axis(m.armour_yaw, 0.0);
        out.push(lit(model(ARMOUR, 0, 0, 0.0), m.armour_origin, armour_axis, s.armour, false));
        out.push(lit(model(ARMOUR, 0, 0, 0.0), m.armour_origin, armour_axis, s.shell, false));
        if let Some((origin, direction)) = m.rocket {
            let yaw = direction.y.atan2(direction.x).to_degrees();
            let pitch = direction.z.asin().to_degrees();
            out.push(lit(model(ROCKET, 0, 0, 0.0), origin, script::axis(yaw, pitch), s.rocket, false));
            let sprite = EntityKind::Sprite { radius: 16.0, rgba: [255; 4] };
            out.push(lit(sprite, origin - direction * 18.0, Mat3::IDENTITY, s.flame, false));
        }
        for puff in &m.puffs {
            let rgba = [255, 255, 255, (puff.alpha * 255.0) as u8];
            out.push(lit(EntityKind::Sprite { radius: puff.radius, rgba }, puff.origin, Mat3::IDENTITY, s.smoke, false));
        }
        out.push(lit(model(WEAPON, 0, 0, 0.0), m.eye, m.view_axis, s.weapon, true));
        out
    }

    /// Draws frame `frame` (without presenting it); fails on a GL error.
    pub fn draw(&mut self, gl: &Gl, frame: u64) -> Result<(), String> {
        // Safety: a context is current.
        let error = unsafe { gl.glGetError() };
        if error != GL_NO_ERROR {
            return Err(format!("frame {frame}: glGetError() = 0x{error:04x}"));
        }
        // Safety: a context is current.
        unsafe { gl.glDrawBuffer(GL_BACK) };
        let m = script::moment(frame);
        let dlights: Vec<Dlight> = m.rocket.iter().map(|&(origin, _)| Dlight { origin, radius: ROCKET_LIGHT.0, colour: ROCKET_LIGHT.1 }).collect();
        let entities = self.entities(&m, &dlights);
        let [w, h] = self.screen;
        let view = ViewParms::new(m.eye, m.view_axis, [FOV_X, back_end::fov_y(FOV_X, w, h)], [0, 0, w, h], Z_FAR);
        let mut surfaces = front_end::world_surfaces(&self.level, &self.shader_of, &self.shaders, &view, &dlights);
        surfaces.extend(front_end::entity_surfaces(&entities, &self.shaders, &view));
        front_end::sort(&mut surfaces);
        let scene = Scene { level: &self.level, models: &self.models, entities: &entities, dlights: &dlights };
        let mut backend = Backend {
            api: Api { gl, mt: &self.mt, lock: &self.lock },
            state: &mut self.state,
            tess: &mut self.tess,
            shaders: &self.shaders,
            dlight_image: self.dlight_image,
            time: frame as f32 / script::RATE,
            view,
            light: None,
            dlights: Vec::new(),
            projection_2d: false,
            screen: self.screen,
            counts: Counts::default(),
        };
        backend.render_view(view, &surfaces, &scene);
        self.hud.draw_icons(&mut backend, &scene, &self.shaders);
        self.hud.draw_2d(&mut backend, frame);
        backend.finish();
        if self.verbose {
            let c = backend.counts;
            println!("q3 frame {frame}: {} surfaces, {} batches, {} glDrawElements, {} glBegin", surfaces.len(), c.batches, c.draw_elements, c.begins);
        }
        Ok(())
    }

    /// Deletes the textures.
    pub fn delete(&self, gl: &Gl) {
        self.images.delete(gl);
    }
}
