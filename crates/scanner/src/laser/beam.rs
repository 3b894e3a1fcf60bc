//! One beam through the realistic sensor: the first surface along it (the building or a
//! walking person), what the surface does to it (return, pass through glass, lose it), and the
//! noisy range of what comes back.

use super::people::Walkers;
use super::realism::Realism;
use super::returns::Fate;
use crate::building::Material;
use crate::geometry::BuildingGeometry;
use cloud::{Label, Rng};
use glam::{Quat, Vec3};

/// Surfaces a beam may pass through (glass panes) before it is given up.
const MAX_LAYERS: usize = 8;
/// How far past a surface a beam going on through it restarts (metres).
const RESTART_M: f32 = 1e-4;

/// What one scan's beams meet: the building, the people, and where the sensor is.
pub struct Scene<'a> {
    /// The building.
    pub geometry: &'a BuildingGeometry,
    /// The people of this scan.
    pub walkers: Walkers,
    /// The sensor's origin (world frame).
    pub origin: Vec3,
    /// The tilted sensor's orientation (world from sensor).
    pub world_from_sensor: Quat,
    /// Returns nearer than this are missing.
    pub min_range_m: f32,
    /// Returns beyond this are missing.
    pub max_range_m: f32,
    /// The laser's base range sigma.
    pub sigma0_m: f64,
    /// The realism parameters.
    pub realism: &'a Realism,
}

/// A surface met by a ray.
#[derive(Debug, Clone, Copy)]
pub struct Surface {
    /// Distance along the ray.
    pub t: f32,
    /// Unit normal.
    pub normal: Vec3,
    /// What it is made of.
    pub material: Material,
    /// Its ground-truth label (unknown for people).
    pub label: Label,
    /// The building box it belongs to (none for people).
    pub part: Option<usize>,
    /// Which surface it is: the box's index, or [`PERSON_ID`] plus the person's.
    pub id: u32,
}

/// Surface ids of people start here (box indices lie below).
pub const PERSON_ID: u32 = 1 << 30;
/// The surface id of no surface.
pub const NO_SURFACE: u32 = u32::MAX;

/// What the sensor reports for one beam.
#[derive(Debug, Clone, Copy)]
pub struct Beam {
    /// The point in the sensor frame (NaN for a missing return without a no-echo value).
    pub point: Vec3,
    /// Its label.
    pub label: Label,
    /// Distance to the first surface along the beam (NaN if none within range), before noise.
    pub first_t: f32,
    /// Which surface that is ([`NO_SURFACE`] if none).
    pub first_id: u32,
    /// Whether the point is a return from that first surface.
    pub from_first: bool,
}

impl Scene<'_> {
    /// The nearest surface along `from + t * dir` (`dir` unit, world frame) within `max_t` at
    /// rotation step `row`. With `solid` false a ray starting inside a box meets its far side.
    pub fn first_surface(
        &self,
        row: usize,
        from: Vec3,
        dir: Vec3,
        max_t: f32,
        solid: bool,
    ) -> Option<Surface> {
        let building = self
            .geometry
            .cast_ray_with_normal(from, dir, max_t, solid)
            .and_then(|(t, normal, part)| {
                let p = self.geometry.parts().get(part)?;
                Some(Surface {
                    t,
                    normal,
                    material: p.material,
                    label: p.label,
                    part: Some(part),
                    id: part as u32,
                })
            });
        let limit = building.map_or(max_t, |s| s.t);
        match self.walkers.cast(row, from, dir, limit) {
            Some((t, normal, q)) => Some(Surface {
                t,
                normal,
                material: Material::Matte,
                label: Label::default(),
                part: None,
                id: PERSON_ID + q as u32,
            }),
            None => building,
        }
    }

    /// Traces beam `index` (unit direction `d` in the sensor frame, rotation step `row`), its
    /// random draws from `rng`.
    pub fn trace(&self, row: usize, d: Vec3, rng: &mut Rng) -> Beam {
        let r = self.realism;
        let dir = self.world_from_sensor * d;
        // The first draw is the range noise, as the ideal laser's.
        let g = rng.gaussian();
        let divergence_rad = r.beam_divergence_mrad * 1e-3;
        let (mut from, mut travelled, mut transmission) = (self.origin, 0.0f32, 1.0f64);
        let (mut first_t, mut first_id) = (f32::NAN, NO_SURFACE);
        // The glass pane the beam is inside of, if it went on through one.
        let mut inside: Option<usize> = None;
        let mut layer = 0;
        let mut returned: Option<(f32, Label)> = None;
        while layer < MAX_LAYERS {
            // Inside a pane the ray must find the pane's far side, not stop where it starts.
            let solid = inside.is_none();
            let Some(s) = self.first_surface(row, from, dir, self.max_range_m - travelled, solid)
            else {
                break;
            };
            if s.part.is_some() && s.part == inside {
                // The far side of the pane the beam is passing through.
                inside = None;
                travelled += s.t + RESTART_M;
                from += dir * (s.t + RESTART_M);
                continue;
            }
            let range = travelled + s.t;
            if layer == 0 {
                (first_t, first_id) = (range, s.id);
            }
            if range < self.min_range_m {
                break;
            }
            let cos = s.normal.dot(dir).abs() as f64;
            let p_return = (1.0 - r.returns.grazing_dropout(cos))
                * r.returns.detection(
                    r.returns.reflectivity(s.material),
                    range as f64,
                    cos,
                    transmission,
                );
            match r.returns.fate(s.material, p_return, rng.unit()) {
                Fate::Return => {
                    let sigma = r
                        .noise
                        .sigma_m(self.sigma0_m, range as f64, cos, divergence_rad);
                    returned = Some((range + (sigma * g) as f32, s.label));
                    break;
                }
                Fate::PassThrough => {
                    transmission *= r.returns.glass_pass_probability.powi(2);
                    inside = s.part;
                    travelled += s.t + RESTART_M;
                    from += dir * (s.t + RESTART_M);
                    layer += 1;
                }
                Fate::Lost => break,
            }
        }
        match returned {
            Some((range, label)) => Beam {
                point: d * range,
                label,
                first_t,
                first_id,
                from_first: layer == 0,
            },
            None => Beam {
                point: r.no_echo_range_m.map_or(Vec3::NAN, |e| d * e as f32),
                label: Label::default(),
                first_t,
                first_id,
                from_first: false,
            },
        }
    }
}
