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
        let numbers: Vec<f64> = text
            .split_whitespace()
            .map(|f| {
                f.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        PipelineError::bad_input(format!("{g}: '{f}' is not a finite number"))
                    })
            })
            .collect::<Result<_>>()?;
        let arr: [f64; 16] = numbers.as_slice().try_into().map_err(|_| {
            PipelineError::bad_input(format!(
                "{g}: a guess file holds 16 numbers (a row-major 4x4 matrix), found {}",
                numbers.len()
            ))
        })?;
        return Ok(cloud::affine_from_mat4(
            DMat4::from_cols_array(&arr).transpose(),
            path,
            1,
        )?);
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
}
