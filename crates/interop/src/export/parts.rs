//! The world as the exports see it: every static box with the element name it gets
//! (`wall_12`, `stairs_30_step_0`), each door's hinge and leaf relative to it, the physics
//! semsim gives them (as `sim::WorldConfig::default()` and the rapier world set them up), and
//! the relations between entities.

use cloud::EntityClass;
use semantic::{Relation, RelationType};
use sim::{BoxSpec, DoorSpec, WorldConfig, WorldSpec};
use std::collections::BTreeSet;

/// A static box of the world: a fixed box, a stair step or a landing.
pub(crate) struct StaticBox<'a> {
    /// Its entity's id.
    pub entity: u32,
    /// Its entity's class.
    pub class: EntityClass,
    /// Its entity's machine name (as in the world spec).
    pub entity_name: &'a str,
    /// Its entity's human label (may be empty).
    pub label: &'a str,
    /// The element name: `<class>_<id>`, with `_<k>` for the k-th box of an entity with
    /// several, `_step_<i>` / `_landing` for stairs.
    pub part: String,
    /// The box.
    pub geometry: &'a BoxSpec,
}

/// `<class>_<id>`: the name an entity's elements start with (`wall_12`, `door_17`).
pub(crate) fn element_name(class: EntityClass, id: u32) -> String {
    format!("{}_{id}", class.name())
}

/// Every static box, fixed boxes first (in the spec's order), then each staircase's steps
/// and landing.
pub(crate) fn static_boxes(spec: &WorldSpec) -> Vec<StaticBox<'_>> {
    let mut count = std::collections::HashMap::<u32, usize>::new();
    for f in &spec.fixed {
        *count.entry(f.entity).or_default() += 1;
    }
    let mut seen = std::collections::HashMap::<u32, usize>::new();
    let mut out = Vec::with_capacity(spec.static_box_count());
    for f in &spec.fixed {
        let k = seen.entry(f.entity).or_default();
        let base = element_name(f.class, f.entity);
        let part = if count.get(&f.entity).copied().unwrap_or(1) > 1 {
            format!("{base}_{k}")
        } else {
            base
        };
        *k += 1;
        out.push(StaticBox {
            entity: f.entity,
            class: f.class,
            entity_name: &f.name,
            label: &f.label,
            part,
            geometry: &f.geometry,
        });
    }
    for s in &spec.stairs {
        let base = element_name(EntityClass::Stairs, s.entity);
        for step in &s.steps {
            out.push(StaticBox {
                entity: s.entity,
                class: EntityClass::Stairs,
                entity_name: &s.name,
                label: &s.label,
                part: format!("{base}_step_{}", step.index),
                geometry: &step.geometry,
            });
        }
        if let Some(l) = &s.landing {
            out.push(StaticBox {
                entity: s.entity,
                class: EntityClass::Stairs,
                entity_name: &s.name,
                label: &s.label,
                part: format!("{base}_landing"),
                geometry: l,
            });
        }
    }
    out
}

/// The static boxes grouped by entity, entities in the order of their first box (an
/// entity's boxes need not be next to each other in the spec).
pub(crate) fn by_entity<'b, 'a>(boxes: &'b [StaticBox<'a>]) -> Vec<Vec<&'b StaticBox<'a>>> {
    let mut index = std::collections::HashMap::<u32, usize>::new();
    let mut groups: Vec<Vec<&StaticBox>> = vec![];
    for b in boxes {
        let i = *index.entry(b.entity).or_insert_with(|| {
            groups.push(vec![]);
            groups.len() - 1
        });
        groups[i].push(b);
    }
    groups
}

/// A door's hinge point: (x, y) of the hinge at the leaf centre's height (where sim puts the
/// leaf body's origin).
pub(crate) fn hinge_point(d: &DoorSpec) -> [f64; 3] {
    [d.hinge_m[0], d.hinge_m[1], d.leaf.center_m[2]]
}

/// The closed leaf's centre relative to the hinge point.
pub(crate) fn leaf_offset(d: &DoorSpec) -> [f64; 3] {
    let h = hinge_point(d);
    let c = d.leaf.center_m;
    [c[0] - h[0], c[1] - h[1], c[2] - h[2]]
}

/// The leaf's moment of inertia about the hinge axis (kg m^2): a uniform box, by the parallel
/// axis theorem.
pub(crate) fn leaf_inertia_about_hinge(d: &DoorSpec) -> f64 {
    let [hx, hy, _] = d.leaf.half_extents_m;
    let o = leaf_offset(d);
    d.mass_kg * ((4.0 * hx * hx + 4.0 * hy * hy) / 12.0 + o[0] * o[0] + o[1] * o[1])
}

/// The hinge's viscous damping (N m s/rad) equivalent to sim's angular damping of the leaf
/// body (1/s): damping rate x moment of inertia about the hinge.
pub(crate) fn hinge_damping_nms(d: &DoorSpec) -> f64 {
    d.damping_per_s * leaf_inertia_about_hinge(d)
}

/// The principal moments of inertia of a uniform box (kg m^2) about its centre.
pub(crate) fn box_inertia(mass_kg: f64, half_extents_m: [f64; 3]) -> [f64; 3] {
    let [x, y, z] = half_extents_m.map(|h| 4.0 * h * h);
    [
        mass_kg * (y + z) / 12.0,
        mass_kg * (x + z) / 12.0,
        mass_kg * (x + y) / 12.0,
    ]
}

/// A uniform cylinder's moments of inertia (kg m^2): (about its axis, about a diameter).
pub(crate) fn cylinder_inertia(mass_kg: f64, radius_m: f64, length_m: f64) -> (f64, f64) {
    let r2 = radius_m * radius_m;
    (
        mass_kg * r2 / 2.0,
        mass_kg * (3.0 * r2 + length_m * length_m) / 12.0,
    )
}

/// The physics settings exported: sim's defaults (time step, gravity, friction).
pub(crate) fn physics() -> WorldConfig {
    WorldConfig::default()
}

/// The given relations plus those the world implies (a door `connected_via_joint` to its
/// wall; a free space `available_inside` its wall and its door `available_inside` it), each
/// once, sorted.
pub(crate) fn relations(spec: &WorldSpec, given: &[Relation]) -> Vec<Relation> {
    let mut set: BTreeSet<(u32, u32, &'static str)> = BTreeSet::new();
    let mut out = vec![];
    let mut add = |kind: RelationType, a: u32, b: u32| {
        if set.insert((a, b, kind.name())) {
            out.push(Relation { kind, a, b });
        }
    };
    for r in given {
        add(r.kind, r.a, r.b);
    }
    for d in &spec.doors {
        add(RelationType::ConnectedViaJoint, d.entity, d.wall);
    }
    for f in &spec.free_spaces {
        if let Some(w) = f.wall {
            add(RelationType::AvailableInside, f.entity, w);
        }
        if let Some(d) = f.door {
            add(RelationType::AvailableInside, d, f.entity);
        }
    }
    out.sort_by_key(|r| (r.a, r.b, r.kind.name()));
    out
}

/// An sRGB colour (0-255) as linear RGB (0-1), for glTF's `baseColorFactor`.
pub(crate) fn linear_rgb(srgb: [u8; 3]) -> [f64; 3] {
    srgb.map(|c| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    })
}

/// The class's colour (as in semsim's renders) as sRGB 0-1, for MJCF and SDF colours.
pub(crate) fn srgb(class: EntityClass) -> [f64; 3] {
    semantic::class_color(class).map(|c| c as f64 / 255.0)
}
