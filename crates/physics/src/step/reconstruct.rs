//! Stage "reconstruct": the strand's shape, velocities and Jacobians from q
//! and q̇, root to tip in O(N).
//!
//! Element Q starts at point p_Q with frame R_Q (columns n₀, n₁, n₂). Its
//! centreline is p_Q + R_Q h(σ, q_Q) and its end frame R_Q exp(ℓ_Q\[q_Q\]×)
//! (see [`crate::geometry::helix`]). The sweep runs on [`Jet`]s seeded with the root's
//! motion and (q, q̇, 0), so each quadrature sample gets its position,
//! velocity and its acceleration with q̈ = 0 (Coriolis, centrifugal and root
//! terms) in the same pass.
//!
//! Jacobians. Moving q_Q moves element Q and carries everything beyond it
//! rigidly: for a point r beyond element Q,
//! ∂r/∂q_Q = a_Q − [r − p_{Q+1}]× b_Q = A_Q − \[r\]× B_Q, with
//! a_Q = R_Q ∂h(ℓ_Q)/∂k, b_Q = ℓ_Q R_Q J_l(ℓ_Q q_Q) and A_Q = a_Q + [p_{Q+1}]× b_Q.
//! Writing it as A − \[r\]×B makes every later integral a function of the
//! mass moments of what lies beyond, which suffix sums give in O(N). Inside
//! element Q the Jacobian is R_Q ∂h(σ)/∂k, stored per sample.
//!
//! Positions are relative to the root point, so magnitudes stay of the
//! strand's size wherever the head is.

use glam::{DMat3, DVec3};

use crate::geometry::helix::{centreline_jets, end_geometry_and_parts, geometry_parts, skew};
use crate::geometry::helix_rates::{centreline_jacobian_rate, left_jacobian_rate};
use crate::geometry::jet::Jet;
use crate::model::StrandModel;
use crate::motion::RigidMotion;

/// One quadrature sample of the centreline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Position relative to the root point, metres.
    pub position_m: DVec3,
    /// Velocity, m/s (root motion included).
    pub velocity_m_per_s: DVec3,
    /// Acceleration with q̈ = 0, m/s²: the velocity-dependent part of r̈.
    pub free_acceleration_m_per_s2: DVec3,
    /// ∂r/∂q of the sample's own element, R_Q ∂h(σ)/∂k, in metres².
    pub jacobian: DMat3,
    /// Quadrature weight times element length, metres.
    pub weight_m: f64,
}

/// The "beyond" Jacobian of an element: ∂r/∂q_Q = A − \[r\]×B for any point r
/// past the element's end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementJacobian {
    /// A_Q = a_Q + [p_{Q+1}]× b_Q, metres².
    pub a: DMat3,
    /// B_Q = ℓ_Q R_Q J_l(ℓ_Q q_Q), metres.
    pub b: DMat3,
}

/// Everything the later stages need about the current shape.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Kinematics {
    /// Frames R_Q at element starts, plus the tip frame (N + 1).
    pub frames: Vec<DMat3>,
    /// Element boundary points relative to the root point (N + 1).
    pub points_m: Vec<DVec3>,
    /// Velocities of the boundary points, m/s (N + 1).
    pub point_velocities_m_per_s: Vec<DVec3>,
    /// Quadrature samples, element by element (N × points).
    pub samples: Vec<Sample>,
    /// Beyond-Jacobians per element (N).
    pub elements: Vec<ElementJacobian>,
    /// Time derivative of each sample's own Jacobian, d/dt(R_Q ∂h(σ)/∂k),
    /// metres²/s (N × points); only [`reconstruct_with_rates`] fills it.
    pub jacobian_rates: Vec<DMat3>,
    /// Time derivatives Ȧ_Q, Ḃ_Q of the beyond-Jacobians (N); only
    /// [`reconstruct_with_rates`] fills them.
    pub element_rates: Vec<ElementJacobian>,
}

/// Rebuilds `out` from the strains `q`, their rates `v` and the root motion.
pub fn reconstruct(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
    out: &mut Kinematics,
) {
    sweep(model, q, v, root, false, out);
}

/// [`reconstruct`], plus the Jacobians' time derivatives J̇ (the
/// [`Kinematics::jacobian_rates`] and [`Kinematics::element_rates`]) that
/// the velocity terms' product G x = 2 ∫ ρS Jᵀ J̇ x ds needs
/// ([`crate::step::velocity_terms`]). Ṙ_Q and ṗ come from the sweep's jets, the
/// closed forms' own rates from [`crate::geometry::helix_rates`]:
/// Ȧ_Q = ȧ_Q + [ṗ_{Q+1}]× b_Q + [p_{Q+1}]× ḃ_Q.
pub fn reconstruct_with_rates(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
    out: &mut Kinematics,
) {
    sweep(model, q, v, root, true, out);
}

fn sweep(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
    rates: bool,
    out: &mut Kinematics,
) {
    let n = model.elements();
    out.frames.clear();
    out.points_m.clear();
    out.point_velocities_m_per_s.clear();
    out.samples.clear();
    out.elements.clear();
    out.jacobian_rates.clear();
    out.element_rates.clear();

    let (mut frame, mut point) = root_jets(root);
    out.frames.push(frame.v);
    out.points_m.push(point.v);
    out.point_velocities_m_per_s.push(point.d);

    for e in 0..n {
        let length = model.lengths_m[e];
        let k = Jet::new(q[e], v[e], DVec3::ZERO);
        for (node, weight) in model.quadrature.nodes.iter().zip(&model.quadrature.weights) {
            let sigma = node * length;
            let (phi, co, _, geometry) = geometry_parts(sigma, k);
            let r = point + frame * geometry.centreline;
            if rates {
                out.jacobian_rates.push(
                    frame.d * geometry.centreline_jacobian
                        + frame.v * centreline_jacobian_rate(sigma, phi.v, phi.d, &co),
                );
            }
            out.samples.push(Sample {
                position_m: r.v,
                velocity_m_per_s: r.d,
                free_acceleration_m_per_s2: r.dd,
                jacobian: frame.v * geometry.centreline_jacobian,
                weight_m: weight * length,
            });
        }
        let (end, phi, co) = end_geometry_and_parts(length, k);
        let next_point = point + frame * end.point.centreline;
        let a = frame.v * end.point.centreline_jacobian;
        let b = frame.v * end.left_jacobian * length;
        out.elements.push(ElementJacobian {
            a: a + skew(next_point.v) * b,
            b,
        });
        if rates {
            let a_rate = frame.d * end.point.centreline_jacobian
                + frame.v * centreline_jacobian_rate(length, phi.v, phi.d, &co);
            let b_rate = (frame.d * end.left_jacobian
                + frame.v * left_jacobian_rate(phi.v, phi.d, &co))
                * length;
            out.element_rates.push(ElementJacobian {
                a: a_rate + skew(next_point.d) * b + skew(next_point.v) * b_rate,
                b: b_rate,
            });
        }
        frame = frame * end.rotation;
        point = next_point;
        out.frames.push(frame.v);
        out.points_m.push(point.v);
        out.point_velocities_m_per_s.push(point.d);
    }
}

/// The free acceleration r̈ (q̈ = 0) of every quadrature sample, element by
/// element, for strains `q`, rates `v` and the root motion: the same jet
/// sweep as [`reconstruct`], keeping only what the velocity terms need
/// ([`crate::step::velocity_terms`]).
pub fn free_accelerations(
    model: &StrandModel,
    q: &[DVec3],
    v: &[DVec3],
    root: &RigidMotion,
    out: &mut Vec<DVec3>,
) {
    out.clear();
    let (mut frame, mut point) = root_jets(root);
    for e in 0..model.elements() {
        let length = model.lengths_m[e];
        let k = Jet::new(q[e], v[e], DVec3::ZERO);
        for node in &model.quadrature.nodes {
            let (centreline, _) = centreline_jets(node * length, k, false);
            out.push((point + frame * centreline).dd);
        }
        let (centreline, rotation) = centreline_jets(length, k, true);
        point = point + frame * centreline;
        frame = frame * rotation;
    }
}

/// The root frame's and point's jets: the sweep's seed (positions relative
/// to the root point).
fn root_jets(root: &RigidMotion) -> (Jet<DMat3>, Jet<DVec3>) {
    let w = skew(root.angular_velocity_rad_per_s);
    let alpha = skew(root.angular_acceleration_rad_per_s2);
    let r0 = root.world_from_body;
    (
        Jet::new(r0, w * r0, (alpha + w * w) * r0),
        Jet::new(
            DVec3::ZERO,
            root.velocity_m_per_s,
            root.acceleration_m_per_s2,
        ),
    )
}
