//! The generator's styles: the clean style pinned to its original buildings, every style
//! valid and deterministic over 20 seeds, holding what it promises, with nothing standing in
//! anything else.

use cloud::EntityClass;
use scanner::{generate_building, Building, BuildingGeometry, GeneratorConfig, Material, Style};
use std::path::Path;

fn config(style: Style) -> GeneratorConfig {
    GeneratorConfig {
        style,
        ..Default::default()
    }
}

#[test]
fn clean_style_buildings_are_unchanged_from_the_original_generator() {
    // tests/data/clean_seed_N.toml were written by the generator before styles existed.
    for seed in [1u64, 7, 42, 1234] {
        let path = format!(
            "{}/tests/data/clean_seed_{seed}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let pinned = Building::load(Path::new(&path)).expect("pinned building");
        let now = generate_building(seed, &GeneratorConfig::default()).expect("valid");
        assert_eq!(now, pinned, "seed {seed}");
        assert_eq!(
            now,
            generate_building(seed, &config(Style::Clean)).expect("valid")
        );
    }
}

/// The group a part belongs to for the overlap check: a thing's name, a wall, a staircase or
/// a ramp; `None` for slabs, lintels and leaves.
fn group(b: &Building, name: &str) -> Option<String> {
    if let Some(i) = name
        .strip_prefix("boxes[")
        .and_then(|s| s.strip_suffix(']'))
    {
        let i: usize = i.parse().ok()?;
        return Some(format!("thing {}", b.boxes[i].name));
    }
    if name.starts_with("walls[") && !name.contains('.') {
        return Some("wall".into());
    }
    (name.starts_with("stairs[") || name.starts_with("ramps[")).then(|| name.to_string())
}

/// Pairs of parts of different groups whose solids overlap (by more than 1 mm), except a
/// beam resting on a column and walls meeting walls.
fn overlaps(b: &Building) -> Vec<String> {
    let g = BuildingGeometry::new(b);
    let name = |id: u32| g.entities()[id as usize - 1].name.clone();
    let parts: Vec<_> = g
        .parts()
        .iter()
        .filter_map(|p| Some((group(b, &name(p.label.entity))?, p)))
        .collect();
    let mut bad = Vec::new();
    for (i, (ga, a)) in parts.iter().enumerate() {
        for (gb, p) in &parts[i + 1..] {
            let classes = [a.label.class, p.label.class];
            if ga == gb
                || (ga == "wall" && gb == "wall")
                || (classes.contains(&EntityClass::Beam) && classes.contains(&EntityClass::Column))
            {
                continue;
            }
            let z = |q: &scanner::BoxPart| {
                let r = if q.pitch_rad == 0.0 {
                    q.half_extents_m.z
                } else {
                    q.half_extents_m.length()
                };
                (q.center_m.z - r, q.center_m.z + r)
            };
            let ((a0, a1), (b0, b1)) = (z(a), z(p));
            if a1 <= b0 + 1e-3 || b1 <= a0 + 1e-3 {
                continue;
            }
            if rect_overlap(a, p) {
                bad.push(format!(
                    "{} / {}",
                    name(a.label.entity),
                    name(p.label.entity)
                ));
            }
        }
    }
    bad
}

fn rect_overlap(a: &scanner::BoxPart, b: &scanner::BoxPart) -> bool {
    let corners = |p: &scanner::BoxPart| {
        let (s, c) = (p.yaw_rad.sin(), p.yaw_rad.cos());
        let hx =
            p.half_extents_m.x * p.pitch_rad.cos() + p.half_extents_m.z * p.pitch_rad.sin().abs();
        let hy = p.half_extents_m.y;
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(u, v): (f32, f32)| {
            [
                p.center_m.x + c * u * hx - s * v * hy,
                p.center_m.y + s * u * hx + c * v * hy,
            ]
        })
    };
    let axes = |p: &scanner::BoxPart| {
        let (s, c) = (p.yaw_rad.sin(), p.yaw_rad.cos());
        [[c, s], [-s, c]]
    };
    let (ca, cb) = (corners(a), corners(b));
    axes(a).into_iter().chain(axes(b)).all(|ax| {
        let proj = |pts: &[[f32; 2]; 4]| {
            pts.iter()
                .map(|q| q[0] * ax[0] + q[1] * ax[1])
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                })
        };
        let ((a0, a1), (b0, b1)) = (proj(&ca), proj(&cb));
        a1 > b0 + 1e-3 && b1 > a0 + 1e-3
    })
}

fn count(b: &Building, class: EntityClass) -> usize {
    let mut names: Vec<&str> = b
        .boxes
        .iter()
        .filter(|x| x.class == class)
        .map(|x| x.name.as_str())
        .collect();
    names.sort_unstable();
    names.dedup();
    names.len()
}

fn check_style(style: Style, mut promise: impl FnMut(&Building) -> Result<(), String>) {
    let cfg = config(style);
    for seed in 0..20u64 {
        let b =
            generate_building(seed, &cfg).unwrap_or_else(|e| panic!("{style} seed {seed}: {e}"));
        assert_eq!(
            b,
            generate_building(seed, &cfg).expect("valid"),
            "{style} seed {seed}: not deterministic"
        );
        if let Err(e) = promise(&b) {
            panic!("{style} seed {seed}: {e}");
        }
        let bad = overlaps(&b);
        assert!(bad.is_empty(), "{style} seed {seed}: overlapping {bad:?}");
    }
}

#[test]
fn office_buildings_have_furniture_on_legs_cabinets_glass_and_a_partial_partition() {
    let mut two_stairs = 0;
    check_style(Style::Office, |b| {
        let legs = b
            .boxes
            .iter()
            .filter(|x| x.name.starts_with("desk") && x.size_m[0] < 0.1)
            .count();
        let glass_wall = b.walls.iter().any(|w| w.material == Material::Glass);
        let glass_door = b.walls.iter().flat_map(|w| &w.doors).any(|d| {
            d.leaf
                .as_ref()
                .is_some_and(|l| l.material == Material::Glass)
        });
        let partial = b.walls.iter().any(|w| w.height_m.is_some_and(|h| h < 1.6));
        two_stairs += usize::from(b.stairs.len() >= 2);
        match () {
            _ if legs < 4 => Err(format!("{legs} desk legs")),
            _ if !b.boxes.iter().any(|x| x.name.starts_with("chair")) => Err("no chair".into()),
            _ if count(b, EntityClass::Obstacle) < 1 => Err("no cabinet".into()),
            _ if !glass_wall && !glass_door => Err("no glass".into()),
            _ if !partial => Err("no partial-height partition".into()),
            _ if b.stairs.is_empty() => Err("no staircase".into()),
            _ if !b.boxes.iter().any(|x| x.name == "doorway crate") => {
                Err("no doorway clutter".into())
            }
            _ => Ok(()),
        }
    });
    assert!(
        two_stairs >= 5,
        "only {two_stairs} of 20 offices have two staircases"
    );
}

#[test]
fn garage_buildings_have_pillars_cars_beams_a_ramp_and_stairs() {
    check_style(Style::Garage, |b| {
        let cars = b
            .boxes
            .iter()
            .filter(|x| x.name.starts_with("car "))
            .map(|x| &x.name)
            .collect::<std::collections::BTreeSet<_>>()
            .len();
        let tyres = b
            .boxes
            .iter()
            .filter(|x| x.name.starts_with("car ") && x.material == Material::Dark)
            .count();
        match () {
            _ if count(b, EntityClass::Column) < 4 => {
                Err(format!("{} pillars", count(b, EntityClass::Column)))
            }
            _ if cars < 2 || tyres < 8 => Err(format!("{cars} cars, {tyres} dark tyres")),
            _ if count(b, EntityClass::Beam) < 1 => Err("no beam".into()),
            _ if b.ramps.len() != 1 => Err(format!("{} ramps", b.ramps.len())),
            _ if b.stairs.is_empty() => Err("no staircase".into()),
            _ => Ok(()),
        }
    });
}

#[test]
fn hall_buildings_are_wide_with_walls_not_at_right_angles_and_pillars() {
    check_style(Style::Hall, |b| {
        let oblique = b.walls.iter().any(|w| {
            let a = (w.end_m[1] - w.start_m[1])
                .atan2(w.end_m[0] - w.start_m[0])
                .to_degrees()
                .rem_euclid(90.0);
            a > 3.0 && a < 87.0
        });
        let f = &b.floor;
        let area = (f.max_m[0] - f.min_m[0]) * (f.max_m[1] - f.min_m[1]);
        match () {
            _ if !oblique => Err("every wall at a right angle".into()),
            _ if area < 150.0 => Err(format!("{area:.0} m² only")),
            _ if count(b, EntityClass::Column) < 2 => Err("fewer than 2 pillars".into()),
            _ if count(b, EntityClass::Furniture) < 2 => Err("no furniture".into()),
            _ if b.walls.iter().flat_map(|w| &w.doors).count() < 1 => Err("no door".into()),
            _ => Ok(()),
        }
    });
}

#[test]
fn mixed_style_gives_each_seed_one_of_the_other_styles_buildings() {
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..20u64 {
        let style = scanner::resolve_style(Style::Mixed, seed);
        assert_ne!(style, Style::Mixed);
        let mixed = generate_building(seed, &config(Style::Mixed)).expect("valid");
        assert_eq!(
            mixed,
            generate_building(seed, &config(style)).expect("valid"),
            "seed {seed}"
        );
        seen.insert(style.name());
    }
    assert!(seen.len() >= 3, "mixed picks only {seen:?}");
}
