//! Every integration test of the formats crate in one binary, one module
//! per file: one link of the crate and its dependencies instead of one per
//! file. Run one file's tests with
//! `cargo test --release -p helixhair-formats --test suite <file>::`.

#[path = "support/alembic.rs"]
mod alembic;
mod common;
#[path = "support/pxr.rs"]
mod pxr;
#[path = "support/python.rs"]
mod python;

mod abc_alembic;
mod abc_hostile;
mod hair_hostile;
mod mutation;
mod obj_hostile;
mod repair;
mod round_trip;
mod sintel;
mod tfx_hostile;
mod usd_pxr;
mod usda_features;
mod usda_hostile;
mod usdc_hostile;
mod usdc_pxr;
