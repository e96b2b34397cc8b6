//! Finds the line an OBJ parse error is on.
//!
//! `tobj` says what kind of statement it could not read (a position, a
//! normal, a face, ...) but not where. This module re-reads the text and
//! returns the first line of that kind that is broken, with a short reason,
//! so a user can open the file at the right place. It checks only what
//! `tobj` checks, so it finds the line `tobj` stopped at.

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
    fn an_error_with_no_line_is_not_located() {
        assert_eq!(
            locate_obj_error("v 0 0 0\n", &tobj::LoadError::ReadError),
            None
        );
    }
}
