//! An initial transform for a pair registration (`semsim register --guess`): a file of 16
//! numbers (a row-major 4x4 matrix) or `x,y,z,roll,pitch,yaw` in metres and degrees.

use crate::error::{PipelineError, Result};
use glam::{DAffine3, DMat4, DQuat, DVec3, EulerRot};
use std::path::Path;

/// Parses `--guess`: a 4x4 matrix file (16 numbers) or `x,y,z,roll,pitch,yaw` in metres and degrees.
pub fn parse_guess(g: &str) -> Result<DAffine3> {
    let path = Path::new(g);
    if path.is_file() {
        let text = std::fs::read_to_string(path).map_err(|e| cloud::CloudError::io(path, e))?;
        return guess_from_text(&text, path);
    }
    let v: Vec<f64> = g
        .split(',')
        .map(|f| f.trim().parse::<f64>().unwrap_or(f64::NAN))
        .collect();
    match v.as_slice() {
        [x, y, z, roll, pitch, yaw] if v.iter().all(|x| x.is_finite()) => Ok(DAffine3::from_rotation_translation(
            DQuat::from_euler(EulerRot::ZYX, yaw.to_radians(), pitch.to_radians(), roll.to_radians()),
            DVec3::new(*x, *y, *z),
        )),
        _ => Err(PipelineError::bad_input(format!(
            "--guess '{g}': neither a file nor six finite numbers x,y,z,roll,pitch,yaw (metres, degrees)"
        ))),
    }
}

/// A guess file's text (`path` names it in errors): 16 finite numbers, a row-major 4x4
/// matrix whose 3x3 part is a rotation and whose last row is 0 0 0 1.
pub fn guess_from_text(text: &str, path: &Path) -> Result<DAffine3> {
    let name = path.display();
    let mut numbers = Vec::with_capacity(16);
    for f in text.split_whitespace() {
        let v = f
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                PipelineError::bad_input(format!("{name}: '{f}' is not a finite number"))
            })?;
        // (at most one more than a matrix holds: no allocation follows the file's length)
        if numbers.len() == 16 {
            return Err(PipelineError::bad_input(format!(
                "{name}: a guess file holds 16 numbers (a row-major 4x4 matrix), found more"
            )));
        }
        numbers.push(v);
    }
    let arr: [f64; 16] = numbers.as_slice().try_into().map_err(|_| {
        PipelineError::bad_input(format!(
            "{name}: a guess file holds 16 numbers (a row-major 4x4 matrix), found {}",
            numbers.len()
        ))
    })?;
    Ok(cloud::affine_from_mat4(
        DMat4::from_cols_array(&arr).transpose(),
        path,
        1,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn six_numbers_are_a_pose_and_anything_else_is_bad_input() {
        let g = parse_guess("1,2,3,0,0,90").expect("a pose");
        assert!((g.translation - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        assert!((g.transform_vector3(DVec3::X) - DVec3::Y).length() < 1e-12);
        for bad in ["1,2,3", "1,2,3,0,0,nan", "x,y,z,r,p,q"] {
            let e = parse_guess(bad).expect_err(bad);
            assert!(e.to_string().contains(bad), "{e}");
        }
    }

    #[test]
    fn a_guess_file_is_a_rigid_matrix_and_anything_else_names_the_file() {
        let f = Path::new("guess.txt");
        let g = guess_from_text("0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1\n", f).expect("a matrix");
        assert!((g.translation - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12);
        assert!((g.transform_vector3(DVec3::X) - DVec3::Y).length() < 1e-12);
        let seventeen = "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 5";
        let scaled = "2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1";
        for bad in [
            "1 2 3",
            seventeen,
            scaled,
            "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 inf",
        ] {
            let e = guess_from_text(bad, f).expect_err(bad);
            assert!(e.to_string().contains("guess.txt"), "{e}");
            assert!(cloud::BadInput::is_bad_input(&e), "{e}");
        }
    }
}
