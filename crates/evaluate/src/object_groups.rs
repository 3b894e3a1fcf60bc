//! The building's boxes grouped into objects (see `obstacles`): boxes of one name and class
//! that touch are one object (a table and its legs, a chair's seat, backrest and legs); boxes
//! of one name standing apart are objects of their own (the generator's "clutter" boxes, a
//! user's several "crate"s).

use glam::DVec2;
use scanner::Furniture;
use semantic::{convex_intersection_area, OrientedBox};

/// Boxes within this of each other touch (m): a leg under a table's top, a backrest over a seat
/// (the generator's chairs leave 2 cm between them).
const TOUCH_M: f64 = 0.05;

/// The boxes' indices, grouped into objects, each with its name: the boxes' name (or
/// `boxes[i]` for an unnamed box), and for a second or later group of one name, ` #2`, ` #3`...
pub(crate) fn object_groups(boxes: &[Furniture]) -> Vec<(String, Vec<usize>)> {
    let key = |i: usize| {
        if boxes[i].name.is_empty() {
            format!("boxes[{i}]")
        } else {
            boxes[i].name.clone()
        }
    };
    // Union-find over the touching pairs of one name and class.
    let mut parent: Vec<usize> = (0..boxes.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let grown = |i: usize| {
        let b = &boxes[i];
        let g = OrientedBox {
            center_m: b.center_m,
            size_m: [
                b.size_m[0] + 2.0 * TOUCH_M,
                b.size_m[1] + 2.0 * TOUCH_M,
                b.size_m[2],
            ],
            yaw_deg: b.yaw_deg,
        };
        (g.corners_xy().map(DVec2::from_array), g.z_range_m())
    };
    for i in 0..boxes.len() {
        for j in i + 1..boxes.len() {
            if boxes[i].class != boxes[j].class || key(i) != key(j) {
                continue;
            }
            let ((fi, zi), (fj, zj)) = (grown(i), grown(j));
            let z_touch = zi[0] <= zj[1] + TOUCH_M && zj[0] <= zi[1] + TOUCH_M;
            if z_touch && convex_intersection_area(&fi, &fj) > 0.0 {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    // The groups in the order of their first box; the names numbered from the second group on.
    let mut groups: Vec<(usize, Vec<usize>)> = Vec::new();
    for i in 0..boxes.len() {
        let r = root(&mut parent, i);
        match groups.iter_mut().find(|g| g.0 == r) {
            Some(g) => g.1.push(i),
            None => groups.push((r, vec![i])),
        }
    }
    let mut seen: Vec<String> = Vec::new();
    groups
        .into_iter()
        .map(|(_, members)| {
            let name = key(members[0]);
            let n = seen.iter().filter(|s| **s == name).count();
            seen.push(name.clone());
            let shown = if n == 0 {
                name
            } else {
                format!("{name} #{}", n + 1)
            };
            (shown, members)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxed(name: &str, center_m: [f64; 3], size_m: [f64; 3]) -> Furniture {
        Furniture {
            name: name.into(),
            class: cloud::EntityClass::Furniture,
            material: Default::default(),
            center_m,
            size_m,
            yaw_deg: 0.0,
        }
    }

    /// Regression (the mixed style's generator names every box of clutter "clutter": mixed-241
    /// of seeds 241-245 held 15, scored as one object): boxes of one name apart are objects of
    /// their own; a table's top and its legs, touching, are one.
    #[test]
    fn boxes_of_one_name_are_one_object_only_where_they_touch() {
        let boxes = vec![
            boxed("clutter", [0.0, 0.0, 0.25], [0.5, 0.5, 0.5]),
            boxed("table", [3.0, 0.0, 0.72], [1.2, 0.8, 0.04]),
            boxed("clutter", [1.5, 0.0, 0.25], [0.5, 0.5, 0.5]),
            boxed("table", [2.45, 0.35, 0.35], [0.05, 0.05, 0.7]),
            boxed("table", [3.55, -0.35, 0.35], [0.05, 0.05, 0.7]),
            boxed("", [5.0, 0.0, 0.25], [0.5, 0.5, 0.5]),
        ];
        let groups = object_groups(&boxes);
        assert_eq!(
            groups,
            vec![
                ("clutter".to_string(), vec![0]),
                ("table".to_string(), vec![1, 3, 4]),
                ("clutter #2".to_string(), vec![2]),
                ("boxes[5]".to_string(), vec![5]),
            ]
        );
    }
}
