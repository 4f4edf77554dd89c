//! Speed against accuracy: work-precision diagrams, the stability map and
//! the cost of one right-hand side.

use super::Study;

pub const STUDIES: &[Study] = &[];
