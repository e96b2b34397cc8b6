//! Prim transforms from `xformOp` attributes, as USD composes them.
//!
//! A prim's local transform is the product of the ops its `xformOpOrder`
//! lists, the first op outermost (for `[translate, rotateXYZ, scale]` a
//! point is scaled, then rotated, then translated); ops not listed are not
//! applied, `!invert!` inverts an op and `!resetXformStack!` drops the
//! parents' transforms. Supported ops: `translate`, `scale`, `rotateX`,
//! `rotateY`, `rotateZ`, the six `rotateXYZ`-style Euler ops (degrees),
//! `orient` (a quaternion, real part first) and `transform` (a `matrix4d`,
//! whose rows USD writes with the translation in the last). Time-sampled
//! ops are not applied (the default value is, when there is one), and a
//! warning says so.

use glam::{DMat4, DQuat, DVec3, EulerRot};

use crate::usda::parse::{Prim, PrimPath};
use crate::warnings::{Warnings, short};

/// Each prim's world transform (parents come before children in `prims`).
pub(crate) fn world_transforms(prims: &[Prim], warnings: &mut Warnings) -> Vec<DMat4> {
    let mut world: Vec<DMat4> = Vec::with_capacity(prims.len());
    for (index, prim) in prims.iter().enumerate() {
        let parent = prim.parent.map_or(DMat4::IDENTITY, |index| world[index]);
        let path = PrimPath { prims, index };
        let (local, reset) = local_transform(prim, path, warnings);
        world.push(if reset { local } else { parent * local });
    }
    world
}

/// A prim's local transform and whether it resets the parents' stack.
fn local_transform(prim: &Prim, path: PrimPath, warnings: &mut Warnings) -> (DMat4, bool) {
    if prim.animated_xform {
        warnings.push(|| {
            format!("<{path}> has time-sampled transform ops; their default values are used")
        });
    }
    let Some(order) = &prim.xform_op_order else {
        return (DMat4::IDENTITY, false);
    };
    let mut local = DMat4::IDENTITY;
    let mut reset = false;
    for entry in order {
        if entry == "!resetXformStack!" {
            reset = true;
            local = DMat4::IDENTITY;
            continue;
        }
        let (name, invert) = match entry.strip_prefix("!invert!") {
            Some(name) => (name, true),
            None => (entry.as_str(), false),
        };
        let Some((_, _, values)) = prim.xform_ops.iter().find(|(op, _, _)| op == name) else {
            warnings.push(|| {
                format!(
                    "<{}>: {} is in xformOpOrder but has no value; skipped",
                    path,
                    short(name)
                )
            });
            continue;
        };
        match op_matrix(name, values) {
            Some(matrix) => local *= if invert { matrix.inverse() } else { matrix },
            None => warnings.push(|| {
                format!(
                    "<{}>: {} with {} values is not a transform op this reader knows; skipped",
                    path,
                    short(name),
                    values.len()
                )
            }),
        }
    }
    (local, reset)
}

/// One op's matrix (column vectors), or `None` for an unknown op.
fn op_matrix(name: &str, values: &[f64]) -> Option<DMat4> {
    let kind = name.strip_prefix("xformOp:")?;
    let kind = kind.split(':').next()?;
    let vec3 = || (values.len() == 3).then(|| DVec3::new(values[0], values[1], values[2]));
    let angle = || (values.len() == 1).then(|| values[0].to_radians());
    let euler = |order: EulerRot| {
        let v = vec3()?;
        // USD's rotateXYZ turns about X first, then Y, then Z: R = Rz Ry Rx.
        // glam's Euler orders name the outermost rotation first.
        Some(DMat4::from_quat(DQuat::from_euler(
            order,
            v[order_index(order, 0)].to_radians(),
            v[order_index(order, 1)].to_radians(),
            v[order_index(order, 2)].to_radians(),
        )))
    };
    match kind {
        "translate" => vec3().map(DMat4::from_translation),
        "scale" => vec3().map(DMat4::from_scale),
        "rotateX" => angle().map(DMat4::from_rotation_x),
        "rotateY" => angle().map(DMat4::from_rotation_y),
        "rotateZ" => angle().map(DMat4::from_rotation_z),
        "rotateXYZ" => euler(EulerRot::ZYX),
        "rotateXZY" => euler(EulerRot::YZX),
        "rotateYXZ" => euler(EulerRot::ZXY),
        "rotateYZX" => euler(EulerRot::XZY),
        "rotateZXY" => euler(EulerRot::YXZ),
        "rotateZYX" => euler(EulerRot::XYZ),
        "orient" => (values.len() == 4).then(|| {
            DMat4::from_quat(
                DQuat::from_xyzw(values[1], values[2], values[3], values[0]).normalize(),
            )
        }),
        "transform" => {
            let array: [f64; 16] = values.try_into().ok()?;
            // USD rows (translation last) are glam's columns.
            Some(DMat4::from_cols_array(&array))
        }
        _ => None,
    }
}

/// Which of USD's (x, y, z) angles glam's Euler order takes `slot`th: glam
/// lists the outermost axis first, USD's name lists the innermost first.
fn order_index(order: EulerRot, slot: usize) -> usize {
    let axes = match order {
        EulerRot::ZYX => [2, 1, 0],
        EulerRot::YZX => [1, 2, 0],
        EulerRot::ZXY => [2, 0, 1],
        EulerRot::XZY => [0, 2, 1],
        EulerRot::YXZ => [1, 0, 2],
        _ => [0, 1, 2],
    };
    axes[slot]
}
