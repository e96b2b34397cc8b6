//! What the CPU twins of [`super::GpuSystem`]'s Dense kernel
//! ([`super::dense_twin`]) share: the kernel uniforms as the batch path's
//! constants, the root's and the frame chain's arithmetic (`chain.wgsl`),
//! and the conversions between its buffers and the batch path's types,
//! all with the batch path's f32 arithmetic ([`crate::batch`], at width
//! 1). (The GPU engine's twin is [`super::engine_twin`].)

use crate::batch::forward::{FrameState, advance_local, root_jacobian};
use crate::batch::layout::{BatchModel, ElementData, StepEnv};
use crate::batch::vec::V3;

use super::layout::{
    ElementConstGpu, FrameGpu, JacobiansGpu, OwnGpu, ParamsGpu, RootPoseGpu, m3, m4, v3, v4,
};

/// The batch path's constants and environment from the kernel uniforms.
pub fn model_of(params: &ParamsGpu, elements: &[ElementConstGpu]) -> (BatchModel, StepEnv) {
    let points = params.points as usize;
    let flat =
        |a: &[[f32; 4]; 2]| -> Vec<f32> { a.iter().flatten().copied().take(points).collect() };
    let model = BatchModel {
        lengths_m: elements.iter().map(|e| e.stiffness_length[3]).collect(),
        stiffness: elements
            .iter()
            .map(|e| {
                [
                    e.stiffness_length[0],
                    e.stiffness_length[1],
                    e.stiffness_length[2],
                ]
            })
            .collect(),
        natural: elements
            .iter()
            .map(|e| {
                [
                    e.natural_friction[0],
                    e.natural_friction[1],
                    e.natural_friction[2],
                ]
            })
            .collect(),
        friction: elements.iter().map(|e| e.natural_friction[3]).collect(),
        mass_per_length: params.mass_per_length,
        air_drag: params.air_drag,
        nodes: flat(&params.nodes),
        weights: flat(&params.weights),
    };
    let xyz = |v: [f32; 4]| [v[0], v[1], v[2]].map(f64::from);
    let env = StepEnv {
        h_secs: f64::from(params.h_secs),
        gravity_m_per_s2: xyz(params.gravity_m_per_s2),
        air_velocity_m_per_s: xyz(params.air_velocity_m_per_s),
    };
    (model, env)
}

/// The root frame state of a strand, carried by the head in f32 (WGSL
/// `root_state`).
pub fn root_state(params: &ParamsGpu, pose: &RootPoseGpu) -> FrameState<f32> {
    let head = m3(&params.head_rotation);
    let offset = head * v3(pose.position_m);
    let w = v3(params.head_angular_velocity);
    let alpha = v3(params.head_angular_acceleration);
    FrameState {
        frame: head.mul_mat(&m3(&pose.head_from_root)),
        angular_velocity: w,
        angular_acceleration: alpha,
        point_m: V3::zero(),
        point_velocity: v3(params.head_velocity) + w.cross(offset),
        point_acceleration: v3(params.head_acceleration)
            + alpha.cross(offset)
            + w.cross(w.cross(offset)),
    }
}

pub(crate) fn frame_of(f: &FrameGpu) -> FrameState<f32> {
    FrameState {
        frame: m3(&f.frame),
        angular_velocity: v3(f.angular_velocity),
        angular_acceleration: v3(f.angular_acceleration),
        point_m: v3(f.point_m),
        point_velocity: v3(f.point_velocity),
        point_acceleration: v3(f.point_acceleration),
    }
}

/// The frame chain of `chain.wgsl`'s `stage_frames`, with A_Q about the
/// root and a zero span.
pub(crate) fn frame_chain(
    params: &ParamsGpu,
    elements: &[ElementConstGpu],
    roots: &[RootPoseGpu],
    (q, v): (&[[f32; 4]], &[[f32; 4]]),
    frames: &mut [FrameGpu],
    jacobians: &mut [JacobiansGpu],
) {
    let n = params.elements as usize;
    for (strand, pose) in roots.iter().enumerate() {
        let mut s = root_state(params, pose);
        for (e, element) in elements.iter().enumerate().take(n) {
            let i = strand * n + e;
            frames[i] = FrameGpu {
                frame: m4(&s.frame),
                angular_velocity: v4(s.angular_velocity),
                angular_acceleration: v4(s.angular_acceleration),
                point_m: v4(s.point_m),
                point_velocity: v4(s.point_velocity),
                point_acceleration: v4(s.point_acceleration),
            };
            let (next, a, b, _) =
                advance_local(&s, element.stiffness_length[3], v3(q[i]), v3(v[i]));
            jacobians[i] = JacobiansGpu {
                a: m4(&root_jacobian(a, next.point_m, &b)),
                b: m4(&b),
                span: [0.0; 4],
            };
            s = next;
        }
    }
}

/// An element's own sums as the kernels store them (WGSL `Own`).
pub(crate) fn own_of(el: &ElementData<f32>) -> OwnGpu {
    let mut moment = v4(el.first_moment);
    moment[3] = el.mass;
    OwnGpu {
        mass_block: m4(&el.own_mass_block),
        inertia: m4(&el.inertia),
        force: v4(el.own_force),
        moment,
        force_sum: v4(el.force_sum),
        torque_sum: v4(el.torque_sum),
    }
}

pub(crate) fn element_of(jac: &JacobiansGpu, own: &OwnGpu) -> ElementData<f32> {
    ElementData {
        a: m3(&jac.a),
        b: m3(&jac.b),
        span: v3(jac.span),
        own_mass_block: m3(&own.mass_block),
        own_force: v3(own.force),
        mass: own.moment[3],
        first_moment: v3(own.moment),
        inertia: m3(&own.inertia),
        force_sum: v3(own.force_sum),
        torque_sum: v3(own.torque_sum),
        ..ElementData::zero()
    }
}
