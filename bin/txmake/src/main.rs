fn main() {
    eprintln!("txmake: not built yet");
    std::process::exit(2);
}
