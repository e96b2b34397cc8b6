//! Heads as Wavefront OBJ files: loading a user's head (through the `tobj`
//! crate) and writing one (the default head's asset).
//!
//! The scalp is the faces of the OBJ group or object named `scalp` (any
//! case); all other faces are the rest of the head. A head without one
//! loads (a style that lists its roots needs no scalp); a style that
//! grows hair on the scalp is then refused by the caller, which knows it
//! needs one ([`HeadMesh::scalp_triangles`] is empty). Normals come from the
//! file's `vn` lines when every face has them, and are computed otherwise.
//! Faces with more than three corners are triangulated.
//!
//! `tobj` reports what went wrong but not where, so on a parse error
//! [`crate::obj_locate`] finds the first line of the kind `tobj` refused, and
//! the error names it: `head.obj:12: position parse error: ...`.

use std::fmt;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::mesh::{HeadMesh, Mesh};
use crate::obj_locate::{find_index_out_of_range, locate_obj_error};

/// The name of the OBJ group or object that holds the scalp faces.
pub const SCALP_GROUP: &str = "scalp";

/// What a head without a scalp group is told when a style grows hair on
/// its scalp.
pub const NO_SCALP_HINT: &str = "it has no scalp: put the faces hair grows on in a group \
     named `scalp` (a line `g scalp` before them), or list the style's roots";

/// Why a head could not be loaded from an OBJ file.
#[derive(Debug, thiserror::Error)]
pub enum ObjError {
    /// The file could not be read.
    /// (The I/O error is part of the message, not a `source`: error
    /// chains printed whole, as the binary prints them, would say it twice.)
    #[error("{}: cannot read the head mesh: {error}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The file was read but does not describe a usable head.
    #[error("{location}: {message}")]
    Invalid {
        /// The file and, when known, the 1-based line.
        location: ObjLocation,
        /// What is wrong, in words.
        message: String,
    },
}

/// A file and, when known, a 1-based line in it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjLocation {
    /// The file.
    pub path: PathBuf,
    /// The 1-based line, when the problem is on one line.
    pub line: Option<usize>,
}

impl fmt::Display for ObjLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}", self.path.display()),
            None => write!(f, "{}", self.path.display()),
        }
    }
}

fn invalid(path: &Path, line: Option<usize>, message: impl Into<String>) -> ObjError {
    ObjError::Invalid {
        location: ObjLocation {
            path: path.to_owned(),
            line,
        },
        message: message.into(),
    }
}

/// Reads the head at `path`; see [`parse_head_obj`].
pub fn load_head_obj(path: &Path) -> Result<HeadMesh, ObjError> {
    let text = std::fs::read_to_string(path).map_err(|error| ObjError::Read {
        path: path.to_owned(),
        error,
    })?;
    parse_head_obj(&text, path)
}

/// Loads any closed mesh as a head: its `scalp` group if it has one, and
/// every face as scalp otherwise (an imported groom brings its own roots,
/// so it needs no scalp to grow on; `helixhair import --head`).
pub fn load_mesh_obj(path: &Path) -> Result<HeadMesh, ObjError> {
    let text = std::fs::read_to_string(path).map_err(|error| ObjError::Read {
        path: path.to_owned(),
        error,
    })?;
    parse_obj(&text, path, true)
}

/// Parses a head from OBJ text; `path` only names the file in errors.
pub fn parse_head_obj(text: &str, path: &Path) -> Result<HeadMesh, ObjError> {
    parse_obj(text, path, false)
}

/// Parses OBJ text; without a `scalp` group the mesh has no scalp, or,
/// with `all_scalp_without_group`, every face is scalp.
fn parse_obj(text: &str, path: &Path, all_scalp_without_group: bool) -> Result<HeadMesh, ObjError> {
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    // Indices are checked first: tobj's own arithmetic on an index that
    // names nothing can overflow (see obj_locate).
    if let Some((line, problem)) = find_index_out_of_range(text) {
        return Err(invalid(path, Some(line), problem));
    }
    // A head needs no materials: `mtllib` lines are ignored.
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|error| {
        let (line, detail) = locate_obj_error(text, &error).unzip();
        let detail = detail.map_or(String::new(), |d| format!(": {d}"));
        invalid(path, line, format!("{error}{detail}"))
    })?;

    let mut head = HeadMesh::default();
    let mut every_face_has_normals = true;
    for model in &models {
        let m = &model.mesh;
        let first = head.mesh.positions.len() as u32;
        let first_triangle = head.mesh.triangle_count() as u32;
        head.mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        every_face_has_normals &= m.normals.len() == m.positions.len();
        head.mesh.normals.extend(
            m.normals
                .chunks_exact(3)
                .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or(Vec3::Y)),
        );
        head.mesh
            .indices
            .extend(m.indices.iter().map(|i| i + first));
        if model.name.trim().eq_ignore_ascii_case(SCALP_GROUP) {
            let last_triangle = head.mesh.triangle_count() as u32;
            head.scalp_triangles.extend(first_triangle..last_triangle);
        }
    }
    check_head(&head.mesh, path)?;
    if !every_face_has_normals {
        head.mesh.compute_normals();
    }
    // A mesh read for another use than a head (an imported groom's bust,
    // `load_mesh_obj`) has every face as scalp; a head without a scalp
    // group loads with none, and the caller refuses styles that need one.
    if head.scalp_triangles.is_empty() && all_scalp_without_group {
        head.scalp_triangles = (0..head.mesh.triangle_count() as u32).collect();
    }
    Ok(head)
}

/// A head has triangles and finite coordinates.
fn check_head(mesh: &Mesh, path: &Path) -> Result<(), ObjError> {
    if mesh.triangle_count() == 0 {
        return Err(invalid(path, None, "no faces: a head needs triangles"));
    }
    if let Some(p) = mesh.positions.iter().find(|p| !p.is_finite()) {
        return Err(invalid(
            path,
            None,
            format!("a vertex position is not finite: {p}"),
        ));
    }
    Ok(())
}

/// The head as OBJ text: positions, normals, then the non-scalp faces in
/// group `head` and the scalp faces in group [`SCALP_GROUP`].
pub fn write_head_obj(head: &HeadMesh, comment: &str) -> String {
    let mut out = String::new();
    for line in comment.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let mesh = &head.mesh;
    for p in &mesh.positions {
        let _ = writeln!(out, "v {:.6} {:.6} {:.6}", p.x, p.y, p.z);
    }
    for n in &mesh.normals {
        let _ = writeln!(out, "vn {:.5} {:.5} {:.5}", n.x, n.y, n.z);
    }
    let mut is_scalp = vec![false; mesh.triangle_count()];
    for &t in &head.scalp_triangles {
        is_scalp[t as usize] = true;
    }
    for (group, want) in [("head", false), (SCALP_GROUP, true)] {
        let _ = writeln!(out, "g {group}");
        for t in (0..mesh.triangle_count()).filter(|&t| is_scalp[t] == want) {
            let i = &mesh.indices[3 * t..3 * t + 3];
            let _ = writeln!(
                out,
                "f {a}//{a} {b}//{b} {c}//{c}",
                a = i[0] + 1,
                b = i[1] + 1,
                c = i[2] + 1
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head_generate::default_head;

    #[test]
    fn the_default_head_round_trips_through_obj() {
        let head = default_head();
        let text = write_head_obj(&head, "test");
        let back = parse_head_obj(&text, Path::new("head.obj")).expect("loads");
        assert_eq!(back.mesh.triangle_count(), head.mesh.triangle_count());
        assert_eq!(back.scalp_triangles.len(), head.scalp_triangles.len());
        let area = (back.scalp_area_m2() - head.scalp_area_m2()).abs();
        assert!(area < 1e-6, "{area}");
    }

    fn error(text: &str) -> String {
        parse_head_obj(text, Path::new("bad.obj"))
            .expect_err("refused")
            .to_string()
    }

    #[test]
    fn a_broken_position_names_its_line() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 x 1\ng scalp\nf 1 2 3\n";
        let message = error(text);
        assert!(
            message.starts_with("bad.obj:3: position parse error"),
            "{message}"
        );
    }

    #[test]
    fn a_face_beyond_the_vertices_names_its_line() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\ng scalp\nf 1 2 3\nf 1 2 9\n";
        let message = error(text);
        assert!(message.starts_with("bad.obj:6: "), "{message}");
        assert!(message.contains("vertex 9"), "{message}");
    }

    /// The fuzzer's reproducer (crates/app/fuzz/found): tobj overflowed on
    /// a relative texture index before any `vt`; now a located error.
    #[test]
    fn obj_head_tobj_texcoord_index_overflow() {
        let text = "0\nl  1 1/-2   1 1/-2 2 1 11/-21  1 1/-2  0\nvt 0 0\nl 1/1 2/1\nl 2 3\nl -2 1\nv 1 1 0\nvt 0 0\nl  0\nvt 0 0\nl 1/1 2/1\nl 2 3\nl\n";
        let message = error(text);
        assert!(message.starts_with("bad.obj:2: "), "{message}");
        assert!(message.contains("does not exist"), "{message}");
    }

    #[test]
    fn a_head_without_scalp_loads_with_none() {
        // Styles that list their roots need no scalp (issue 14, item 10).
        let head = parse_head_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Path::new("a.obj"))
            .expect("loads");
        assert!(head.scalp_triangles.is_empty());
        assert!(NO_SCALP_HINT.contains("g scalp"), "{NO_SCALP_HINT}");
    }

    #[test]
    fn a_missing_file_says_why_once_even_as_a_chain() {
        let error = load_head_obj(Path::new("/nonexistent/head.obj")).expect_err("refused");
        assert!(std::error::Error::source(&error).is_none());
        let message = error.to_string();
        assert_eq!(message.matches("No such file").count(), 1, "{message}");
    }

    #[test]
    fn faces_without_normals_get_computed_ones() {
        let head = parse_head_obj(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\ng Scalp\nf 1 2 3\n",
            Path::new("tri.obj"),
        )
        .expect("loads");
        assert_eq!(head.scalp_triangles, [0]);
        assert!((head.mesh.normals[0] - Vec3::Z).length() < 1e-6);
    }
}
