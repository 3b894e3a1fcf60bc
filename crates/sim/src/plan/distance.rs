//! The exact Euclidean distance transform of a grid (Felzenszwalb and Huttenlocher, "Distance
//! transforms of sampled functions", 2012): the clearance of every free-space grid cell.

/// Squared distances (in cells) from each cell to the nearest `true` cell (Felzenszwalb and
/// Huttenlocher's exact transform: columns, then rows). Infinite where nothing is blocked.
pub(crate) fn distance_transform(blocked: &[bool], nx: usize, ny: usize) -> Vec<f64> {
    let mut d: Vec<f64> = blocked
        .iter()
        .map(|&b| if b { 0.0 } else { f64::INFINITY })
        .collect();
    let n = nx.max(ny);
    let (mut f, mut out, mut v, mut z) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![0usize; n],
        vec![0.0; n + 1],
    );
    for i in 0..nx {
        for j in 0..ny {
            f[j] = d[j * nx + i];
        }
        edt_1d(&f[..ny], &mut out[..ny], &mut v, &mut z);
        for j in 0..ny {
            d[j * nx + i] = out[j];
        }
    }
    for j in 0..ny {
        f[..nx].copy_from_slice(&d[j * nx..(j + 1) * nx]);
        edt_1d(&f[..nx], &mut out[..nx], &mut v, &mut z);
        d[j * nx..(j + 1) * nx].copy_from_slice(&out[..nx]);
    }
    d
}

/// The 1D squared distance transform of `f` (lower envelope of parabolas).
fn edt_1d(f: &[f64], d: &mut [f64], v: &mut [usize], z: &mut [f64]) {
    let n = f.len();
    // Only finite samples carry parabolas.
    let mut k: isize = -1;
    for q in 0..n {
        if !f[q].is_finite() {
            continue;
        }
        loop {
            if k < 0 {
                k = 0;
                v[0] = q;
                z[0] = f64::NEG_INFINITY;
                z[1] = f64::INFINITY;
                break;
            }
            let p = v[k as usize];
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q - p) as f64);
            if s <= z[k as usize] {
                k -= 1;
                continue;
            }
            k += 1;
            v[k as usize] = q;
            z[k as usize] = s;
            z[k as usize + 1] = f64::INFINITY;
            break;
        }
    }
    if k < 0 {
        d.iter_mut().for_each(|x| *x = f64::INFINITY);
        return;
    }
    let mut k = 0usize;
    for (q, dq) in d.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let diff = q as f64 - p as f64;
        *dq = diff * diff + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_transform_is_exact_against_brute_force() {
        let (nx, ny) = (13, 9);
        let blocked: Vec<bool> = (0..nx * ny).map(|c| c % 7 == 3 || c == 50).collect();
        let d = distance_transform(&blocked, nx, ny);
        for (c, &dc) in d.iter().enumerate() {
            let (i, j) = ((c % nx) as f64, (c / nx) as f64);
            let brute = (0..nx * ny)
                .filter(|&b| blocked[b])
                .map(|b| ((b % nx) as f64 - i).powi(2) + ((b / nx) as f64 - j).powi(2))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(dc, brute, "cell {c}");
        }
        assert!(distance_transform(&[false; 6], 3, 2)
            .iter()
            .all(|v| v.is_infinite()));
    }
}
