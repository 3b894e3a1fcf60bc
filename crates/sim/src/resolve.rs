//! Querying a [`WorldSpec`]: its entities, and scenario references resolved to them (id,
//! machine name, opening name or unique human label).

use crate::error::{Result, SimError};
use crate::spec::{EntityInfo, WorldSpec};
use cloud::EntityClass;
use std::collections::BTreeMap;

impl WorldSpec {
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
}
