#![doc = include_str!("../README.md")]
#![deny(missing_docs)]

pub mod contact;
pub mod error;
pub mod math;
pub mod shape;
pub mod solve;
pub mod broad_phase;
pub mod dem;
pub mod integrate;
pub mod scene;
pub mod output;
pub mod reproduce;
