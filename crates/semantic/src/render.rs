//! Pictures for people: segments over an image, a top view of the map's entities and a top
//! view of labelled points, as RGB images in an [`ImageFrame`] (north up; no text).

use crate::error::{Result, SemanticError};
use crate::image_frame::{pixel_center, pixel_range, ImageFrame};
use crate::map::{HingeEdge, OrientedBox, SemanticMap, SwingSide};
use crate::merge::Segment;
use cloud::{EntityClass, Label, PointCloud};
use glam::{DVec2, DVec3};
use image::{GrayImage, Rgb, RgbImage};

/// Writes `image` (a `GrayImage` or an `RgbImage`, e.g. the skeleton of a map's output or
/// [`render_top_view`]'s) as a PNG file, atomically.
pub fn save_png(path: &std::path::Path, image: impl Into<image::DynamicImage>) -> Result<()> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .into()
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| SemanticError::Image {
            path: path.into(),
            msg: e.to_string(),
        })?;
    cloud::write_bytes_atomically(path, bytes.get_ref())?;
    Ok(())
}

/// The colour of each class in the pictures (of the map's entities; `unknown`, `furniture` and
/// `robot` are those of labelled points).
pub fn class_color(class: EntityClass) -> [u8; 3] {
    match class {
        EntityClass::Unknown => [150, 150, 150],
        EntityClass::Floor => [225, 225, 225],
        EntityClass::Ceiling => [200, 220, 240],
        EntityClass::Wall => [30, 30, 30],
        EntityClass::WallAboveDoor => [60, 60, 170],
        EntityClass::Door => [170, 90, 20],
        EntityClass::FreeSpaceForDoor => [110, 200, 110],
        EntityClass::Stairs => [235, 150, 40],
        EntityClass::Furniture => [120, 60, 160],
        EntityClass::Robot => [20, 160, 160],
        EntityClass::Obstacle => [150, 40, 120],
        EntityClass::Column => [90, 90, 90],
        EntityClass::Beam => [120, 120, 60],
        EntityClass::Ramp => [200, 190, 110],
    }
}

/// The colour of a labelled point: its class's, but walls in red (black is the map's wall).
fn point_color(class: EntityClass) -> [u8; 3] {
    match class {
        EntityClass::Wall => [200, 30, 30],
        c => class_color(c),
    }
}

/// `background` (dimmed) with `segments` drawn over it in `color`, plus their end points.
pub fn render_segments(
    background: &GrayImage,
    frame: &ImageFrame,
    segments: &[Segment],
    color: [u8; 3],
) -> RgbImage {
    let mut img = RgbImage::from_fn(background.width(), background.height(), |x, y| {
        let v = 255 - background.get_pixel(x, y).0[0] / 2;
        Rgb([v, v, v])
    });
    for s in segments {
        let a = frame.to_pixel(s.a_m[0], s.a_m[1]);
        let b = frame.to_pixel(s.b_m[0], s.b_m[1]);
        draw_line(&mut img, a, b, color);
        for p in [a, b] {
            for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
                put(&mut img, p[0] + dx, p[1] + dy, [0, 0, 255]);
            }
        }
    }
    img
}

/// A top view of the map's entities: floor, stairs (darker with height), free space for
/// doors, walls (their solid boxes), lintels and door leaves (closed, with a line at the
/// observed opening angle from the hinge).
pub fn render_top_view(map: &SemanticMap, frame: &ImageFrame) -> RgbImage {
    let mut img = RgbImage::from_pixel(frame.width_px, frame.height_px, Rgb([255, 255, 255]));
    let order = [
        EntityClass::Floor,
        EntityClass::Stairs,
        EntityClass::FreeSpaceForDoor,
        EntityClass::Wall,
        EntityClass::WallAboveDoor,
        EntityClass::Door,
    ];
    for class in order {
        for e in map.of_class(class) {
            let color = class_color(class);
            match (&e.wall, &e.stairs, &e.door) {
                (Some(w), _, _) => {
                    for b in &w.solid_boxes {
                        fill_box(&mut img, frame, b, color);
                    }
                }
                (_, Some(s), _) => {
                    let top = s.steps.len().max(1) as f64;
                    for (k, b) in s.steps.iter().chain(&s.landing).enumerate() {
                        let f = 1.0 - 0.5 * (k as f64 / top).min(1.0);
                        let c = color.map(|v| (v as f64 * f) as u8);
                        fill_box(&mut img, frame, b, c);
                    }
                }
                (_, _, Some(d)) => {
                    fill_box(&mut img, frame, &e.geometry, color);
                    let len = e.geometry.size_m[0];
                    let yaw = e.geometry.yaw_deg.to_radians();
                    let sign_edge = if d.hinge_edge == HingeEdge::Start {
                        1.0
                    } else {
                        -1.0
                    };
                    let into = DVec2::from_angle(yaw) * sign_edge;
                    let left = (d.swing == SwingSide::Left) == (sign_edge > 0.0);
                    let a = d.observed_open_deg.to_radians() * if left { 1.0 } else { -1.0 };
                    let h = DVec2::new(d.hinge_m[0], d.hinge_m[1]);
                    let tip = h + DVec2::from_angle(a).rotate(into) * len;
                    draw_line(
                        &mut img,
                        frame.to_pixel(h.x, h.y),
                        frame.to_pixel(tip.x, tip.y),
                        color,
                    );
                }
                _ => fill_box(&mut img, frame, &e.geometry, color),
            }
        }
    }
    img
}

/// A top view of labelled points (in the input cloud's frame; moved into the map frame with
/// `map.input_from_map`), coloured by class, higher points drawn over lower ones.
pub fn render_labels(
    cloud: &PointCloud,
    labels: &[Label],
    map: &SemanticMap,
    frame: &ImageFrame,
) -> RgbImage {
    let mut img = RgbImage::from_pixel(frame.width_px, frame.height_px, Rgb([255, 255, 255]));
    let map_from_input = map.input_from_map().inverse();
    let mut pts: Vec<(DVec3, [u8; 3])> = cloud
        .points
        .iter()
        .zip(labels)
        .filter(|(p, _)| p.is_finite())
        .map(|(p, l)| {
            (
                map_from_input.transform_point3(p.as_dvec3()),
                point_color(l.class),
            )
        })
        .filter(|(_, c)| *c != class_color(EntityClass::Ceiling))
        .collect();
    pts.sort_by(|a, b| a.0.z.total_cmp(&b.0.z));
    for (p, c) in pts {
        if let Some((x, y)) = frame.pixel_of(p.x, p.y) {
            img.put_pixel(x, y, Rgb(c));
        }
    }
    img
}

fn put(img: &mut RgbImage, x: f64, y: f64, c: [u8; 3]) {
    if x >= 0.0 && y >= 0.0 && x < img.width() as f64 && y < img.height() as f64 {
        img.put_pixel(x as u32, y as u32, Rgb(c));
    }
}

fn draw_line(img: &mut RgbImage, a: [f64; 2], b: [f64; 2], c: [u8; 3]) {
    let n = ((b[0] - a[0]).abs().max((b[1] - a[1]).abs()).ceil() as usize).clamp(1, 100_000);
    for k in 0..=n {
        let t = k as f64 / n as f64;
        put(img, a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, c);
    }
}

fn fill_box(img: &mut RgbImage, frame: &ImageFrame, b: &OrientedBox, c: [u8; 3]) {
    let corners = b.corners_xy().map(DVec2::from_array);
    let lo = corners
        .iter()
        .fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = corners
        .iter()
        .fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    if let Some((c0, c1, r0, r1)) = pixel_range(frame, lo, hi) {
        for row in r0..=r1 {
            for col in c0..=c1 {
                let q = pixel_center(frame, col as f64, row as f64);
                let inside = (0..4).all(|k| {
                    let (p, n) = (corners[k], corners[(k + 1) % 4]);
                    (n - p).perp_dot(q - p) >= 0.0
                });
                if inside {
                    img.put_pixel(col as u32, row as u32, Rgb(c));
                }
            }
        }
    }
    // Thin boxes (leaves, thin walls) would vanish between pixel centres: draw the axis too.
    let (s, co) = b.yaw_deg.to_radians().sin_cos();
    let h = b.size_m[0] / 2.0;
    let a = [b.center_m[0] - co * h, b.center_m[1] - s * h];
    let e = [b.center_m[0] + co * h, b.center_m[1] + s * h];
    draw_line(
        img,
        frame.to_pixel(a[0], a[1]),
        frame.to_pixel(e[0], e[1]),
        c,
    );
}
