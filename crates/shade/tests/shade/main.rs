//! Integration tests of reyes-shade against analytic geometry: one binary, one module per
//! effect, shared helpers in `common`.

mod common;

mod glass;
mod local;
mod mirror;
mod motion;
mod penumbra;
mod recursion;
mod renderman;
mod shapes;
