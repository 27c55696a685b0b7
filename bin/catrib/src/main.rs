fn main() {
    eprintln!("catrib: not built yet");
    std::process::exit(2);
}
