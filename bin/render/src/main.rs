fn main() {
    eprintln!("render: not built yet");
    std::process::exit(2);
}
