//! Evaluation of the floor and the ceiling: found, and at the right height.

use crate::config::EvalConfig;
use crate::score::ClassScore;
use crate::truth::Truth;
use crate::Evaluation;
use cloud::EntityClass;
use scanner::Building;
use semantic::SemanticMap;

/// Scores the floor and the ceiling: expected (where the scans saw enough of them), and
/// matched where the map's entity lies within `max_height_error_m` of the true height.
pub(crate) fn evaluate_slabs(
    ev: &mut Evaluation,
    map: &SemanticMap,
    building: &Building,
    t: &Truth,
    c: &EvalConfig,
) {
    let f = &building.floor;
    let (cx, cy) = (
        (f.min_m[0] + f.max_m[0]) / 2.0,
        (f.min_m[1] + f.max_m[1]) / 2.0,
    );
    for (class, name, z) in [
        (EntityClass::Floor, "floor", 0.0),
        (EntityClass::Ceiling, "ceiling", building.ceiling.height_m),
    ] {
        let want = usize::from(!t.observed || t.count(name) >= c.min_points);
        let found: Vec<_> = map.of_class(class).collect();
        let truth_z = t.to_map(cx, cy, z).z;
        let err = found
            .iter()
            .map(|e| {
                let [b, t] = e.geometry.z_range_m();
                (if class == EntityClass::Floor { t } else { b }) - truth_z
            })
            .min_by(|a, b| a.abs().total_cmp(&b.abs()));
        let ok = usize::from(want == 1 && err.is_some_and(|e| e.abs() <= c.max_height_error_m));
        let score = ClassScore::new(want, found.len(), ok);
        if class == EntityClass::Floor {
            ev.floor = score;
            ev.floor_height_error_m = err;
        } else {
            ev.ceiling = score;
            ev.ceiling_height_error_m = err;
        }
        if want == 1 && ok == 0 {
            ev.missed.push(name.into());
        }
    }
}
