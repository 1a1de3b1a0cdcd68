//! `ehl-bearing` command line.

fn main() {
    println!("ehl-bearing");
}
