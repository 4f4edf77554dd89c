//! Validation against physics: convergence in n, the folded chain against
//! its analytic law, the energy budget, normal modes and the support force.

use super::Study;

pub const STUDIES: &[Study] = &[];
