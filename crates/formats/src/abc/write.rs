//! Writing a groom (and optionally its animation and head) as an Alembic
//! (Ogawa) archive, the curves as `AbcGeom_Curve_v2`, as Maya's and
//! Unreal's importers read them.
//!
//! # What is written
//!
//! The top object holds `hair`, a curves object whose `.geom` holds `P`
//! (one sample per frame), `nVertices`, `curveBasisAndType` (linear,
//! open), `width` (per curve or per point, when every curve has one) and
//! `.selfBnds`; and with a head, `head`, a `PolyMesh` (its faces wound
//! clockwise, Alembic's convention), or with head poses an `Xform` `head`
//! whose matrix is sampled per pose, holding the mesh as `headShape`.
//! Points are metres, Y up (Alembic declares no unit). Frames at evenly
//! spaced time codes become a uniform time sampling at the animation's
//! rate, others an acyclic one. Colours are not written (curves have no
//! standard colour attribute in Alembic).
//!
//! Each sample's data starts with a 16-byte key, which Alembic's writer
//! makes from a hash of the data and no reader checks; this writer uses a
//! 128-bit FNV-1a hash. Object hashes are written the same way.

use std::io::Write;

use glam::Vec3;

use crate::abc::archive::{Kind, pod};
use crate::abc::ogawa::OgawaWriter;
use crate::animation::Animation;
use crate::curve_set::{CurveSet, StrandValue, bounds_of};
use crate::error::WriteError;
use crate::format::Format;
use crate::mesh::{MeshPose, TriangleMesh};
use crate::write::usd_checks::usd_inputs;

/// The library version written (Alembic 1.8.12's number).
const LIBRARY_VERSION: i32 = 10812;
const GEOM_BASE: &str = "schemaBaseType=AbcGeom_GeomBase_v1";

/// A property written: its header's fields and its group.
struct Prop {
    name: String,
    kind: Kind,
    pod: u8,
    extent: u8,
    metadata: String,
    samples: u32,
    constant: bool,
    time_sampling: u32,
    homogenous: bool,
    scalar_like: bool,
    group: u64,
}

/// A child object written: its header's fields and its group.
struct Obj {
    name: String,
    metadata: String,
    group: u64,
}

/// 128 bits of FNV-1a: the sample keys and object hashes.
fn key(parts: &[&[u8]]) -> [u8; 16] {
    let mut a: u64 = 0xcbf2_9ce4_8422_2325;
    let mut b: u64 = 0x6c62_272e_07bb_0142;
    for byte in parts.iter().flat_map(|p| p.iter()) {
        a = (a ^ u64::from(*byte)).wrapping_mul(0x0000_0100_0000_01b3);
        b = (b ^ u64::from(*byte)).wrapping_mul(0x0000_0100_0000_01b3);
    }
    let mut out = [0; 16];
    out[..8].copy_from_slice(&a.to_le_bytes());
    out[8..].copy_from_slice(&b.to_le_bytes());
    out
}

fn push_hinted(out: &mut Vec<u8>, value: u32, hint: u32) {
    let bytes = value.to_le_bytes();
    out.extend_from_slice(&bytes[..[1, 2, 4][hint as usize]]);
}

/// The property headers block (`WritePropertyInfo`), metadata inline.
fn property_headers(props: &[Prop]) -> Vec<u8> {
    let mut out = Vec::new();
    for prop in props {
        let longest = [
            prop.metadata.len() as u32,
            prop.name.len() as u32,
            prop.samples,
            prop.time_sampling,
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        let hint = match longest {
            0..=255 => 0,
            256..=65_535 => 1,
            _ => 2,
        };
        let metadata_index: u32 = if prop.metadata.is_empty() { 0 } else { 0xff };
        let mut info = (hint << 2) | (metadata_index << 20);
        if prop.kind != Kind::Compound {
            info |= match prop.kind {
                Kind::Scalar => 1,
                _ => 2,
            };
            info |= u32::from(prop.scalar_like);
            info |= u32::from(prop.pod) << 4;
            if prop.time_sampling != 0 {
                info |= 0x100;
            }
            if prop.constant {
                info |= 0x800;
            }
            if prop.homogenous {
                info |= 0x400;
            }
            info |= u32::from(prop.extent) << 12;
        }
        out.extend_from_slice(&info.to_le_bytes());
        if prop.kind != Kind::Compound {
            push_hinted(&mut out, prop.samples, hint);
            if prop.time_sampling != 0 {
                push_hinted(&mut out, prop.time_sampling, hint);
            }
        }
        push_hinted(&mut out, prop.name.len() as u32, hint);
        out.extend_from_slice(prop.name.as_bytes());
        if metadata_index == 0xff {
            push_hinted(&mut out, prop.metadata.len() as u32, hint);
            out.extend_from_slice(prop.metadata.as_bytes());
        }
    }
    out
}

/// The archive being written.
struct Writer {
    ogawa: OgawaWriter,
}

/// What a sampled property holds: its stored samples (one when constant
/// over `count` samples) and its sampling.
struct Samples<'a> {
    stored: &'a [Vec<u8>],
    count: u32,
    time_sampling: u32,
}

impl Writer {
    fn property(
        &mut self,
        name: &str,
        kind: Kind,
        (pod, extent): (u8, u8),
        metadata: &str,
        samples: Samples,
    ) -> Prop {
        let mut children = Vec::new();
        for data in samples.stored {
            let key = key(&[data]);
            children.push(self.ogawa.data(&[&key, data]));
            if kind == Kind::Array {
                // Plain lists: the dimensions follow from the size.
                children.push(self.ogawa.data(&[]));
            }
        }
        let element = (extent as usize).max(1)
            * match pod {
                pod::F64 => 8,
                pod::U8 | pod::BOOL => 1,
                _ => 4,
            };
        let lengths: Vec<usize> = samples.stored.iter().map(Vec::len).collect();
        Prop {
            name: name.to_owned(),
            kind,
            pod,
            extent,
            metadata: metadata.to_owned(),
            samples: samples.count,
            constant: samples.stored.len() == 1,
            time_sampling: samples.time_sampling,
            homogenous: lengths.windows(2).all(|w| w[0] == w[1]),
            scalar_like: kind == Kind::Scalar || lengths.iter().all(|&l| l == element),
            group: self.ogawa.group(&children),
        }
    }

    /// A compound's group: its properties' groups, then their headers.
    fn compound_group(&mut self, props: &[Prop]) -> u64 {
        if props.is_empty() {
            return 0;
        }
        let mut children: Vec<u64> = props.iter().map(|p| p.group).collect();
        let headers = property_headers(props);
        children.push(self.ogawa.data(&[&headers]));
        self.ogawa.group(&children)
    }

    fn compound(&mut self, name: &str, metadata: &str, props: Vec<Prop>) -> Prop {
        let group = self.compound_group(&props);
        Prop {
            name: name.to_owned(),
            kind: Kind::Compound,
            pod: 0,
            extent: 0,
            metadata: metadata.to_owned(),
            samples: 0,
            constant: false,
            time_sampling: 0,
            homogenous: false,
            scalar_like: false,
            group,
        }
    }

    /// An object's group: its properties, its children, their headers
    /// and the hashes.
    fn object(&mut self, name: &str, metadata: &str, props: Vec<Prop>, children: Vec<Obj>) -> Obj {
        let mut entries = vec![self.compound_group(&props)];
        entries.extend(children.iter().map(|c| c.group));
        let mut headers = Vec::new();
        for child in &children {
            headers.extend_from_slice(&(child.name.len() as u32).to_le_bytes());
            headers.extend_from_slice(child.name.as_bytes());
            if child.metadata.is_empty() {
                headers.push(0);
            } else {
                headers.push(0xff);
                headers.extend_from_slice(&(child.metadata.len() as u32).to_le_bytes());
                headers.extend_from_slice(child.metadata.as_bytes());
            }
        }
        let hash = key(&[&headers]);
        entries.push(self.ogawa.data(&[&headers, &hash, &hash]));
        Obj {
            name: name.to_owned(),
            metadata: metadata.to_owned(),
            group: self.ogawa.group(&entries),
        }
    }
}

fn f32_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}

fn points_bytes<'a>(points: impl Iterator<Item = &'a Vec3>) -> Vec<u8> {
    f32_bytes(points.flat_map(|p| p.to_array()))
}

fn bounds_bytes<'a>(points: impl Iterator<Item = &'a Vec3>) -> Vec<u8> {
    let (min, max) = bounds_of(points).unwrap_or((Vec3::ZERO, Vec3::ZERO));
    [min.x, min.y, min.z, max.x, max.y, max.z]
        .into_iter()
        .flat_map(|v| f64::from(v).to_le_bytes())
        .collect()
}

fn i32_bytes(values: impl Iterator<Item = i32>) -> Vec<u8> {
    values.flat_map(i32::to_le_bytes).collect()
}

/// A time sampling's bytes for these times (time codes at `rate` per
/// second): uniform when evenly spaced, else acyclic.
fn time_sampling(times: &[f64], rate: f64) -> Vec<u8> {
    let seconds: Vec<f64> = times.iter().map(|t| t / rate).collect();
    let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    let uniform = steps
        .windows(2)
        .all(|w| (w[0] - w[1]).abs() <= 1e-9 * w[0].abs());
    let mut out = Vec::new();
    out.extend_from_slice(&(times.len() as u32).to_le_bytes());
    if uniform {
        let step = steps.first().copied().unwrap_or(1.0) / rate;
        out.extend_from_slice(&step.to_le_bytes());
        out.extend_from_slice(&1u32.to_le_bytes());
        out.extend_from_slice(&seconds.first().copied().unwrap_or(0.0).to_le_bytes());
    } else {
        out.extend_from_slice(&crate::abc::archive::ACYCLIC_TIME_PER_CYCLE.to_le_bytes());
        out.extend_from_slice(&(seconds.len() as u32).to_le_bytes());
        for s in seconds {
            out.extend_from_slice(&s.to_le_bytes());
        }
    }
    out
}

/// Writes one Alembic archive: the curves, their frames (time samples of
/// `P`), and the head and its poses; checked as the USD writers check
/// before the first byte.
pub fn write_abc(
    out: &mut impl Write,
    curves: &CurveSet,
    animation: Option<&Animation>,
    head: Option<&TriangleMesh>,
    head_poses: &[MeshPose],
) -> Result<(), WriteError> {
    let (with_width, _) = usd_inputs(Format::Abc, curves, animation, head, head_poses)?;
    let too_many = |what: &str| WriteError::invalid(Format::Abc, format!("more than 2^31 {what}"));
    if curves.point_count() > i32::MAX as usize {
        return Err(too_many("points"));
    }
    if head.is_some_and(|h| h.vertices_m.len() > i32::MAX as usize) {
        return Err(too_many("head vertices"));
    }
    let rate = animation.map_or(24.0, |a| a.time_codes_per_second);
    let mut samplings = vec![time_sampling(&[0.0], 1.0)];
    let frames = animation.map(|a| a.frames.as_slice()).unwrap_or(&[]);
    let frame_times: Vec<f64> = frames.iter().map(|f| f.time_code).collect();
    let hair_sampling = if frames.is_empty() {
        0
    } else {
        samplings.push(time_sampling(&frame_times, rate));
        1
    };
    let pose_times: Vec<f64> = head_poses.iter().map(|p| p.time_code).collect();
    let pose_sampling = if head_poses.is_empty() {
        0
    } else if pose_times == frame_times {
        hair_sampling
    } else {
        samplings.push(time_sampling(&pose_times, rate));
        samplings.len() as u32 - 1
    };

    let mut w = Writer {
        ogawa: OgawaWriter::new(),
    };
    let mut children = vec![hair(&mut w, curves, frames, hair_sampling, with_width)];
    if let Some(head) = head {
        children.push(head_object(&mut w, head, head_poses, pose_sampling));
    }
    let top = w.object("ABC", "", Vec::new(), children);
    let version = w.ogawa.data(&[&0i32.to_le_bytes()]);
    let library = w.ogawa.data(&[&LIBRARY_VERSION.to_le_bytes()]);
    let metadata = w.ogawa.data(&[b"_ai_Application=helixhair-formats"]);
    let samplings_bytes: Vec<u8> = samplings.concat();
    let samplings = w.ogawa.data(&[&samplings_bytes]);
    let indexed = w.ogawa.data(&[]);
    let root = w
        .ogawa
        .group(&[version, library, top.group, metadata, samplings, indexed]);
    let bytes = w.ogawa.finish(root);
    out.write_all(&bytes).map_err(WriteError::io(Format::Abc))
}

fn hair(
    w: &mut Writer,
    curves: &CurveSet,
    frames: &[crate::Frame],
    sampling: u32,
    with_width: bool,
) -> Obj {
    let still: Vec<Vec3> = curves
        .curves
        .iter()
        .flat_map(|c| c.points_m.iter().copied())
        .collect();
    let (points, bounds): (Vec<Vec<u8>>, Vec<Vec<u8>>) = if frames.is_empty() {
        (
            vec![points_bytes(still.iter())],
            vec![bounds_bytes(still.iter())],
        )
    } else {
        frames
            .iter()
            .map(|f| {
                (
                    points_bytes(f.points_m.iter()),
                    bounds_bytes(f.points_m.iter()),
                )
            })
            .unzip()
    };
    let count = points.len() as u32;
    let sampled = |stored| Samples {
        stored,
        count,
        time_sampling: sampling,
    };
    let mut props = vec![
        w.property(
            ".selfBnds",
            Kind::Scalar,
            (pod::F64, 6),
            "interpretation=box",
            sampled(&bounds),
        ),
        w.property(
            "P",
            Kind::Array,
            (pod::F32, 3),
            "geoScope=vtx;interpretation=point",
            sampled(&points),
        ),
    ];
    let counts = [i32_bytes(
        curves.curves.iter().map(|c| c.points_m.len() as i32),
    )];
    props.push(w.property(
        "nVertices",
        Kind::Array,
        (pod::I32, 1),
        "",
        sampled(&counts),
    ));
    let basis = [vec![1u8, 0, 0, 0]];
    props.push(w.property(
        "curveBasisAndType",
        Kind::Scalar,
        (pod::U8, 4),
        "",
        sampled(&basis),
    ));
    if with_width {
        let uniform = curves
            .curves
            .iter()
            .all(|c| matches!(c.width_m, Some(StrandValue::PerStrand(_))));
        let widths = curves.curves.iter().flat_map(|curve| {
            let n = if uniform { 1 } else { curve.points_m.len() };
            (0..n)
                .map(|i| curve.width_m.as_ref().and_then(|w| w.at(i)).unwrap_or(0.0))
                .collect::<Vec<_>>()
        });
        let widths = [f32_bytes(widths)];
        let scope = if uniform { "uni" } else { "vtx" };
        let metadata = format!(
            "arrayExtent=1;geoScope={scope};isGeomParam=true;podExtent=1;podName=float32_t"
        );
        props.push(w.property(
            "width",
            Kind::Array,
            (pod::F32, 1),
            &metadata,
            sampled(&widths),
        ));
    }
    let schema = format!("schema=AbcGeom_Curve_v2;{GEOM_BASE}");
    let geom = w.compound(".geom", &schema, props);
    let metadata = format!("{schema};schemaObjTitle=AbcGeom_Curve_v2:.geom");
    w.object("hair", &metadata, vec![geom], Vec::new())
}

fn head_object(w: &mut Writer, head: &TriangleMesh, poses: &[MeshPose], sampling: u32) -> Obj {
    let one = |stored| Samples {
        stored,
        count: 1,
        time_sampling: 0,
    };
    let bounds = [bounds_bytes(head.vertices_m.iter())];
    let points = [points_bytes(head.vertices_m.iter())];
    // Alembic winds faces clockwise: each triangle reversed.
    let indices = [i32_bytes(
        head.triangles
            .iter()
            .flat_map(|t| [t[0], t[2], t[1]])
            .map(|v| v as i32),
    )];
    let counts = [i32_bytes(head.triangles.iter().map(|_| 3))];
    let props = vec![
        w.property(
            ".selfBnds",
            Kind::Scalar,
            (pod::F64, 6),
            "interpretation=box",
            one(&bounds),
        ),
        w.property(
            "P",
            Kind::Array,
            (pod::F32, 3),
            "geoScope=vtx;interpretation=point",
            one(&points),
        ),
        w.property(
            ".faceIndices",
            Kind::Array,
            (pod::I32, 1),
            "",
            one(&indices),
        ),
        w.property(".faceCounts", Kind::Array, (pod::I32, 1), "", one(&counts)),
    ];
    let schema = format!("schema=AbcGeom_PolyMesh_v1;{GEOM_BASE}");
    let geom = w.compound(".geom", &schema, props);
    let metadata = format!("{schema};schemaObjTitle=AbcGeom_PolyMesh_v1:.geom");
    if poses.is_empty() {
        return w.object("head", &metadata, vec![geom], Vec::new());
    }
    let mesh = w.object("headShape", &metadata, vec![geom], Vec::new());
    // One matrix op (type 3): Imath's row-vector matrix, rows in order.
    let values: Vec<Vec<u8>> = poses
        .iter()
        .map(|pose| {
            let (r, t) = (pose.rotation, pose.translation_m);
            [
                r.x_axis.x, r.x_axis.y, r.x_axis.z, 0.0, r.y_axis.x, r.y_axis.y, r.y_axis.z, 0.0,
                r.z_axis.x, r.z_axis.y, r.z_axis.z, 0.0, t.x, t.y, t.z, 1.0,
            ]
            .into_iter()
            .flat_map(f64::to_le_bytes)
            .collect()
        })
        .collect();
    // `.inherits` gives the transform its sample count and times in
    // Alembic's reader; the values are in `.vals`.
    let inherits = Samples {
        stored: &[vec![1]],
        count: values.len() as u32,
        time_sampling: sampling,
    };
    let props = vec![
        w.property(".inherits", Kind::Scalar, (pod::BOOL, 1), "", inherits),
        w.property(".ops", Kind::Scalar, (pod::U8, 1), "", one(&[vec![0x30]])),
        w.property(
            ".vals",
            Kind::Scalar,
            (pod::F64, 16),
            "",
            Samples {
                stored: &values,
                count: values.len() as u32,
                time_sampling: sampling,
            },
        ),
        w.property(
            "isNotConstantIdentity",
            Kind::Scalar,
            (pod::BOOL, 1),
            "",
            one(&[vec![1]]),
        ),
    ];
    let xform = w.compound(".xform", "schema=AbcGeom_Xform_v3", props);
    w.object(
        "head",
        "schema=AbcGeom_Xform_v3;schemaObjTitle=AbcGeom_Xform_v3:.xform",
        vec![xform],
        vec![mesh],
    )
}
