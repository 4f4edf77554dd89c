//! Random anchors: the chains always end where they must.

use super::{dist, torque_check};
use catenary::{discrete_equilibrium, joints, Catenary};
use proptest::prelude::*;

proptest! {
    #[test]
    fn random_anchors(
        x0 in -10.0..10.0f64,
        y0 in -10.0..10.0f64,
        d in 0.05..10.0f64,
        left in any::<bool>(),
        h in -10.0..10.0f64,
        stretch in 1.01..5.0f64,
        n in 2usize..300,
    ) {
        let p0 = [x0, y0];
        let p1 = [x0 + if left { -d } else { d }, y0 + h];
        let l = stretch * dist(p0, p1);
        let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
        let r = joints(p0, l, &eq.angles);
        prop_assert!(dist(r[n], p1) <= 1e-12 * l, "miss {:e}", dist(r[n], p1));
        if n >= 3 {
            let (_, torque) = torque_check(&r);
            prop_assert!(torque < 1e-10, "torque {:e}", torque);
        }
        let cat = Catenary::through(p0, p1, l).unwrap();
        prop_assert!((cat.y(p0[0]) - p0[1]).abs() <= 1e-12 * l);
        prop_assert!((cat.y(p1[0]) - p1[1]).abs() <= 1e-12 * l);
        prop_assert!((cat.arc_length(p0[0], p1[0]).abs() - l).abs() <= 1e-10 * l);
    }
}
