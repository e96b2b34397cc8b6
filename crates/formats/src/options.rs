//! What a caller can tell a reader that the file does not say.

use crate::curve_set::UpAxis;

/// Reading choices. The default reads every format as its own convention
/// says: TressFX, `.hair`, OBJ and Alembic in metres with Y up (they
/// declare neither), USD as its `metersPerUnit` and `upAxis` say (USD's fallbacks
/// when absent: 0.01 m, Y).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// The file's length unit in metres, overriding what the file declares
    /// (e.g. 0.01 for a `.hair` model authored in centimetres). Must be
    /// finite and positive.
    pub metres_per_unit: Option<f64>,
    /// The file's up axis, overriding what the file declares (e.g.
    /// [`UpAxis::Z`] for Cem Yuksel's models).
    pub up_axis: Option<UpAxis>,
}
