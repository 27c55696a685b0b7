//! `Procedural` (RI Spec 3.2 §5.7): `DelayedReadArchive` and `RunProgram`, expanded when their
//! bound reaches the screen; `DynamicLoad` is refused (no native code is loaded).
use crate::archive::Scope;
use crate::state::Ri;
use illume_rib::Span;
use std::path::{Path, PathBuf};

impl Ri {
    pub(crate) fn procedural(
        &mut self,
        kind: &str,
        args: &[String],
        bound: &[f32; 6],
        span: &Span,
    ) {
        if !self.in_world() {
            self.diagnostics.error_kind(
                crate::ErrorKind::NotPrims,
                span,
                "Procedural",
                "only valid inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if !self.world_active {
            return;
        }
        let on_screen = match self.raster_bound(bound, self.ctm) {
            None => true,
            Some(r) => {
                let cam = self.camera.as_ref().expect("in world");
                let margin = f64::from(self.options.filter.1.max(self.options.filter.2));
                let [x0, x1, y0, y1] = cam.crop.map(f64::from);
                r[1] >= x0 - margin
                    && r[0] <= x1 + margin
                    && r[3] >= y0 - margin
                    && r[2] <= y1 + margin
            }
        };
        match kind {
            "DelayedReadArchive" => {
                let Some(file) = args.first() else {
                    self.diagnostics
                        .error(span, "Procedural", "DelayedReadArchive expects a file name");
                    return;
                };
                if on_screen {
                    self.read_archive(file, span, Scope::Block);
                }
            }
            "RunProgram" => {
                if on_screen {
                    let detail = self
                        .raster_bound(bound, self.ctm)
                        .map_or(f64::INFINITY, |r| (r[1] - r[0]) * (r[3] - r[2]));
                    self.run_program(args, detail, span);
                }
            }
            "DynamicLoad" => self.diagnostics.error(
                span,
                "Procedural",
                "DynamicLoad is unsupported: Illume does not load native code; use RunProgram or DelayedReadArchive",
            ),
            other => self.diagnostics.error(
                span,
                "Procedural",
                format!("unknown procedural \"{other}\", expected DelayedReadArchive, RunProgram or DynamicLoad"),
            ),
        }
    }

    /// `Procedural "RunProgram" ["prog args" "data"]`: the program reads `detail data` lines on
    /// stdin and answers each with RIB ending in a 0xFF byte (RI Spec 3.2 §5.7).
    pub(crate) fn run_program(&mut self, args: &[String], detail: f64, span: &Span) {
        use std::io::Write;
        use std::process::{Command, Stdio};
        let (Some(prog), data) = (args.first(), args.get(1).cloned().unwrap_or_default()) else {
            self.diagnostics
                .error(span, "Procedural", "RunProgram expects a program name");
            return;
        };
        let mut words = prog.split_whitespace();
        let Some(exe) = words.next() else {
            self.diagnostics
                .error(span, "Procedural", "RunProgram: empty program name");
            return;
        };
        let exe_path = self
            .options
            .procedural_path
            .iter()
            .map(|d| Path::new(d).join(exe))
            .find(|p| p.is_file())
            .unwrap_or_else(|| PathBuf::from(exe));
        let child = Command::new(&exe_path)
            .args(words)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn();
        let mut child = match child {
            Ok(c) => c,
            Err(e) => {
                self.diagnostics
                    .error(span, "Procedural", format!("RunProgram \"{exe}\": {e}"));
                return;
            }
        };
        if let Some(mut stdin) = child.stdin.take() {
            let _ = writeln!(stdin, "{detail} {data}");
        }
        let output = match child.wait_with_output() {
            Ok(o) => o,
            Err(e) => {
                self.diagnostics
                    .error(span, "Procedural", format!("RunProgram \"{exe}\": {e}"));
                return;
            }
        };
        let mut bytes = output.stdout;
        while bytes.last() == Some(&0xFF) {
            bytes.pop();
        }
        self.read_stream(
            Box::new(std::io::Cursor::new(bytes)),
            &format!("{exe} (RunProgram)"),
            span,
            "Procedural",
            Scope::Block,
        );
    }
}
