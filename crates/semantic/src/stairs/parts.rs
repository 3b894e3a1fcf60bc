//! A blob's parts. Blobs join pixels within two pixels of each other, over every return, and a
//! realistic laser leaves returns on no surface where a beam straddles a depth edge (mixed
//! pixels, see `surface`): a chair 0.4 m in front of a staircase's side face throws a trail of
//! them towards the face and joins the two in one blob, whose profile then mixes the chair's
//! seat and the desk beside it with the steps. The parts are the blob's surface returns' pixels
//! joined the same way; every return of the blob goes with the part whose surface pixels lie
//! within two pixels of its own (the rest, mixed pixels away from every surface, with none).

use std::collections::HashMap;

/// One part of a blob: its returns, and those of them on surfaces (indexes into the scene's
/// points), and how many pixels its returns cover.
pub(super) struct Part {
    pub members: Vec<usize>,
    pub surface: Vec<usize>,
    pub pixels: usize,
}

/// The parts of a blob of `members` whose returns on surfaces are `surface` (a subset),
/// `pixel_of_point` giving each return's height-map pixel in a map `width` pixels wide. A blob
/// whose surface pixels are all joined is one part: the blob itself.
pub(super) fn parts(
    members: &[usize],
    surface: &[usize],
    pixel_of_point: &[u32],
    width: usize,
) -> Vec<Part> {
    let pixel = |i: usize| pixel_of_point[i] as usize;
    // 1. The surface pixels, joined within two pixels (as the blobs).
    let mut part_of: HashMap<usize, usize> =
        surface.iter().map(|&i| (pixel(i), usize::MAX)).collect();
    let mut starts: Vec<usize> = part_of.keys().copied().collect();
    starts.sort_unstable();
    let mut count = 0;
    for start in starts {
        if part_of[&start] != usize::MAX {
            continue;
        }
        part_of.insert(start, count);
        let mut stack = vec![start];
        while let Some(k) = stack.pop() {
            for n in around(k, width) {
                if part_of.get(&n) == Some(&usize::MAX) {
                    part_of.insert(n, count);
                    stack.push(n);
                }
            }
        }
        count += 1;
    }
    if count <= 1 {
        let mut px: Vec<usize> = members.iter().map(|&i| pixel(i)).collect();
        px.sort_unstable();
        px.dedup();
        return vec![Part {
            members: members.to_vec(),
            surface: surface.to_vec(),
            pixels: px.len(),
        }];
    }
    // 2. Every return with the part of a surface pixel at or near its own (its own first).
    let mut out: Vec<Part> = (0..count)
        .map(|_| Part {
            members: Vec::new(),
            surface: Vec::new(),
            pixels: 0,
        })
        .collect();
    let mut pixels_of: Vec<Vec<usize>> = vec![Vec::new(); count];
    for &i in members {
        let k = pixel(i);
        let own = part_of.get(&k).copied();
        if let Some(p) = own.or_else(|| around(k, width).find_map(|n| part_of.get(&n).copied())) {
            out[p].members.push(i);
            pixels_of[p].push(k);
        }
    }
    for &i in surface {
        out[part_of[&pixel(i)]].surface.push(i);
    }
    for (part, mut px) in out.iter_mut().zip(pixels_of) {
        px.sort_unstable();
        px.dedup();
        part.pixels = px.len();
    }
    out
}

/// The pixels within two pixels of pixel `k` (itself included) in a map `width` pixels wide
/// (pixels past the map's left or right edge are left out; rows past its top or bottom have
/// no returns).
fn around(k: usize, width: usize) -> impl Iterator<Item = usize> {
    let (x, y) = ((k % width) as isize, (k / width) as isize);
    (-2..=2isize).flat_map(move |dy| {
        (-2..=2isize).filter_map(move |dx| {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && (nx as usize) < width {
                Some(ny as usize * width + nx as usize)
            } else {
                None
            }
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pixel of column `x`, row `y` in a 100-pixel-wide map.
    fn px(x: u32, y: u32) -> u32 {
        y * 100 + x
    }

    #[test]
    fn mixed_pixels_joining_two_surfaces_leave_them_two_parts() {
        // A face along row 10 (columns 0-19), a chair along row 2 (columns 5-9), and a trail
        // of mixed pixels (one return each, on no surface) from the chair to the face.
        let mut pixel_of_point = Vec::new();
        let mut surface = Vec::new();
        for x in 0..20 {
            surface.push(pixel_of_point.len());
            pixel_of_point.push(px(x, 10));
        }
        for x in 5..10 {
            surface.push(pixel_of_point.len());
            pixel_of_point.push(px(x, 2));
        }
        let trail: Vec<usize> = (4..9)
            .map(|y| {
                pixel_of_point.push(px(7, y));
                pixel_of_point.len() - 1
            })
            .collect();
        let members: Vec<usize> = (0..pixel_of_point.len()).collect();
        let got = parts(&members, &surface, &pixel_of_point, 100);
        assert_eq!(got.len(), 2);
        let face = got
            .iter()
            .find(|p| p.surface.len() == 20)
            .expect("the face");
        let chair = got
            .iter()
            .find(|p| p.surface.len() == 5)
            .expect("the chair");
        // The trail's ends go with the surfaces next to them (rows 4 and 8, within two pixels
        // of the chair's and the face's), its middle (rows 5-7) with neither.
        assert!(chair.members.contains(&trail[0]) && face.members.contains(&trail[4]));
        for t in &trail[1..4] {
            assert!(!face.members.contains(t) && !chair.members.contains(t));
        }
        assert_eq!((face.pixels, chair.pixels), (21, 6));
    }

    #[test]
    fn a_blob_with_joined_surfaces_is_one_part() {
        let pixel_of_point: Vec<u32> = (0..10).map(|x| px(x * 2, 5)).collect();
        let members: Vec<usize> = (0..10).collect();
        let got = parts(&members, &members[..9], &pixel_of_point, 100);
        assert_eq!(got.len(), 1);
        assert_eq!((got[0].members.len(), got[0].pixels), (10, 10));
    }
}
