#![allow(clippy::unwrap_used)]
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let c = browser::find().unwrap();
    let mut b = browser::Browser::launch(&c, std::path::Path::new("/tmp"), 1200, 900).unwrap();
    b.open(std::path::Path::new(&a[1])).unwrap();
    if a.len() > 3 {
        println!("{:?}", b.eval(&a[3]));
    }
    println!("{:?}", b.errors());
    std::fs::write(&a[2], b.screenshot().unwrap()).unwrap();
}
