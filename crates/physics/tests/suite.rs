//! Every test of the physics crate, one module per file, in one binary:
//! one link of the crate and its dependencies instead of one per file, and
//! no unit-test build (`[lib] test = false`, which would compile the whole
//! crate a second time). Run one file's tests with
//! `cargo test --release -p helixhair-physics --test suite collision::`.

mod common;

mod batch_contact;
mod batch_guard;
mod batch_implicit_contact;
mod batch_lanes;
mod batch_parity;
mod batch_stable_step;
mod batch_volume;
mod block_contact;
mod block_velocity_terms;
mod collision;
mod derivatives;
mod engine;
mod f64_instance;
mod failure_modes;
mod fit;
mod geometry;
mod gpu_curves;
mod gpu_dense;
mod gpu_engine;
mod gpu_layout;
mod gpu_measure;
mod gpu_parity;
mod guard_acceleration_jump;
mod guards;
mod invariants;
mod lane_coefficients;
mod lane_fma;
mod lane_screen;
mod lane_trig;
mod reconstruction;
mod rest_contact;
mod solvers;
mod stable_step;
mod statics;
mod velocity_terms;
mod vibration;
mod volume;
mod volume_guard;
mod volume_lanes;
