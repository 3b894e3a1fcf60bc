//! wgpu's validation errors, forced on purpose, come back as typed errors naming what was
//! being done (not as wgpu's default panic), and the device stays usable afterwards.
use super::*;
use crate::context::AdapterChoice;
use cloud::BadInput;

fn open(test: &str) -> Option<GpuIcp> {
    match GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => Some(GpuIcp::new(ctx).expect("kernels compile")),
        Err(GpuError::NoAdapter(why)) => {
            eprintln!("{test}: SKIPPED: no GPU adapter at all ({why})");
            None
        }
        Err(e) => panic!("{test}: opening the GPU failed: {e}"),
    }
}

fn line(n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|i| Vec3::new(i as f32 * 0.01, 0.0, 0.0))
        .collect()
}

#[test]
fn a_validation_error_inside_a_scope_is_a_typed_error_and_the_device_recovers() {
    let Some(mut icp) = open("validation_error") else {
        return;
    };
    let points = line(500);
    icp.set_target(&points, None, 0.2).expect("target");
    icp.set_source(&points).expect("source");
    let (before, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
    assert_eq!(before.count as usize, 500);
    // Submitted stage by stage (to time them) or at once, the sums are the same.
    icp.set_stage_timing(true);
    let (split, times) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
    assert_eq!(split, before);
    assert!(
        times.reduce_ms > 0.0 && times.download_ms > 0.0,
        "{times:?}"
    );
    icp.set_stage_timing(false);
    // More workgroups than one dispatch may have: wgpu rejects the dispatch.
    let too_many = icp.ctx.limits.max_compute_workgroups_per_dimension + 1;
    let bind = icp.bind.clone().expect("bound");
    let err = icp
        .ctx
        .scoped("dispatching too many workgroups", || {
            icp.dispatch(&bind, &icp.search, too_many)
        })
        .expect_err("wgpu must reject the dispatch");
    match &err {
        GpuError::Validation { during, msg } => {
            assert_eq!(during, "dispatching too many workgroups");
            assert!(!msg.is_empty());
        }
        other => panic!("expected a validation error, got {other:?}"),
    }
    assert!(
        !err.is_bad_input(),
        "a kernel misuse is not the user's input"
    );
    // Nothing is lost: the next iteration runs and gives the same sums.
    let (after, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
    assert_eq!(after, before);
}

#[test]
fn an_error_outside_every_scope_is_reported_by_the_next_operation() {
    let Some(mut icp) = open("uncaptured_error") else {
        return;
    };
    // A buffer larger than the device allows, created outside any error scope: wgpu hands
    // the error to the uncaptured-error handler (whose default would panic).
    let too_big = icp.ctx.limits.max_buffer_size.saturating_add(16);
    let _ = icp.ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("too big"),
        size: too_big,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let points = line(100);
    let err = icp
        .set_target(&points, None, 0.2)
        .expect_err("the recorded error comes back");
    assert!(
        matches!(&err, GpuError::Validation { msg, .. } if !msg.is_empty()),
        "{err:?}"
    );
    // Reported once: the retry succeeds.
    icp.set_target(&points, None, 0.2).expect("target");
    icp.set_source(&points).expect("source");
    let (sums, _) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO).expect("sums");
    assert_eq!(sums.count as usize, 100);
}
