//! Many runs of one scene: parameter sweeps over scene keys ([`sweep`]),
//! the shards that split a sweep or a study across machines and the merge
//! that joins them again ([`shard`], the one home of `--shard I/N` and of
//! a row's provenance), and the wall-time budget of a study ([`budget`]).
//!
//! It builds on fc-scene (a run and its summary) and knows no study: the
//! CLI's `sweep` and `merge`, Python's `sweep` and `merge`, and fc-study's
//! sharded studies call it.

pub mod budget;
pub mod shard;
pub mod sweep;
