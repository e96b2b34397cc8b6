//! The hair–hair model's lane form (`volume::splat_lanes`,
//! `VolumeField::update_lanes` and `read_lanes`, what the batch engine
//! runs) against its scalar form (`VolumeField::update` and `read_in`,
//! what the reference engine runs): the same points, four to a group,
//! give the same node sums, cells and readings bit for bit, including
//! points outside the grid, at NaN and of zero mass (a batch's padding).

use glam::DVec3;
use helixhair_physics::RigidMotion;
use helixhair_physics::volume::friction::HeadVelocity;
use helixhair_physics::volume::splat_lanes::PointLanes;
use helixhair_physics::volume::{InteractionSettings, RestDensity, SamplePoint, VolumeField};
use wide::f64x4;

/// A deterministic spread of numbers in [0, 1) (a 64-bit LCG's top bits).
struct Spread(u64);

impl Spread {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `groups` groups of four points in a 10 cm cube about the origin, some
/// outside it, one at NaN, every fifth of zero mass.
fn groups(count: usize) -> Vec<PointLanes> {
    let mut spread = Spread(7);
    let mut lane = |i: usize| {
        let mut p = || 0.12 * (spread.next() - 0.5);
        let position_m = if i == 13 {
            DVec3::new(0.0, f64::NAN, 0.0)
        } else {
            DVec3::new(p(), p(), p())
        };
        let velocity_m_per_s = DVec3::new(p(), p(), p()) * 10.0;
        let mass_kg = if i.is_multiple_of(5) {
            0.0
        } else {
            1e-6 * (1.0 + p())
        };
        (position_m, velocity_m_per_s, mass_kg)
    };
    (0..count)
        .map(|g| {
            let lanes: [_; 4] = std::array::from_fn(|k| lane(4 * g + k));
            let axis = |f: fn(&(DVec3, DVec3, f64)) -> DVec3, a: usize| {
                f64x4::new(lanes.each_ref().map(|l| f(l).to_array()[a]))
            };
            PointLanes {
                position_m: std::array::from_fn(|a| axis(|l| l.0, a)),
                velocity_m_per_s: std::array::from_fn(|a| axis(|l| l.1, a)),
                mass_kg: f64x4::new(lanes.map(|l| l.2)),
            }
        })
        .collect()
}

#[test]
fn the_lane_splat_and_read_equal_the_scalar_ones_bit_for_bit() {
    // 64 groups: the four pieces cut the groups where they cut the points.
    let lanes = groups(64);
    let points: Vec<SamplePoint> = lanes
        .iter()
        .flat_map(|g| (0..4).map(|k| g.lane(k)))
        .collect();
    let settings = InteractionSettings {
        pressure_m2_per_s2: 1.0,
        ..InteractionSettings::default()
    };
    // A rest pose of a quarter of the points, so that the rest are in
    // excess somewhere and the push is read too.
    let rest_points: Vec<SamplePoint> = points
        .iter()
        .step_by(4)
        .filter(|p| p.position_m.is_finite())
        .copied()
        .collect();
    let rest = RestDensity::new(&rest_points, 0.02, 0.0).unwrap();
    let (mut scalar, mut lane) = (VolumeField::default(), VolumeField::default());
    // A head that moves and turns: the nodes keep velocities relative to it.
    let head = HeadVelocity::of(&RigidMotion {
        velocity_m_per_s: DVec3::new(0.1, -0.2, 0.05),
        angular_velocity_rad_per_s: DVec3::new(1.0, 2.0, -0.5),
        ..RigidMotion::default()
    });
    scalar.update(&rest, &[&points[..32], &points[32..]], &head, true);
    lane.update_lanes(&rest, &[&lanes[..8], &lanes[8..]], &head, true);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(scalar.density_kg_per_m3()),
        bits(lane.density_kg_per_m3())
    );
    assert_eq!(bits(scalar.excess()), bits(lane.excess()));
    assert!(scalar.excess().iter().any(|e| *e > 0.0));
    let (mut outside, mut pushed) = (0, 0);
    for (i, point) in points.iter().enumerate() {
        let (g, k) = (i / 4, i % 4);
        let cell = scalar.cells()[i];
        assert_eq!(lane.cell_lanes()[g].lane(k), cell, "point {i}");
        outside += usize::from(cell.is_none());
        let expected = scalar.read_in(&settings, cell, point);
        let group = &lanes[g];
        let mut seen = false;
        lane.read_lanes(
            &settings,
            &lane.cell_lanes()[g],
            group,
            |at, target, push| {
                if at != k {
                    return;
                }
                seen = true;
                let [x, y, z, _] = target.to_array();
                assert_eq!(
                    bits(&[x, y, z]),
                    bits(&expected.relative_target_m_per_s.to_array()),
                    "point {i}"
                );
                let push = push.unwrap_or(DVec3::ZERO);
                assert_eq!(
                    bits(&push.to_array()),
                    bits(&expected.push_m_per_s2.to_array()),
                    "point {i}"
                );
                pushed += usize::from(push != DVec3::ZERO);
            },
        );
        assert!(seen);
    }
    // The cases the test is for did occur.
    assert!(
        outside > 0 && pushed > 0,
        "outside {outside}, pushed {pushed}"
    );
}
