//! What happens in the level, as a function of the frame number only (60 steps per second of
//! game time, no clock, no random numbers): the camera's path ([`PATH_FRAMES`] frames from the
//! west end of the hall through the doorway into the courtyard, looking up at the sky, around
//! the pool and back; then again), two players walking (one circling in the hall, one pacing
//! along the courtyard's north wall), the armour spinning and bobbing, and a rocket flying
//! every [`ROCKET_PERIOD`] frames from the courtyard through the doorway across the hall,
//! trailing smoke puffs.

use glam::{Mat3, Vec3};

use super::models::WALK_FRAMES;

/// Game steps per second.
pub const RATE: f32 = 60.0;
/// Frames of the camera's path.
pub const PATH_FRAMES: u64 = 480;
/// Frames between rockets, and frames one flies.
pub const ROCKET_PERIOD: u64 = 100;
const ROCKET_FLIGHT: u64 = 70;
/// A smoke puff every `PUFF_EVERY` frames of flight, living `PUFF_LIFE` frames.
const PUFF_EVERY: u64 = 6;
const PUFF_LIFE: u64 = 30;
/// Units per walk cycle.
const STRIDE: f32 = 64.0;

/// The camera's key positions: frame, position, yaw and pitch (degrees, pitch up).
const CAMERA_KEYS: [(u64, [f32; 3], f32, f32); 8] = [
    (0, [40.0, 300.0, 60.0], -18.0, 2.0),
    (90, [140.0, 270.0, 60.0], -12.0, 4.0),
    (190, [430.0, 200.0, 60.0], 0.0, 10.0),
    (270, [640.0, 180.0, 60.0], 15.0, 32.0),
    (340, [800.0, 30.0, 60.0], 80.0, 6.0),
    (410, [980.0, 330.0, 60.0], 190.0, 2.0),
    (460, [760.0, 360.0, 60.0], 200.0, 0.0),
    (480, [560.0, 300.0, 60.0], 195.0, 0.0),
];

/// A view's axes (forward, left, up) for yaw and pitch in degrees.
pub fn axis(yaw: f32, pitch: f32) -> Mat3 {
    let (y, p) = (yaw.to_radians(), pitch.to_radians());
    let forward = Vec3::new(p.cos() * y.cos(), p.cos() * y.sin(), p.sin());
    let left = Vec3::new(-y.sin(), y.cos(), 0.0);
    Mat3::from_cols(forward, left, forward.cross(left))
}

/// A walking player: where it stands, its yaw, and the frames of the walk cycle to blend.
#[derive(Clone, Copy, Debug)]
pub struct Walker {
    pub origin: Vec3,
    pub yaw: f32,
    pub frame: usize,
    pub old_frame: usize,
    pub backlerp: f32,
}

impl Walker {
    /// At `origin`, facing along `velocity`, `distance` units walked so far.
    fn new(origin: Vec3, velocity: Vec3, distance: f32) -> Walker {
        let cycle = (distance / STRIDE).rem_euclid(1.0) * WALK_FRAMES as f32;
        let old_frame = cycle.floor() as usize % WALK_FRAMES;
        let frac = cycle.fract();
        Walker { origin, yaw: velocity.y.atan2(velocity.x).to_degrees(), frame: (old_frame + 1) % WALK_FRAMES, old_frame, backlerp: 1.0 - frac }
    }
}

/// A smoke puff: where, how big, how opaque (0..=1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Puff {
    pub origin: Vec3,
    pub radius: f32,
    pub alpha: f32,
}

/// The state of the level at one frame.
#[derive(Clone, Debug)]
pub struct Moment {
    pub eye: Vec3,
    pub view_axis: Mat3,
    pub players: [Walker; 2],
    pub armour_origin: Vec3,
    pub armour_yaw: f32,
    /// The rocket in flight: position and direction.
    pub rocket: Option<(Vec3, Vec3)>,
    pub puffs: Vec<Puff>,
}

/// Smooth interpolation of the camera keys at frame `f` of the path.
fn camera(f: f32) -> (Vec3, Mat3) {
    let next = CAMERA_KEYS.iter().position(|k| k.0 as f32 > f).unwrap_or(CAMERA_KEYS.len() - 1).max(1);
    let (a, b) = (CAMERA_KEYS[next - 1], CAMERA_KEYS[next]);
    let x = ((f - a.0 as f32) / (b.0 - a.0) as f32).clamp(0.0, 1.0);
    let s = x * x * (3.0 - 2.0 * x);
    let eye = Vec3::from(a.1).lerp(Vec3::from(b.1), s);
    (eye, axis(a.2 + (b.2 - a.2) * s, a.3 + (b.3 - a.3) * s))
}

/// Where the rocket is `age` frames into its flight: from the courtyard's east side to the
/// hall's west wall, through the middle of the doorway.
fn rocket_at(age: f32) -> (Vec3, Vec3) {
    let (from, to) = (Vec3::new(1000.0, 205.0, 84.0), Vec3::new(24.0, 250.0, 52.0));
    (from.lerp(to, age / ROCKET_FLIGHT as f32), (to - from).normalize())
}

/// The level at frame `frame`.
pub fn moment(frame: u64) -> Moment {
    let t = frame as f32 / RATE;
    let (eye, view_axis) = camera((frame % PATH_FRAMES) as f32);
    // Player 1 circles an ellipse in the hall in 6 seconds; player 2 paces 380 units and
    // back in 8.
    let angle = t * std::f32::consts::TAU / 6.0 + 3.9;
    let (rx, ry) = (100.0, 70.0);
    let p1 = Walker::new(Vec3::new(330.0 + rx * angle.cos(), 250.0 + ry * angle.sin(), 0.0), Vec3::new(-rx * angle.sin(), ry * angle.cos(), 0.0), angle * 85.0);
    let pace = (t / 8.0).fract() * 2.0;
    let (x, dir) = if pace < 1.0 { (600.0 + 380.0 * pace, 1.0) } else { (600.0 + 380.0 * (2.0 - pace), -1.0) };
    let p2 = Walker::new(Vec3::new(x, 390.0, 0.0), Vec3::new(dir, 0.0, 0.0), t * 95.0);
    let age = frame % ROCKET_PERIOD;
    let rocket = (age < ROCKET_FLIGHT).then(|| rocket_at(age as f32));
    let puffs = (0..=age.min(ROCKET_FLIGHT))
        .filter(|a| a % PUFF_EVERY == 0 && age - a < PUFF_LIFE)
        .map(|a| {
            let life = (age - a) as f32 / PUFF_LIFE as f32;
            Puff { origin: rocket_at(a as f32).0 + Vec3::Z * (life * 12.0), radius: 8.0 + 20.0 * life, alpha: 0.8 * (1.0 - life) }
        })
        .collect();
    Moment {
        eye,
        view_axis,
        players: [p1, p2],
        armour_origin: Vec3::new(420.0, 150.0, 24.0 + 4.0 * (t * 2.5).sin()),
        armour_yaw: (t * 176.0) % 360.0,
        rocket,
        puffs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_camera_follows_its_keys_and_loops() {
        let start = moment(0);
        assert!(start.eye.abs_diff_eq(Vec3::new(40.0, 300.0, 60.0), 1e-4));
        assert!(start.view_axis.x_axis.x > 0.9, "looks east");
        assert!(moment(PATH_FRAMES).eye.abs_diff_eq(start.eye, 1e-4));
        let up = moment(270).view_axis.x_axis;
        assert!(up.z > 0.5, "looks up at the sky in the courtyard: {up}");
        let a = moment(42).view_axis;
        assert!((a.x_axis.cross(a.y_axis) - a.z_axis).length() < 1e-5 && (a.determinant() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn the_rocket_flies_through_the_doorway_with_a_trail() {
        let (crossing, _) = rocket_at(ROCKET_FLIGHT as f32 * (1000.0 - 520.0) / 976.0);
        assert!((128.0..256.0).contains(&crossing.y) && crossing.z < 176.0, "{crossing}");
        let m = moment(ROCKET_PERIOD * 3 + 40);
        assert!(m.rocket.is_some());
        assert_eq!(m.puffs.len(), 5, "{:?}", m.puffs);
        assert!(m.puffs.windows(2).all(|w| w[0].radius > w[1].radius && w[0].alpha < w[1].alpha));
        assert!(moment(ROCKET_PERIOD + ROCKET_FLIGHT + 1).rocket.is_none());
        assert!(moment(ROCKET_PERIOD * 2 - 1).puffs.is_empty(), "all faded before the next rocket");
    }

    #[test]
    fn players_walk_through_their_cycle() {
        let (a, b) = (moment(10).players[0], moment(30).players[0]);
        assert_ne!((a.frame, a.backlerp), (b.frame, b.backlerp));
        assert!(a.frame < WALK_FRAMES && a.old_frame < WALK_FRAMES && (0.0..=1.0).contains(&a.backlerp));
        assert_eq!(a.frame, (a.old_frame + 1) % WALK_FRAMES);
        let p2 = moment(60 * 4 + 1).players[1];
        assert!(p2.yaw.abs() > 179.0, "walks back west after 4 s: {}", p2.yaw);
    }
}
