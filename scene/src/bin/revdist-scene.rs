//! `revdist-scene FILE`: runs a scene (also reached as `revdist scene FILE`).
fn main() {
    eprintln!("error: the scene runner is not built yet");
    std::process::exit(2);
}
