//! reyes-fuzz: a coverage-guided, structure-aware fuzzer of reyes-render's inputs.
//!
//! Targets ([`target`]): the RON loader and validator, the RIB reader with the RI state
//! machine and validator, and whole renders at small sizes in child processes under a memory
//! cap. Coverage ([`coverage`]) comes from the compiler's SanitizerCoverage pass on the stable
//! toolchain (`cargo xtask fuzz` builds with it); without it the same loop is a plain
//! mutational fuzzer, which is what the CI test runs. Mutations ([`mutate`]) know the shape
//! of scene text: numbers, words, bracketed lists, lines.
//!
//! See docs/reliability.md, "Fuzzing", for how to run it and what it found.

pub mod coverage;
pub mod engine;
pub mod limits;
pub mod mutate;
pub mod rng;
pub mod target;
