//! Reading and writing the semantic map file: JSON (pretty), atomic save, and validation with
//! typed errors (unknown classes and relation types, dangling and duplicate ids, a wrong
//! `format` or `version`, entities lacking their class's geometry).

use super::{
    Entity, OrientedBox, RelationType, SemanticMap, MAP_CLASSES, MAP_CLASSES_V1, MAP_FORMAT,
    MAP_VERSION, READ_VERSIONS,
};
use crate::error::{Result, SemanticError};
use cloud::EntityClass;
use std::path::Path;

impl SemanticMap {
    /// Pretty JSON text.
    pub fn to_json_string(&self) -> String {
        // Serialising plain structs of numbers and strings cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Writes the map as JSON, atomically (a temporary file renamed over `path`).
    pub fn save(&self, path: &Path) -> Result<()> {
        self.validate(path)?;
        let mut text = self.to_json_string();
        text.push('\n');
        cloud::write_bytes_atomically(path, text.as_bytes())?;
        Ok(())
    }

    /// Reads and validates a map file.
    pub fn load(path: &Path) -> Result<SemanticMap> {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        SemanticMap::from_json_str(&text, path)
    }

    /// Parses and validates map JSON; `path` only names the source in errors.
    ///
    /// Unknown classes and relation types, dangling or duplicate ids, a wrong `format` or
    /// `version` and entities lacking their class's geometry are typed errors. A version 1 file
    /// (no obstacles, columns, beams or `near`), version 2 file (no `floor` section) or
    /// version 3 file (no ramps) is read as the current version: each is a subset of it.
    pub fn from_json_str(text: &str, path: &Path) -> Result<SemanticMap> {
        let syntax = |e: serde_json::Error| SemanticError::Syntax {
            path: path.to_path_buf(),
            msg: e.to_string(),
        };
        let value: serde_json::Value = serde_json::from_str(text).map_err(syntax)?;
        precheck(&value, path)?;
        let mut map: SemanticMap = serde_json::from_value(value).map_err(syntax)?;
        // Versions 1-3 are read as the current version (their content is a subset).
        map.version = MAP_VERSION;
        map.validate(path)?;
        Ok(map)
    }

    /// Checks ids, relations and per-class geometry; `path` only names the map in errors.
    pub fn validate(&self, path: &Path) -> Result<()> {
        if self.format != MAP_FORMAT {
            return Err(SemanticError::WrongFormat {
                path: path.into(),
                found: self.format.clone(),
                expected: MAP_FORMAT,
            });
        }
        if self.version != MAP_VERSION {
            return Err(SemanticError::UnsupportedVersion {
                path: path.into(),
                found: self.version.into(),
                supported: MAP_VERSION,
            });
        }
        let mut seen = std::collections::HashSet::new();
        for (index, e) in self.entities.iter().enumerate() {
            if !MAP_CLASSES.contains(&e.class) {
                return Err(unknown_class(path, index, e.class.name()));
            }
            if e.id == 0 || !seen.insert(e.id) {
                return Err(SemanticError::BadId {
                    path: path.into(),
                    index,
                    id: e.id,
                    problem: if e.id == 0 {
                        "0 (ids start at 1)"
                    } else {
                        "used twice"
                    },
                });
            }
            check_entity(e).map_err(|msg| SemanticError::InvalidEntity {
                path: path.into(),
                id: e.id,
                class: e.class.name(),
                msg,
            })?;
        }
        for (index, r) in self.relations.iter().enumerate() {
            for id in [r.a, r.b] {
                if !seen.contains(&id) {
                    return Err(SemanticError::DanglingId {
                        path: path.into(),
                        index,
                        kind: r.kind.name().into(),
                        id,
                    });
                }
            }
        }
        if !self.input_from_map.iter().all(|v| v.is_finite()) {
            return Err(SemanticError::Syntax {
                path: path.into(),
                msg: "input_from_map holds a non-finite number".into(),
            });
        }
        Ok(())
    }
}

/// Typed errors for unknown names and a wrong header, before serde sees the structure.
fn precheck(value: &serde_json::Value, path: &Path) -> Result<()> {
    let format = value.get("format").and_then(|v| v.as_str()).unwrap_or("");
    if format != MAP_FORMAT {
        return Err(SemanticError::WrongFormat {
            path: path.into(),
            found: format.into(),
            expected: MAP_FORMAT,
        });
    }
    let version = value.get("version").and_then(|v| v.as_u64()).unwrap_or(0);
    if !READ_VERSIONS.iter().any(|&v| u64::from(v) == version) {
        return Err(SemanticError::UnsupportedVersion {
            path: path.into(),
            found: version,
            supported: MAP_VERSION,
        });
    }
    // Version 1 knew fewer classes and relation types.
    let v1 = version == 1;
    let classes: &[EntityClass] = match version {
        1 => &MAP_CLASSES_V1,
        // Versions 2 and 3 knew every class but the last, `ramp`.
        2 | 3 => &MAP_CLASSES[..MAP_CLASSES.len() - 1],
        _ => &MAP_CLASSES,
    };
    let kinds: &[RelationType] = if v1 {
        &RelationType::ALL[..7]
    } else {
        &RelationType::ALL
    };
    let names = |it: &mut dyn Iterator<Item = &'static str>| it.collect::<Vec<_>>().join(", ");
    if let Some(list) = value.get("entities").and_then(|v| v.as_array()) {
        for (index, e) in list.iter().enumerate() {
            if let Some(class) = e.get("class").and_then(|c| c.as_str()) {
                if !classes.iter().any(|c| c.name() == class) {
                    return Err(SemanticError::UnknownClass {
                        path: path.into(),
                        index,
                        class: class.into(),
                        known: names(&mut classes.iter().map(|c| c.name())),
                    });
                }
            }
        }
    }
    if let Some(list) = value.get("relations").and_then(|v| v.as_array()) {
        for (index, r) in list.iter().enumerate() {
            if let Some(kind) = r.get("type").and_then(|c| c.as_str()) {
                if !kinds.iter().any(|c| c.name() == kind) {
                    return Err(SemanticError::UnknownRelation {
                        path: path.into(),
                        index,
                        kind: kind.into(),
                        known: names(&mut kinds.iter().map(|c| c.name())),
                    });
                }
            }
        }
    }
    Ok(())
}

/// The error for an entity of a class that map entities do not have.
fn unknown_class(path: &Path, index: usize, class: &str) -> SemanticError {
    SemanticError::UnknownClass {
        path: path.into(),
        index,
        class: class.into(),
        known: MAP_CLASSES.map(EntityClass::name).join(", "),
    }
}

fn check_entity(e: &Entity) -> std::result::Result<(), String> {
    if !e.geometry.is_finite() {
        return Err("geometry holds a non-finite or negative number".into());
    }
    if !(0.0..=1.0).contains(&e.confidence) {
        return Err(format!("confidence {} is outside 0..1", e.confidence));
    }
    let need = |present: bool, what: &str| {
        if present {
            Ok(())
        } else {
            Err(format!(
                "a {} entity needs its `{what}` section",
                e.class.name()
            ))
        }
    };
    match e.class {
        EntityClass::Wall => {
            need(e.wall.is_some(), "wall")?;
            if let Some(w) = &e.wall {
                let ok = w.segment_m.iter().flatten().all(|v| v.is_finite())
                    && w.thickness_m.is_finite()
                    && w.thickness_m > 0.0
                    && w.z_range_m[0] <= w.z_range_m[1]
                    && w.solid_boxes.iter().all(OrientedBox::is_finite);
                if !ok {
                    return Err("wall segment, thickness or z range is invalid".into());
                }
            }
        }
        EntityClass::Door => {
            need(e.door.is_some(), "door")?;
            if let Some(d) = &e.door {
                let len = d.hinge_axis.iter().map(|v| v * v).sum::<f64>().sqrt();
                if !((len - 1.0).abs() < 1e-3 && d.hinge_m.iter().all(|v| v.is_finite())) {
                    return Err("hinge axis must be a unit vector and the hinge finite".into());
                }
            }
        }
        EntityClass::Stairs => {
            need(e.stairs.is_some(), "stairs")?;
            if let Some(s) = &e.stairs {
                if s.steps.len() != s.step_count as usize {
                    return Err(format!(
                        "step_count {} but {} step boxes",
                        s.step_count,
                        s.steps.len()
                    ));
                }
                if !s.steps.iter().chain(&s.landing).all(OrientedBox::is_finite) {
                    return Err("a step box is invalid".into());
                }
            }
        }
        EntityClass::FreeSpaceForDoor => need(e.opening.is_some(), "opening")?,
        EntityClass::Floor => {
            if let Some(f) = &e.floor {
                if !(f.parts.iter().all(OrientedBox::is_finite)
                    && (0.0..=1.0).contains(&f.coverage))
                {
                    return Err("a floor part is invalid or the coverage is outside 0..1".into());
                }
            }
        }
        EntityClass::Obstacle | EntityClass::Column | EntityClass::Beam => {
            need(e.obstacle.is_some(), "obstacle")?;
            if let Some(o) = &e.obstacle {
                let ok = o.z_range_m.iter().all(|v| v.is_finite())
                    && o.z_range_m[0] <= o.z_range_m[1]
                    && o.clearance_m.is_finite()
                    && (0.0..=1.0).contains(&o.fill)
                    && o.hull_m.iter().flatten().all(|v| v.is_finite());
                if !ok {
                    return Err("obstacle z range, clearance, fill or hull is invalid".into());
                }
            }
        }
        EntityClass::Ramp => {
            let [length, _, rise] = e.geometry.size_m;
            if !(length > 0.0 && rise > 0.0 && rise <= length) {
                return Err(format!(
                    "a ramp rises along its box's x axis: its length ({length} m) and rise \
                     ({rise} m) must be above 0, the rise at most the length"
                ));
            }
        }
        _ => {}
    }
    Ok(())
}
