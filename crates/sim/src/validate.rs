//! Checking and querying a [`WorldSpec`]: unique ids, references between entities (a door's
//! wall, a free space's door), finite and sensible numbers, and resolving scenario references
//! (id, machine name, opening name or unique human label).

use crate::error::{check_finite, check_range, Result, SimError};
use crate::spec::{BoxSpec, DoorSpec, EntityInfo, HingeEnd, WorldSpec};
use cloud::EntityClass;
use std::collections::BTreeMap;

/// Largest half extent accepted (metres).
const MAX_HALF_M: f64 = 500.0;

impl WorldSpec {
    /// The most static boxes (fixed boxes, stair steps and landings together) a world may
    /// have. The static geometry is merged into one compound collider when it overlaps much,
    /// so memory grows linearly with the count (about 1 kB per box).
    pub const MAX_STATIC_BOXES: usize = 100_000;
    /// The most door leaves a world may have (each is a dynamic body on a joint).
    pub const MAX_DOORS: usize = 2_000;
    /// The most door free-space sensors a world may have.
    pub const MAX_FREE_SPACES: usize = 2_000;
    /// The most steps a staircase may have.
    pub const MAX_STEPS: usize = 1_000;

    /// The number of static boxes: fixed boxes, stair steps and landings.
    pub fn static_box_count(&self) -> usize {
        self.fixed.len()
            + self
                .stairs
                .iter()
                .map(|s| s.steps.len() + usize::from(s.landing.is_some()))
                .sum::<usize>()
    }

    /// Fails with [`SimError::TooMany`] when the world has more elements of a kind than a
    /// simulation can hold ([`WorldSpec::MAX_STATIC_BOXES`], [`WorldSpec::MAX_DOORS`],
    /// [`WorldSpec::MAX_FREE_SPACES`], [`WorldSpec::MAX_STEPS`]).
    pub fn check_limits(&self) -> Result<()> {
        let too_many = |element: &str, what: &str, count: usize, limit: usize| {
            if count > limit {
                Err(SimError::TooMany {
                    element: element.to_string(),
                    what: what.to_string(),
                    count,
                    limit,
                })
            } else {
                Ok(())
            }
        };
        for s in &self.stairs {
            too_many(
                &format!("stairs {}", s.name),
                "steps",
                s.steps.len(),
                Self::MAX_STEPS,
            )?;
        }
        too_many(
            "world",
            "static boxes (fixed boxes, stair steps and landings)",
            self.static_box_count(),
            Self::MAX_STATIC_BOXES,
        )?;
        too_many("world", "doors", self.doors.len(), Self::MAX_DOORS)?;
        too_many(
            "world",
            "door free spaces",
            self.free_spaces.len(),
            Self::MAX_FREE_SPACES,
        )
    }

    /// Parses and validates a world spec from JSON; `source` names it in errors.
    pub fn from_json_str(text: &str, source: &str) -> Result<WorldSpec> {
        let spec: WorldSpec = serde_json::from_str(text).map_err(|e| SimError::Syntax {
            source_name: source.to_string(),
            msg: e.to_string(),
        })?;
        spec.validate().map_err(|e| e.in_source(source))?;
        Ok(spec)
    }

    /// Every entity, by ascending id.
    pub fn entities(&self) -> Vec<EntityInfo> {
        let mut map = BTreeMap::new();
        let mut add = |id: u32, class: EntityClass, name: &str, label: &str| {
            map.entry(id).or_insert_with(|| EntityInfo {
                id,
                class,
                name: name.to_string(),
                label: label.to_string(),
            });
        };
        for f in &self.fixed {
            add(f.entity, f.class, &f.name, &f.label);
        }
        for d in &self.doors {
            add(d.entity, EntityClass::Door, &d.name, &d.label);
        }
        for f in &self.free_spaces {
            add(f.entity, EntityClass::FreeSpaceForDoor, &f.name, "");
        }
        for s in &self.stairs {
            add(s.entity, EntityClass::Stairs, &s.name, &s.label);
        }
        map.into_values().collect()
    }

    /// Finds an entity by id (`"17"`), machine name (`walls[4].doors[2].leaf`), opening name
    /// (`walls[4].doors[2]`: the leaf, or the free space of an opening without one), unique
    /// human label (`corridor north`) or location (`door@14.5,1.1`, `stairs@17,4.2`: the
    /// nearest door opening or staircase to that point of the floor plan, within 2 m; the
    /// form that works alike in a building's world and in a semantic map's, whose entities
    /// have only ids). `element` names the reference in errors.
    pub fn resolve(&self, reference: &str, element: &str) -> Result<EntityInfo> {
        let entities = self.entities();
        let r = reference.trim();
        if let Some((kind, at)) = r.split_once('@') {
            return self.locate(kind.trim(), at, element, reference);
        }
        let found = r
            .parse::<u32>()
            .ok()
            .and_then(|id| entities.iter().find(|e| e.id == id))
            .or_else(|| entities.iter().find(|e| e.name == r))
            .or_else(|| {
                let leaf = format!("{r}.leaf");
                let free = format!("{r}.free_space");
                entities
                    .iter()
                    .find(|e| e.name == leaf)
                    .or_else(|| entities.iter().find(|e| e.name == free))
            })
            .or_else(|| {
                let mut it = entities
                    .iter()
                    .filter(|e| !e.label.is_empty() && e.label == r);
                match (it.next(), it.next()) {
                    (Some(e), None) => Some(e),
                    _ => None,
                }
            });
        found.cloned().ok_or_else(|| {
            let names: Vec<&str> = entities
                .iter()
                .filter(|e| !matches!(e.class, EntityClass::Floor | EntityClass::Ceiling))
                .map(|e| e.name.as_str())
                .take(12)
                .collect();
            SimError::UnknownEntity {
                element: element.to_string(),
                reference: reference.to_string(),
                hint: format!(" (known names include: {})", names.join(", ")),
            }
        })
    }

    /// Resolves `door@x,y` / `stairs@x,y` (see [`WorldSpec::resolve`]).
    fn locate(&self, kind: &str, at: &str, element: &str, reference: &str) -> Result<EntityInfo> {
        const MAX_DISTANCE_M: f64 = 2.0;
        let unknown = |hint: &str| SimError::UnknownEntity {
            element: element.to_string(),
            reference: reference.to_string(),
            hint: hint.to_string(),
        };
        let xy: Vec<f64> = at
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| unknown(" (a location is `door@X,Y` or `stairs@X,Y`, in metres)"))?;
        let [x, y] = xy[..] else {
            return Err(unknown(
                " (a location is `door@X,Y` or `stairs@X,Y`, in metres)",
            ));
        };
        if !(x.is_finite() && y.is_finite()) {
            return Err(unknown(" (the location must be finite)"));
        }
        let dist = |c: [f64; 3]| (c[0] - x).hypot(c[1] - y);
        // Candidates: (distance, entity id).
        let candidates: Vec<(f64, u32)> = match kind {
            "door" => self
                .free_spaces
                .iter()
                .map(|f| (dist(f.geometry.center_m), f.door.unwrap_or(f.entity)))
                .chain(self.doors.iter().map(|d| (dist(d.leaf.center_m), d.entity)))
                .collect(),
            "stairs" => self
                .stairs
                .iter()
                .filter_map(|s| {
                    let n = s.steps.len() as f64;
                    let c = s.steps.iter().fold([0.0; 3], |a, st| {
                        let g = st.geometry.center_m;
                        [a[0] + g[0] / n, a[1] + g[1] / n, 0.0]
                    });
                    (n > 0.0).then_some((dist(c), s.entity))
                })
                .collect(),
            _ => return Err(unknown(" (locations name `door@X,Y` or `stairs@X,Y`)")),
        };
        let best = candidates
            .into_iter()
            .filter(|c| c.0 <= MAX_DISTANCE_M)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let id = best.map(|b| b.1).ok_or_else(|| {
            unknown(&format!(
                " (no {kind} within {MAX_DISTANCE_M} m of ({x}, {y}))"
            ))
        })?;
        self.entities()
            .into_iter()
            .find(|e| e.id == id)
            .ok_or_else(|| unknown(""))
    }

    /// Checks sizes ([`WorldSpec::check_limits`]), ids, references and numbers; see
    /// [`SimError`] for what is reported.
    pub fn validate(&self) -> Result<()> {
        self.check_limits()?;
        let mut classes: BTreeMap<u32, (EntityClass, String)> = BTreeMap::new();
        let mut claim = |id: u32, class: EntityClass, name: &str, element: &str| -> Result<()> {
            if id == 0 {
                return Err(invalid(
                    element,
                    "entity id 0 is reserved for \"no entity\"",
                ));
            }
            match classes.get(&id) {
                Some((c, n)) if *c != class || n != name => Err(invalid(
                    element,
                    &format!("entity id {id} is already used by {n} ({})", c.name()),
                )),
                _ => {
                    classes.insert(id, (class, name.to_string()));
                    Ok(())
                }
            }
        };
        // Borrow-friendly: collect names first.
        let fixed_names: Vec<String> = self.fixed.iter().map(|f| f.name.clone()).collect();
        for (i, f) in self.fixed.iter().enumerate() {
            let el = format!("fixed[{i}] ({})", fixed_names[i]);
            claim(f.entity, f.class, &fixed_names[i], &el)?;
            // `unknown` (the shared vocabulary's "no label") was no class of the world before
            // the vocabularies were merged; it stays refused.
            if matches!(
                f.class,
                EntityClass::Door
                    | EntityClass::FreeSpaceForDoor
                    | EntityClass::Robot
                    | EntityClass::Unknown
            ) {
                return Err(invalid(
                    &el,
                    &format!("a fixed box cannot be a {}", f.class.name()),
                ));
            }
            check_box(&el, &f.geometry)?;
        }
        for d in &self.doors {
            let el = format!("door {}", d.name);
            claim(d.entity, EntityClass::Door, &d.name, &el)?;
        }
        for f in &self.free_spaces {
            let el = format!("free space {}", f.name);
            claim(f.entity, EntityClass::FreeSpaceForDoor, &f.name, &el)?;
        }
        for s in &self.stairs {
            let el = format!("stairs {}", s.name);
            claim(s.entity, EntityClass::Stairs, &s.name, &el)?;
        }
        for d in &self.doors {
            self.check_door(d, &classes)?;
        }
        for f in &self.free_spaces {
            let el = format!("free space {}", f.name);
            check_box(&el, &f.geometry)?;
            if let Some(door) = f.door {
                if classes.get(&door).map(|c| c.0) != Some(EntityClass::Door) {
                    return Err(SimError::UnknownEntity {
                        element: format!("{el}.door"),
                        reference: door.to_string(),
                        hint: " (no door has this id)".into(),
                    });
                }
            }
            if let Some(wall) = f.wall {
                if classes.get(&wall).map(|c| c.0) != Some(EntityClass::Wall) {
                    return Err(SimError::UnknownEntity {
                        element: format!("{el}.wall"),
                        reference: wall.to_string(),
                        hint: " (no wall has this id)".into(),
                    });
                }
            }
        }
        for s in &self.stairs {
            let el = format!("stairs {}", s.name);
            if s.steps.is_empty() {
                return Err(invalid(&el, "a staircase needs at least one step"));
            }
            for (k, step) in s.steps.iter().enumerate() {
                if step.index as usize != k {
                    return Err(invalid(
                        &el,
                        &format!("step {k} has index {}; steps must be listed lowest first, indexed 0, 1, 2, ...", step.index),
                    ));
                }
                check_box(&format!("{el}.steps[{k}]"), &step.geometry)?;
            }
            if let Some(l) = &s.landing {
                check_box(&format!("{el}.landing"), l)?;
            }
        }
        Ok(())
    }

    fn check_door(
        &self,
        d: &DoorSpec,
        classes: &BTreeMap<u32, (EntityClass, String)>,
    ) -> Result<()> {
        let el = format!("door {}", d.name);
        if classes.get(&d.wall).map(|c| c.0) != Some(EntityClass::Wall) {
            return Err(SimError::DoorWithoutWall {
                source_name: String::new(),
                door: d.name.clone(),
                wall: d.wall,
            });
        }
        check_box(&el, &d.leaf)?;
        check_finite(&el, "hinge_m", &d.hinge_m)?;
        check_range(
            &el,
            "min_deg",
            d.min_deg,
            -180.0,
            180.0,
            "an angle in [-180, 180]",
        )?;
        check_range(
            &el,
            "max_deg",
            d.max_deg,
            d.min_deg,
            180.0,
            "in [min_deg, 180]",
        )?;
        check_range(
            &el,
            "initial_deg",
            d.initial_deg,
            d.min_deg,
            d.max_deg,
            "within [min_deg, max_deg]",
        )?;
        check_range(
            &el,
            "mass_kg",
            d.mass_kg,
            0.1,
            10_000.0,
            "a leaf of 0.1 kg to 10 t",
        )?;
        check_range(
            &el,
            "damping_per_s",
            d.damping_per_s,
            0.0,
            1000.0,
            "in [0, 1000]",
        )?;
        check_range(
            &el,
            "hinge_friction_nm",
            d.hinge_friction_nm,
            0.0,
            1.0e5,
            "in [0, 1e5]",
        )?;
        if let Some(f) = d.break_force_n {
            check_range(
                &el,
                "break_force_n",
                f,
                1.0,
                1.0e9,
                "a force of 1 N to 1e9 N",
            )?;
        }
        // The hinge must sit at the hinged end of the closed leaf.
        let yaw = d.leaf.yaw_deg.to_radians();
        let sign = match d.hinge_end {
            HingeEnd::Start => -1.0,
            HingeEnd::End => 1.0,
        };
        let hx = d.leaf.half_extents_m[0];
        let end = [
            d.leaf.center_m[0] + sign * hx * yaw.cos(),
            d.leaf.center_m[1] + sign * hx * yaw.sin(),
        ];
        let off = ((end[0] - d.hinge_m[0]).powi(2) + (end[1] - d.hinge_m[1]).powi(2)).sqrt();
        let tol = 0.05 + d.leaf.half_extents_m[1];
        if off > tol {
            return Err(invalid(
                &el,
                &format!("the hinge ({:.3}, {:.3}) is {off:.3} m from the leaf's {:?} end; expected within {tol:.3} m", d.hinge_m[0], d.hinge_m[1], d.hinge_end),
            ));
        }
        Ok(())
    }
}

fn invalid(element: &str, msg: &str) -> SimError {
    SimError::Invalid {
        element: element.to_string(),
        msg: msg.to_string(),
    }
}

fn check_box(element: &str, b: &BoxSpec) -> Result<()> {
    check_finite(element, "center_m", &b.center_m)?;
    check_finite(element, "yaw_deg", &[b.yaw_deg])?;
    check_finite(element, "half_extents_m", &b.half_extents_m)?;
    for h in b.half_extents_m {
        check_range(
            element,
            "half_extents_m",
            h,
            1e-4,
            MAX_HALF_M,
            "half extents must lie in [0.1 mm, 500 m]",
        )?;
    }
    if b.center_m.iter().any(|c| c.abs() > 1.0e5) {
        return Err(invalid(element, "centre more than 100 km from the origin"));
    }
    Ok(())
}
