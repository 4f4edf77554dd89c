use catenary::*;
fn main() {
    let cases: [([f64; 2], [f64; 2], f64); 3] = [
        ([0.0, 0.0], [5.0, 1.0], 6.0),
        ([0.0, 0.0], [1.0, 0.0], 50.0),
        ([0.0, 0.0], [0.05, 3.2247960820488197], 1.01 * 3.2251836),
    ];
    for (p0, p1, l) in cases {
        for n in [2, 3, 10, 50, 301, 2000] {
            println!(
                "{p0:?} {p1:?} {l} {n}: {:?}",
                discrete_equilibrium(p0, p1, l, n).map(|e| (
                    e.iterations,
                    e.end_error,
                    e.alpha,
                    e.beta
                ))
            );
        }
    }
}
