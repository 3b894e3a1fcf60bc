//! 3DTK's 2009 corridor (three real scans, placed with 3DTK's registration): floor, ceiling,
//! both corridor walls and door openings along them. Skips with a message where the data
//! folder (`../shared/data/real/3dtk-corridor` beside the checkout) is absent.

use glam::DVec2;
use semantic::{build_semantic_map, EntityClass, RelationType, SemanticConfig};

#[test]
fn threedtk_corridor_has_floor_ceiling_two_walls_and_doors() {
    let Some(cloud) = fixtures::threedtk_corridor() else {
        eprintln!("skipping: 3DTK corridor data not found (../shared/data/real/3dtk-corridor)");
        return;
    };
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    // The world frame is scan000's, pitched about 3 degrees: levelled.
    assert!(
        out.tilt_deg > 1.5 && out.tilt_deg < 4.5,
        "tilt {}",
        out.tilt_deg
    );
    let (floor, ceiling) = (
        out.floor_z_m.expect("floor"),
        out.ceiling_z_m.expect("ceiling"),
    );
    assert!(
        (2.0..3.0).contains(&(ceiling - floor)),
        "room height {}",
        ceiling - floor
    );
    assert_eq!(out.map.of_class(EntityClass::Floor).count(), 1);
    assert_eq!(out.map.of_class(EntityClass::Ceiling).count(), 1);
    // The corridor: two long walls, nearly parallel, 2 to 3 m apart, each with door openings.
    let walls: Vec<_> = out
        .map
        .of_class(EntityClass::Wall)
        .filter_map(|e| {
            e.wall.as_ref().map(|w| {
                (
                    e.id,
                    DVec2::from_array(w.segment_m[0]),
                    DVec2::from_array(w.segment_m[1]),
                )
            })
        })
        .filter(|(_, a, b)| a.distance(*b) >= 5.0)
        .collect();
    let openings = |id: u32| {
        out.map
            .relations_of(RelationType::AvailableInside)
            .filter(|r| {
                r.b == id
                    && out
                        .map
                        .entity(r.a)
                        .is_some_and(|e| e.class == EntityClass::FreeSpaceForDoor)
            })
            .count()
    };
    // The pair with the longest shorter wall.
    let mut corridor: Option<(u32, u32, f64, f64, f64)> = None;
    for (i, (ia, a0, a1)) in walls.iter().enumerate() {
        for (ib, b0, b1) in &walls[i + 1..] {
            let (da, db) = ((*a1 - *a0).normalize(), (*b1 - *b0).normalize());
            let angle = da.dot(db).abs().min(1.0).acos().to_degrees();
            let mid = (*b0 + *b1) / 2.0;
            let gap = (mid - *a0).perp_dot(da).abs();
            let shorter = a0.distance(*a1).min(b0.distance(*b1));
            if angle < 5.0 && (2.0..3.0).contains(&gap) && corridor.is_none_or(|c| shorter > c.4) {
                corridor = Some((*ia, *ib, angle, gap, shorter));
            }
        }
    }
    let (a, b, angle, gap, shorter) = corridor.expect("two long parallel walls 2-3 m apart");
    assert!(
        shorter >= 10.0,
        "the corridor walls are only {shorter:.1} m long"
    );
    eprintln!(
        "corridor walls {a} and {b}: {angle:.1} deg apart, {gap:.2} m wide, {shorter:.1} m long at least; {} and {} door openings; {} walls, {} openings, {} doors in all",
        openings(a),
        openings(b),
        out.map.of_class(EntityClass::Wall).count(),
        out.map.of_class(EntityClass::FreeSpaceForDoor).count(),
        out.map.of_class(EntityClass::Door).count()
    );
    assert!(
        openings(a) >= 1 && openings(b) >= 1,
        "door openings along both corridor walls"
    );
}
