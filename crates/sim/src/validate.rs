//! Checking a [`WorldSpec`]: sizes, unique ids, references between entities (a door's wall, a
//! free space's door), finite and sensible numbers.

use crate::error::{check_finite, check_range, Result, SimError};
use crate::spec::{BoxSpec, DoorSpec, HingeEnd, WorldSpec};
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
