//! `catrib` as users run it: exit codes, fixed point, binary and gzip round trips, `-o`.
use std::io::Write;
use std::process::{Command, Output, Stdio};

const SCENE: &str = "##RenderMan RIB\nversion 3.03\nFormat 320 240 1\n\
Projection \"perspective\" \"fov\" 40\nWorldBegin\n  LightSource \"ambientlight\" 1 \"intensity\" .3\n\
  Color [1 0 0] # red\n  Sphere 1 -1 1 360 \"constant float Kd\" [0.25]\nWorldEnd\n";

fn catrib(args: &[&str], stdin: &[u8]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_catrib"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(stdin).unwrap();
    child.wait_with_output().unwrap()
}

#[test]
fn clean_input_exits_0_with_one_request_per_line() {
    let out = catrib(&["-"], SCENE.as_bytes());
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        text,
        "##RenderMan RIB\nversion 3.03\nFormat 320 240 1\nProjection \"perspective\" \"fov\" [40]\n\
         WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" [0.3]\nColor [1 0 0]\n\
         Sphere 1 -1 1 360 \"constant float Kd\" [0.25]\nWorldEnd\n"
    );
}

#[test]
fn output_is_a_fixed_point() {
    let once = catrib(&["-"], SCENE.as_bytes()).stdout;
    let twice = catrib(&["-"], &once).stdout;
    assert_eq!(
        String::from_utf8(twice).unwrap(),
        String::from_utf8(once).unwrap()
    );
}

#[test]
fn binary_and_gzip_round_trip_to_the_same_ascii() {
    let ascii = catrib(&["-"], SCENE.as_bytes()).stdout;
    let binary = catrib(&["--binary", "-"], SCENE.as_bytes());
    assert_eq!(binary.status.code(), Some(0));
    assert!(
        binary.stdout.iter().any(|&b| b >= 0x80),
        "binary output expected"
    );
    assert_eq!(catrib(&["-"], &binary.stdout).stdout, ascii);
    let gz = catrib(&["--binary", "--gzip", "-"], SCENE.as_bytes()).stdout;
    assert_eq!(&gz[..2], &[0x1f, 0x8b]);
    assert_eq!(catrib(&["-"], &gz).stdout, ascii);
}

#[test]
fn errors_exit_1_but_the_good_requests_are_still_written() {
    let out = catrib(&["-"], b"WorldBegin\nSphere 1 2 3\nWorldEnd\n");
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "WorldBegin\nWorldEnd\n"
    );
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "-:2:1: error: Sphere: expected 4 numbers, found 3\nSphere 1 2 3\n^\n"
    );
}

#[test]
fn unknown_requests_warn_pass_through_and_exit_0() {
    let out = catrib(&["-"], b"MyThing 1 \"a\"\nWorldBegin\n");
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "MyThing [1] [\"a\"]\nWorldBegin\n"
    );
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("warning: MyThing: unknown request"));
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(catrib(&[], b"").status.code(), Some(2));
    assert_eq!(catrib(&["--frobnicate", "-"], b"").status.code(), Some(2));
}

#[test]
fn missing_input_file_exits_1_and_names_it() {
    let out = catrib(&["/nonexistent/scene.rib"], b"");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("/nonexistent/scene.rib"));
}

#[test]
fn output_file_is_written_and_several_inputs_concatenate() {
    let dir = std::env::temp_dir().join(format!("catrib-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("a.rib");
    std::fs::write(&input, "WorldBegin\n").unwrap();
    let output = dir.join("out.rib");
    let out = catrib(
        &[
            "-o",
            output.to_str().unwrap(),
            input.to_str().unwrap(),
            input.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(
        std::fs::read_to_string(&output).unwrap(),
        "WorldBegin\nWorldBegin\n"
    );
    let leftovers = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(leftovers, 2, "no temporary file left behind");
    std::fs::remove_dir_all(&dir).unwrap();
}
