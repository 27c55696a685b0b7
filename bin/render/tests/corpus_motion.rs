//! `render` on the corpus' motion-blur scene (Aqsis `transmb_test.rib`: moving, scaling and
//! rotating spheres and a cylinder, with motion blocks that cancel), in a temporary directory:
//! exit code 0, no panic, and its framebuffer PNG written.
use std::process::Command;

#[test]
fn transmb_test_renders_cleanly() {
    let Some(rib) = illume_testenv::shared_file("corpus/aqsis2001/transmb_test.rib") else {
        return; // skipped loudly; a failure under CI=true
    };
    let dir = std::env::temp_dir().join(format!("illume-transmb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_render"))
        .arg("-q")
        .arg(&rib)
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(dir.join("transmb_test.png").is_file(), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}
