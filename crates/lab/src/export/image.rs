//! Images in: the surface sensors read from a picture instead of the
//! simulator, and a controller driven by a sequence of such frames.
//!
//! The camera model is a flat ground seen from above, as a downward camera
//! (or an omnidirectional mirror camera whose frame has been unwarped to the
//! ground plane, or a top-down map such as a scenario render) sees it: the
//! robot's centre is at pixel [`Camera::centre`], the robot faces
//! [`Camera::heading`] (radians clockwise from the image's up, vivae's own
//! heading convention), and one scenario px is [`Camera::scale`] image
//! pixels. The reading at robot-frame offset `(x ahead, y right)` is the
//! pixel at `centre + scale·(x·(sin h, −cos h) + y·(cos h, sin h))` (x to the
//! right, y down, the pixel whose square holds that point), its colour
//! mapped to a reading by the nearest colour of a [`Palette`]. Pixels outside
//! the image, transparent ones and ones farther than [`Camera::radius`] from
//! the centre (outside a mirror's disc) read 0, as the simulator reads
//! outside the arena.

use vivae_sim::{DVec2, World};

use crate::error::Result;
use crate::io::bad_input;
use crate::tasks::substrate::SubstrateEpisode;

/// An RGBA picture, 8 bits a channel, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// `width × height × 4` bytes.
    pub rgba: Vec<u8>,
}

/// Most pixels an image read may have (by its header, checked before
/// decoding): as many as vivae draws at most (`vivae_sim::draw::MAX_PIXELS`).
pub const MAX_IMAGE_PIXELS: u64 = vivae_sim::draw::MAX_PIXELS as u64;

impl Image {
    /// Decodes a PNG (any colour type and depth); `what` names it in errors.
    pub fn from_png(bytes: &[u8], what: &str) -> Result<Image> {
        let bad = |e: png::DecodingError| bad_input(format!("{what}: not a PNG image ({e})"));
        let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info().map_err(bad)?;
        // Checked from the header before anything is allocated: a few bytes
        // may claim 100000 × 100000 pixels.
        let (width, height) = (reader.info().width, reader.info().height);
        if u64::from(width) * u64::from(height) > MAX_IMAGE_PIXELS {
            return Err(bad_input(format!(
                "{what}: its header says {width} x {height} pixels, more than the {MAX_IMAGE_PIXELS} an image may have"
            )));
        }
        let size = (reader.output_buffer_size())
            .ok_or_else(|| bad_input(format!("{what}: image too large")))?;
        let mut buf = vec![0; size];
        let info = reader.next_frame(&mut buf).map_err(bad)?;
        let (w, h) = (info.width as usize, info.height as usize);
        let channels = info.color_type.samples();
        let mut rgba = Vec::with_capacity(w * h * 4);
        for row in buf.chunks(info.line_size).take(h) {
            for px in row[..w * channels].chunks_exact(channels) {
                let (rgb, a) = match channels {
                    1 => ([px[0]; 3], 255),
                    2 => ([px[0]; 3], px[1]),
                    3 => ([px[0], px[1], px[2]], 255),
                    _ => ([px[0], px[1], px[2]], px[3]),
                };
                rgba.extend_from_slice(&[rgb[0], rgb[1], rgb[2], a]);
            }
        }
        Ok(Image {
            width: w,
            height: h,
            rgba,
        })
    }

    /// The pixel whose square holds `(u, v)`, `None` outside the picture.
    fn pixel(&self, u: f64, v: f64) -> Option<[u8; 4]> {
        if !(u >= 0.0 && v >= 0.0 && u < self.width as f64 && v < self.height as f64) {
            return None;
        }
        let at = 4 * ((v as usize) * self.width + u as usize);
        self.rgba.get(at..at + 4).map(|p| [p[0], p[1], p[2], p[3]])
    }
}

/// Where the robot is in a frame, which way it faces, and the frame's scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// The robot's centre in the image, pixels (x right, y down).
    pub centre: [f64; 2],
    /// Image pixels per scenario px.
    pub scale: f64,
    /// The robot's heading in the image: radians clockwise from up.
    pub heading: f64,
    /// Pixels farther than this from `centre` are out of view (read 0); `None`: the whole image.
    pub radius: Option<f64>,
}

impl Camera {
    /// The camera of a top-down map drawn at `scale` pixels per scenario px
    /// (a scenario render without title or legend), the robot at `pos` facing `heading`.
    pub fn on_map(pos: DVec2, heading: f64, scale: f64) -> Camera {
        Camera {
            centre: [pos.x * scale, pos.y * scale],
            scale,
            heading,
            radius: None,
        }
    }

    /// Whether a frame's `scale` and out-of-view `radius` can be used: finite
    /// and positive scale, positive radius (or none).
    pub fn usable(scale: f64, radius: Option<f64>) -> bool {
        scale.is_finite() && scale > 0.0 && radius.is_none_or(|r| r > 0.0)
    }
}

/// Colours and the readings they stand for.
#[derive(Debug, Clone, PartialEq)]
pub struct Palette(pub Vec<([u8; 3], f64)>);

impl Palette {
    /// The colours vivae draws `world`'s surfaces with, each with the reading
    /// its surface gives (the scenario's materials; where two materials of
    /// one kind have different frictions, the first one's).
    pub fn of_world(world: &World) -> Palette {
        let scenario = world.scenario();
        let friction = &world.params().friction;
        let (lo, hi) = friction.range();
        let mut colours: Vec<([u8; 3], f64)> = Vec::new();
        let kinds = (scenario.materials().iter().map(|&(k, f)| (k, f)))
            .chain(std::iter::once((scenario.background(), None)));
        for (kind, over) in kinds {
            let f = over.unwrap_or(friction.of(kind));
            let reading = ((hi - f) / (hi - lo)).clamp(0.0, 1.0);
            let rgb = hex_colour(vivae_sim::surface_color(kind));
            if !colours.iter().any(|(c, _)| *c == rgb) {
                colours.push((rgb, reading));
            }
        }
        Palette(colours)
    }

    /// The reading of the palette colour nearest `rgb` (squared RGB distance; the first on a tie).
    pub fn reading(&self, rgb: [u8; 3]) -> f64 {
        let d = |c: &[u8; 3]| -> i32 {
            (0..3)
                .map(|i| (i32::from(c[i]) - i32::from(rgb[i])).pow(2))
                .sum()
        };
        let mut best = (i32::MAX, 0.0);
        for (c, r) in &self.0 {
            if d(c) < best.0 {
                best = (d(c), *r);
            }
        }
        best.1
    }
}

/// `#rrggbb` as bytes.
fn hex_colour(s: &str) -> [u8; 3] {
    let v = u32::from_str_radix(s.trim_start_matches('#'), 16).unwrap_or(0);
    [(v >> 16) as u8, (v >> 8) as u8, v as u8]
}

/// The surface sensors of an episode, read from pictures.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageSensors {
    /// Each sensor's robot-frame offset (x ahead, y right), scenario px, in input order.
    offsets: Vec<DVec2>,
    /// Colours → readings.
    pub palette: Palette,
}

impl ImageSensors {
    /// The surface sensors of `episode`, colours read by `palette` (default:
    /// the episode's map's); an error if its robots carry another sensor
    /// (distance rays cannot be seen in a picture of the ground).
    pub fn new(episode: &dyn SubstrateEpisode, palette: Option<Palette>) -> Result<ImageSensors> {
        if let Some(s) = episode.sensors().iter().find(|s| s.name() != "surface") {
            return Err(bad_input(format!(
                "the controller also reads {} ({}): only surface sensors can be read from an image",
                s.label,
                s.name()
            )));
        }
        Ok(ImageSensors {
            offsets: episode.surface_offsets().to_vec(),
            palette: palette.unwrap_or_else(|| Palette::of_world(episode.world())),
        })
    }

    /// Number of readings.
    pub fn len(&self) -> usize {
        self.offsets.len()
    }

    /// Whether there is no reading.
    pub fn is_empty(&self) -> bool {
        self.offsets.is_empty()
    }

    /// Reads every sensor from `image` seen through `camera` into `out`.
    pub fn read(&self, image: &Image, camera: &Camera, out: &mut [f64]) {
        let (sin, cos) = vivae_neat::math::sin_cos(camera.heading);
        let (ahead, right) = (DVec2::new(sin, -cos), DVec2::new(cos, sin));
        let centre = DVec2::from(camera.centre);
        for (o, v) in self.offsets.iter().zip(out.iter_mut()) {
            let p = centre + (ahead * o.x + right * o.y) * camera.scale;
            let seen = camera
                .radius
                .is_none_or(|r| (p - centre).length_squared() <= r * r);
            *v = match image.pixel(p.x, p.y) {
                Some([r, g, b, a]) if seen && a >= 128 => self.palette.reading([r, g, b]),
                _ => 0.0,
            };
        }
    }
}

/// Drives `net` (zero state at the start) through `frames`, each seen
/// through its camera: the wheel commands of every frame.
pub fn drive_frames<'a>(
    net: &super::StepNet,
    sensors: &ImageSensors,
    frames: impl IntoIterator<Item = (&'a Image, Camera)>,
) -> Result<Vec<[f64; 2]>> {
    if net.inputs != sensors.len() {
        return Err(bad_input(format!(
            "the controller reads {} inputs, the image sensors give {}",
            net.inputs,
            sensors.len()
        )));
    }
    let mut inputs = vec![0.0; net.inputs];
    if net.outputs.len() != 2 {
        return Err(bad_input(format!(
            "the controller has {} outputs, a robot's two wheels need two",
            net.outputs.len()
        )));
    }
    let (mut state, mut scratch) = (vec![0.0; net.nodes], vec![0.0; net.nodes]);
    Ok(frames
        .into_iter()
        .map(|(image, camera)| {
            sensors.read(image, &camera, &mut inputs);
            let mut wheels = [0.0; 2];
            net.step(&inputs, &mut state, &mut scratch, &mut wheels);
            wheels
        })
        .collect())
}
