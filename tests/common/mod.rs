//! The integration tests' helpers: the shared `ppoe-test-support` crate (also used by
//! `examples/accuracy.rs`), re-exported so that each test keeps `mod common;`.
#![allow(unused_imports)]

pub use ppoe_test_support::*;
