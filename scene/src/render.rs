//! Rendered frames: a small software z-buffer rasteriser of the bodies'
//! certified tessellations ([`revdist::tessellate`]) with a perspective camera and Lambert
//! shading, written as PNG. Meant for a person to look at a scene, not for measurements.

use nalgebra::{Isometry3, Matrix4, Point3, Vector3};
use revdist::tessellate::TriMesh;
use std::path::Path;

/// Okabe-Ito colours (colour-blind safe), cycled over the bodies.
pub const PALETTE: [[u8; 3]; 7] = [
    [0, 114, 178],
    [213, 94, 0],
    [0, 158, 115],
    [204, 121, 167],
    [230, 159, 0],
    [86, 180, 233],
    [240, 228, 66],
];

/// A perspective camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub eye: Point3<f64>,
    pub target: Point3<f64>,
    /// Vertical field of view (radians).
    pub fov_y: f64,
    pub width: usize,
    pub height: usize,
}

/// An RGB image with a depth buffer.
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
    depth: Vec<f64>,
}

impl Canvas {
    /// A canvas cleared to a light vertical gradient.
    pub fn new(width: usize, height: usize) -> Canvas {
        let mut rgb = vec![0u8; width * height * 3];
        for y in 0..height {
            let t = y as f64 / height.max(1) as f64;
            let c = (250.0 - 40.0 * t) as u8;
            for x in 0..width {
                let i = 3 * (y * width + x);
                rgb[i..i + 3].copy_from_slice(&[c, c, c.saturating_add(5)]);
            }
        }
        Canvas {
            width,
            height,
            rgb,
            depth: vec![f64::INFINITY; width * height],
        }
    }

    /// Number of pixels covered by some triangle.
    pub fn covered(&self) -> usize {
        self.depth.iter().filter(|d| d.is_finite()).count()
    }

    /// Draws a mesh (local frame) placed by `pose`, flat-shaded in `colour`.
    pub fn draw(&mut self, cam: &Camera, mesh: &TriMesh, pose: &Isometry3<f64>, colour: [u8; 3]) {
        let view = Isometry3::look_at_rh(&cam.eye, &cam.target, &Vector3::z());
        let aspect = cam.width as f64 / cam.height as f64;
        let proj = Matrix4::new_perspective(aspect, cam.fov_y, 0.01, 1e4);
        let light = Vector3::new(-0.4, -0.5, 1.0).normalize();
        // World positions and screen positions (x, y in pixels, z = view depth).
        let world: Vec<Point3<f64>> = mesh.vertices.iter().map(|v| pose * v).collect();
        let screen: Vec<Option<(f64, f64, f64)>> = world
            .iter()
            .map(|p| {
                let v = view * p;
                if v.z >= -0.01 {
                    return None;
                }
                let c = proj * v.to_homogeneous();
                let (x, y) = (c.x / c.w, c.y / c.w);
                Some((
                    (x + 1.0) * 0.5 * cam.width as f64,
                    (1.0 - y) * 0.5 * cam.height as f64,
                    -v.z,
                ))
            })
            .collect();
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| i as usize);
            let (Some(sa), Some(sb), Some(sc)) = (screen[a], screen[b], screen[c]) else {
                continue;
            };
            let n = (world[b] - world[a]).cross(&(world[c] - world[a]));
            let Some(n) = n.try_normalize(0.0) else {
                continue;
            };
            // Back faces of a closed outward mesh are hidden; skip them.
            let to_eye = cam.eye - world[a];
            if n.dot(&to_eye) <= 0.0 {
                continue;
            }
            let shade = 0.35 + 0.65 * n.dot(&light).max(0.0);
            let col = colour.map(|ch| (ch as f64 * shade).min(255.0) as u8);
            self.fill(sa, sb, sc, col);
        }
    }

    fn fill(&mut self, a: (f64, f64, f64), b: (f64, f64, f64), c: (f64, f64, f64), col: [u8; 3]) {
        let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
        if area.abs() < 1e-12 {
            return;
        }
        let clampx = |v: f64| v.max(0.0).min(self.width as f64 - 1.0) as usize;
        let clampy = |v: f64| v.max(0.0).min(self.height as f64 - 1.0) as usize;
        let (x0, x1) = (
            clampx(a.0.min(b.0).min(c.0)),
            clampx(a.0.max(b.0).max(c.0).ceil()),
        );
        let (y0, y1) = (
            clampy(a.1.min(b.1).min(c.1)),
            clampy(a.1.max(b.1).max(c.1).ceil()),
        );
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let w0 = ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) / area;
                let w1 = ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * a.2 + w1 * b.2 + w2 * c.2;
                let i = y * self.width + x;
                if z < self.depth[i] {
                    self.depth[i] = z;
                    self.rgb[3 * i..3 * i + 3].copy_from_slice(&col);
                }
            }
        }
    }

    /// Writes the image as an 8-bit RGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
        let file = std::fs::File::create(path)
            .map_err(|e| format!("cannot write '{}': {e}", path.display()))?;
        let mut enc = png::Encoder::new(
            std::io::BufWriter::new(file),
            self.width as u32,
            self.height as u32,
        );
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header()?;
        w.write_image_data(&self.rgb)?;
        Ok(())
    }
}

/// Renders the frames of a scene that asks for them: the bodies' meshes are tessellated once
/// (a deforming body again for each rendered frame).
pub struct SceneRenderer {
    camera: Camera,
    every: usize,
    meshes: Vec<Option<TriMesh>>,
    /// Frames rendered so far.
    pub rendered: usize,
    /// The rendered frames (RGB), kept for the animated summary ([`SceneRenderer::write_gif`]).
    frames: Vec<Vec<u8>>,
}

/// Tessellation bound of rendered meshes (a fraction of a pixel at the default camera
/// distance for bodies of the built-in models' size; smaller bodies get 1% of their size).
const RENDER_EPS: f64 = 2e-3;

impl SceneRenderer {
    /// `None` when the scene asks for no frames.
    pub fn new(scene: &crate::format::Scene) -> Option<SceneRenderer> {
        let r = scene.render.as_ref()?;
        Some(SceneRenderer {
            camera: Camera {
                eye: r.eye,
                target: r.target,
                fov_y: r.fov,
                width: r.width,
                height: r.height,
            },
            every: r.every,
            meshes: vec![None; scene.bodies.len()],
            rendered: 0,
            frames: Vec::new(),
        })
    }

    /// Renders `frame` into `dir/NNNNN.png` when it is one of the frames asked for.
    pub fn frame(
        &mut self,
        scene: &crate::format::Scene,
        frame: &crate::runner::Frame,
        dir: &Path,
    ) -> Result<(), Box<dyn std::error::Error>> {
        if !frame.index.is_multiple_of(self.every) {
            return Ok(());
        }
        let mut canvas = Canvas::new(self.camera.width, self.camera.height);
        for (i, body) in scene.bodies.iter().enumerate() {
            let deforming = body.effect == crate::format::Effect::Deforming;
            if self.meshes[i].is_none() || deforming {
                let profile = crate::format::shape_profile(body, frame.time)
                    .map_err(|e| format!("body '{}': {e}", body.name))?;
                // Small shapes (thin tori) get a finer bound: 1% of their profile's size.
                let bb = profile.bounding_box();
                let eps = RENDER_EPS.min(0.01 * (bb.max - bb.min).norm());
                let mesh = revdist::tessellate::tessellate(
                    &profile,
                    eps,
                    revdist::tessellate::TessellateOptions::default(),
                )
                .map_err(|e| format!("body '{}': {e}", body.name))?;
                self.meshes[i] = Some(mesh.mesh);
            }
            if let Some(mesh) = &self.meshes[i] {
                canvas.draw(
                    &self.camera,
                    mesh,
                    &frame.poses[i],
                    PALETTE[i % PALETTE.len()],
                );
            }
        }
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create '{}': {e}", dir.display()))?;
        canvas.write_png(&dir.join(format!("{:05}.png", frame.index)))?;
        self.frames.push(canvas.rgb);
        self.rendered += 1;
        Ok(())
    }

    /// Writes the rendered frames as an animated GIF (the animated summary), each shown
    /// for `frame_seconds` (the scene time between rendered frames: real-time playback),
    /// looping. Colours are quantised per frame (NeuQuant, `gif`'s `from_rgb_speed`).
    /// Nothing is written when no frame was rendered.
    pub fn write_gif(
        &self,
        path: &Path,
        frame_seconds: f64,
    ) -> Result<(), Box<dyn std::error::Error>> {
        if self.frames.is_empty() {
            return Ok(());
        }
        let (w, h) = (self.camera.width as u16, self.camera.height as u16);
        let file = std::fs::File::create(path)
            .map_err(|e| format!("cannot create '{}': {e}", path.display()))?;
        let mut enc = gif::Encoder::new(std::io::BufWriter::new(file), w, h, &[])?;
        enc.set_repeat(gif::Repeat::Infinite)?;
        // GIF delays are in hundredths of a second, at least 2 in common viewers.
        let delay = (frame_seconds * 100.0).round().clamp(2.0, 65535.0) as u16;
        for rgb in &self.frames {
            let mut f = gif::Frame::from_rgb_speed(w, h, rgb, GIF_QUANTISE_SPEED);
            f.delay = delay;
            enc.write_frame(&f)?;
        }
        Ok(())
    }
}

/// NeuQuant speed of the GIF colour quantiser (1 best .. 30 fastest): 10 keeps the shaded
/// bodies' gradients at about 30 ms per 480x360 frame.
const GIF_QUANTISE_SPEED: i32 = 10;

#[cfg(test)]
mod tests {
    use super::*;
    use revdist::tessellate::{tessellate, TessellateOptions};

    /// A sphere in front of the camera covers about the disk its projection predicts, and
    /// nothing is drawn for a sphere behind the camera.
    #[test]
    fn sphere_covers_its_projected_disk() {
        let profile = revdist::models::model("sphere").unwrap();
        let mesh = tessellate(&profile, 1e-3, TessellateOptions::default())
            .unwrap()
            .mesh;
        let cam = Camera {
            eye: Point3::new(5.0, 0.0, 0.75),
            target: Point3::new(0.0, 0.0, 0.75),
            fov_y: 0.6,
            width: 200,
            height: 200,
        };
        let mut canvas = Canvas::new(200, 200);
        canvas.draw(&cam, &mesh, &Isometry3::identity(), PALETTE[0]);
        // Ball of radius 0.75 at distance 5: angular radius asin(0.15); its image radius is
        // tan(asin(0.15)) / tan(fov / 2) * 100 pixels.
        let r = (0.15f64.asin().tan() / 0.3f64.tan()) * 100.0;
        let expected = std::f64::consts::PI * r * r;
        let got = canvas.covered() as f64;
        assert!(
            (got - expected).abs() < 0.05 * expected,
            "{got} vs {expected}"
        );
        let mut behind = Canvas::new(200, 200);
        behind.draw(
            &cam,
            &mesh,
            &Isometry3::translation(10.0, 0.0, 0.0),
            PALETTE[1],
        );
        assert_eq!(behind.covered(), 0);
    }
}

#[cfg(test)]
mod gif_tests {
    use super::*;

    /// The animated summary decodes to the rendered frames: one GIF frame per rendered
    /// frame, the camera's size, the requested delay, and colours within the quantiser's
    /// error of the originals (a shaded sphere in front of a gradient-free background).
    #[test]
    fn gif_holds_every_rendered_frame() {
        let profile = revdist::models::model("sphere").unwrap();
        let mesh = revdist::tessellate::tessellate(
            &profile,
            1e-3,
            revdist::tessellate::TessellateOptions::default(),
        )
        .unwrap()
        .mesh;
        let camera = Camera {
            eye: Point3::new(5.0, 0.0, 0.75),
            target: Point3::new(0.0, 0.0, 0.75),
            fov_y: 0.6,
            width: 120,
            height: 90,
        };
        let mut r = SceneRenderer {
            camera,
            every: 1,
            meshes: Vec::new(),
            rendered: 0,
            frames: Vec::new(),
        };
        for (k, colour) in PALETTE.iter().take(3).enumerate() {
            let mut c = Canvas::new(120, 90);
            let pose = Isometry3::translation(0.0, 0.3 * k as f64 - 0.3, 0.0);
            c.draw(&r.camera, &mesh, &pose, *colour);
            r.frames.push(c.rgb);
        }
        let path =
            std::env::temp_dir().join(format!("revdist-gif-test-{}.gif", std::process::id()));
        r.write_gif(&path, 0.2).unwrap();
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut dec = opts.read_info(std::fs::File::open(&path).unwrap()).unwrap();
        let mut n = 0;
        while let Some(f) = dec.read_next_frame().unwrap() {
            assert_eq!((f.width, f.height), (120, 90));
            assert_eq!(f.delay, 20);
            let orig = &r.frames[n];
            let mut err = 0.0;
            for (i, px) in f.buffer.chunks(4).enumerate() {
                for c in 0..3 {
                    err += (px[c] as f64 - orig[3 * i + c] as f64).abs();
                }
            }
            let mean = err / (3.0 * 120.0 * 90.0);
            assert!(mean < 4.0, "frame {n}: mean colour error {mean}");
            n += 1;
        }
        assert_eq!(n, 3);
        let _ = std::fs::remove_file(&path);
    }
}
