//! The `--camera` option of `helixhair render`: a named view or numbers.

use std::str::FromStr;

use helixhair_render::OrbitCamera;

/// A view of the head: yaw and pitch in degrees, distance in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraArg {
    /// Turn around the head, degrees; 0 faces it, 90 sees its left side
    /// (the +x side).
    pub yaw_deg: f32,
    /// Elevation, degrees, within ±85.
    pub pitch_deg: f32,
    /// Distance from the head, metres, 0.1 to 10.
    pub distance_m: f32,
}

/// The named views and their numbers.
pub const NAMED_VIEWS: [(&str, CameraArg); 4] = [
    (
        "front",
        CameraArg {
            yaw_deg: 0.0,
            pitch_deg: 5.0,
            distance_m: 0.8,
        },
    ),
    (
        "side",
        CameraArg {
            yaw_deg: 90.0,
            pitch_deg: 5.0,
            distance_m: 0.8,
        },
    ),
    (
        "back",
        CameraArg {
            yaw_deg: 180.0,
            pitch_deg: 10.0,
            distance_m: 0.8,
        },
    ),
    (
        "three-quarter",
        CameraArg {
            yaw_deg: 35.0,
            pitch_deg: 12.0,
            distance_m: 0.8,
        },
    ),
];

impl FromStr for CameraArg {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        if let Some((_, view)) = NAMED_VIEWS.iter().find(|(name, _)| *name == text) {
            return Ok(*view);
        }
        let names: Vec<&str> = NAMED_VIEWS.iter().map(|(n, _)| *n).collect();
        let expected = format!(
            "expected {} or YAW,PITCH,DISTANCE (degrees, degrees, metres)",
            names.join(", ")
        );
        let numbers: Vec<f32> = text
            .split(',')
            .map(|x| x.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("`{text}`: {expected}"))?;
        let [yaw_deg, pitch_deg, distance_m] = numbers[..] else {
            return Err(format!("`{text}`: {expected}"));
        };
        if !yaw_deg.is_finite()
            || !(-85.0..=85.0).contains(&pitch_deg)
            || !(0.1..=10.0).contains(&distance_m)
        {
            return Err(format!(
                "`{text}`: yaw must be finite, pitch within ±85 degrees and distance within 0.1..10 m"
            ));
        }
        Ok(Self {
            yaw_deg,
            pitch_deg,
            distance_m,
        })
    }
}

impl CameraArg {
    /// The orbit camera of this view, aimed at the default target.
    pub fn camera(&self) -> OrbitCamera {
        OrbitCamera {
            yaw_rad: self.yaw_deg.to_radians(),
            pitch_rad: self.pitch_deg.to_radians(),
            distance_m: self.distance_m,
            ..OrbitCamera::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_views_and_numbers_parse_and_bad_ones_say_what_is_expected() {
        assert_eq!("front".parse::<CameraArg>().map(|c| c.yaw_deg), Ok(0.0));
        let c: CameraArg = "-30, 20, 1.5".parse().expect("numbers");
        assert_eq!((c.yaw_deg, c.pitch_deg, c.distance_m), (-30.0, 20.0, 1.5));
        for bad in ["above", "1,2", "0,90,1", "0,0,0"] {
            let error = bad.parse::<CameraArg>().expect_err(bad);
            assert!(error.starts_with(&format!("`{bad}`")), "{error}");
        }
    }
}
