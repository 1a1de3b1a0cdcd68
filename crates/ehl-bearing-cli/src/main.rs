//! `ehl-bearing` command line.

mod ehl_cmd;
mod plot;

fn main() {
    let _ = (ehl_cmd::PLACEHOLDER, plot::PLACEHOLDER);
    println!("ehl-bearing");
}
