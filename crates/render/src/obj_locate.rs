//! Finds the line an OBJ parse error is on.
//!
//! `tobj` says what kind of statement it could not read (a position, a
//! normal, a face, ...) but not where. This module re-reads the text and
//! returns the first line of that kind that is broken, with a short reason,
//! so a user can open the file at the right place. It checks only what
//! `tobj` checks, so it finds the line `tobj` stopped at.
//!
//! It also checks every element index *before* `tobj` reads the file
//! ([`find_index_out_of_range`]): `tobj` 4 resolves a relative index such
//! as `1/-2` with unchecked arithmetic, so a texture or normal index before
//! the first `vt`/`vn` wraps to a huge number and overflows (a panic where
//! overflow checks are on; found by fuzzing, see docs/reliability.md).

/// Counts of the indexed statements read so far.
#[derive(Default)]
struct Counts {
    positions: usize,
    texcoords: usize,
    normals: usize,
}

/// Whether `words` holds at least `n` numbers (`tobj` reads the first `n`).
fn has_numbers(words: &[&str], n: usize) -> bool {
    words.len() >= n && words[..n].iter().all(|w| w.parse::<f32>().is_ok())
}

/// Why face corner `corner` is broken, if it is: each of its `/`-separated
/// indices must be an integer naming an existing element (1-based, or
/// negative counting back from the last).
fn corner_problem(corner: &str, counts: &Counts, total_positions: usize) -> Option<String> {
    let kinds = [
        ("vertex", total_positions),
        ("texture coordinate", counts.texcoords),
        ("normal", counts.normals),
    ];
    for (part, (kind, available)) in corner.split('/').zip(kinds) {
        if part.is_empty() && kind != "vertex" {
            continue;
        }
        let Ok(index) = part.parse::<isize>() else {
            return Some(format!("`{part}` in `{corner}` is not a {kind} index"));
        };
        let in_range = match index {
            0 => false,
            i if i > 0 => i as usize <= available,
            i => i.unsigned_abs() <= available,
        };
        if !in_range {
            return Some(format!(
                "{kind} {index} does not exist (the file has {available} before this line)"
            ));
        }
    }
    None
}

/// The first face, line or point statement (1-based line) whose vertex,
/// texture or normal index names nothing, and why.
///
/// A negative (relative) index counts back from the elements read so far,
/// as the OBJ format defines; a positive one may name any element of the
/// file. Run before `tobj`, so that `tobj` never resolves an index that does
/// not exist.
pub fn find_index_out_of_range(text: &str) -> Option<(usize, String)> {
    let mut total = Counts::default();
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => total.positions += 1,
            Some("vt") => total.texcoords += 1,
            Some("vn") => total.normals += 1,
            _ => {}
        }
    }
    let mut before = Counts::default();
    for (i, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some((&keyword, args)) = words.split_first() else {
            continue;
        };
        match keyword {
            "v" => before.positions += 1,
            "vt" => before.texcoords += 1,
            "vn" => before.normals += 1,
            "f" | "l" | "p" => {
                let problem = args
                    .iter()
                    .find_map(|corner| index_problem(corner, &before, &total));
                if let Some(problem) = problem {
                    return Some((i + 1, problem));
                }
            }
            _ => {}
        }
    }
    None
}

/// Why an index of `corner` names nothing: negative indices count back
/// from `before`, positive ones may reach anything in `total`. Parse errors
/// are left to `tobj` (and [`locate_obj_error`]).
fn index_problem(corner: &str, before: &Counts, total: &Counts) -> Option<String> {
    let kinds = [
        ("vertex", before.positions, total.positions),
        ("texture coordinate", before.texcoords, total.texcoords),
        ("normal", before.normals, total.normals),
    ];
    for (part, (kind, so_far, in_file)) in corner.split('/').zip(kinds) {
        let Ok(index) = part.parse::<i64>() else {
            continue;
        };
        let (in_range, available) = match index {
            0 => (false, in_file),
            i if i > 0 => (i.unsigned_abs() as usize <= in_file, in_file),
            i => (i.unsigned_abs() as usize <= so_far, so_far),
        };
        if !in_range {
            return Some(format!(
                "{kind} {index} in `{corner}` does not exist (there are {available} to refer to)"
            ));
        }
    }
    None
}

/// The first line (1-based) that makes `tobj` fail with `error`, and why.
pub fn locate_obj_error(text: &str, error: &tobj::LoadError) -> Option<(usize, String)> {
    use tobj::LoadError as E;
    let total_positions = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count();
    let mut counts = Counts::default();
    for (i, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some((&keyword, args)) = words.split_first() else {
            continue;
        };
        let problem = match (keyword, error) {
            ("v", E::PositionParseError) if !has_numbers(args, 3) => {
                Some(format!("`{line}` needs three numbers x y z"))
            }
            ("vn", E::NormalParseError) if !has_numbers(args, 3) => {
                Some(format!("`{line}` needs three numbers x y z"))
            }
            ("vt", E::TexcoordParseError) if !has_numbers(args, 2) => {
                Some(format!("`{line}` needs two numbers u v"))
            }
            (
                "f",
                E::FaceParseError
                | E::FaceVertexOutOfBounds
                | E::FaceNormalOutOfBounds
                | E::FaceTexCoordOutOfBounds
                | E::InvalidPolygon,
            ) => {
                // Out-of-bounds indices are found when a group ends, against
                // every vertex of the file; the others while reading.
                let positions = match error {
                    E::FaceParseError => counts.positions,
                    _ => total_positions,
                };
                if args.len() < 3 && matches!(error, E::InvalidPolygon) {
                    Some(format!("`{line}` has fewer than three corners"))
                } else {
                    args.iter()
                        .find_map(|c| corner_problem(c, &counts, positions))
                }
            }
            _ => None,
        };
        if let Some(problem) = problem {
            return Some((i + 1, problem));
        }
        match keyword {
            "v" => counts.positions += 1,
            "vt" => counts.texcoords += 1,
            "vn" => counts.normals += 1,
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn broken_normals_and_faces_are_found() {
        let text = "v 0 0 0\nvn 0 1\nf 1 a 1\n";
        let normal = locate_obj_error(text, &tobj::LoadError::NormalParseError);
        assert_eq!(normal.map(|(line, _)| line), Some(2));
        let face = locate_obj_error(text, &tobj::LoadError::FaceParseError);
        let (line, why) = face.expect("found");
        assert_eq!(line, 3);
        assert!(why.contains("`a`"), "{why}");
    }

    #[test]
    fn relative_indices_count_back_from_what_was_read() {
        // The fuzzer's find: `1/-2` before any `vt` overflowed inside tobj.
        let text = "v 0 0 0\nl 1/-2 1\nvt 0 0\nvt 0 0\n";
        let (line, why) = find_index_out_of_range(text).expect("found");
        assert_eq!(line, 2);
        assert!(why.contains("texture coordinate -2"), "{why}");
        // Forward positive references and in-range relative ones are fine.
        let fine = "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
        assert_eq!(find_index_out_of_range(fine), None);
        assert!(find_index_out_of_range("v 0 0 0\nf 0 1 1\n").is_some());
    }

    #[test]
    fn an_error_with_no_line_is_not_located() {
        assert_eq!(
            locate_obj_error("v 0 0 0\n", &tobj::LoadError::ReadError),
            None
        );
    }
}
