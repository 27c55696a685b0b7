//! A RenderMan Interface session: what `RiBegin` … `RiEnd` opens, shared by the C binding
//! (`libillume`) and the Python module.
//!
//! Every call becomes one typed [`illume_rib::Request`], built by printing the call as a RIB
//! line and parsing it with the same parser `render` uses; the request then goes to one
//! [`Backend`]: the in-process renderer (the `ri` state machine and hider of `render`, so a
//! program and the RIB it captures render the same bits) or a RIB writer (canonical ASCII,
//! `catrib`'s form). A shadow `ri` state machine validates the stream for the RIB writer too, so
//! a bad call reaches the error handler whichever back end is open.
#![forbid(unsafe_code)]

mod backend;
mod call;
pub mod errors;
mod filter;
mod framebuffer;
mod ribwriter;

pub use backend::{Backend, InProcess};
pub use call::{Arg, Call, Counts, ParamData};
pub use errors::{RiError, ERRORS, SEVERITIES};
pub use filter::nearest_standard;
pub use framebuffer::{render_rib, Pixels};
pub use illume_core::filter::FilterTable;
pub use illume_rib::{Class, Type};
pub use ribwriter::{RibFormat, RibWriter};

use glam::{DMat4, DVec3};
use illume_ri::Ri;
use illume_rib::{Declaration, Request, Span, Spanned};
use std::path::Path;
use std::sync::Arc;

/// Where `Begin` sends the stream: the name `RiBegin` got, after `ILLUME_RIBOUT`.
pub fn target_for(name: Option<&str>) -> Option<String> {
    match name {
        Some("__render") | Some("") => None,
        Some(n) => Some(n.to_string()),
        None => std::env::var("ILLUME_RIBOUT")
            .ok()
            .filter(|s| !s.is_empty()),
    }
}

/// One open `RiBegin` … `RiEnd`.
pub struct Session {
    backend: Box<dyn Backend>,
    /// Validates the stream and answers `TransformPoints`; for the in-process back end it *is*
    /// the renderer's state (the back end renders the frames it hands over).
    ri: Ri,
    next_handle: i32,
    calls: u32,
    pending: Vec<RiError>,
}

impl Session {
    /// Opens a session: `None` renders in-process, `Some(path)` writes RIB there.
    pub fn begin(target: Option<&str>) -> Result<Session, RiError> {
        let backend: Box<dyn Backend> = match target {
            None => Box::new(InProcess::new()),
            Some(path) => Box::new(RibWriter::create(Path::new(path)).map_err(|e| {
                RiError::new(
                    errors::RIE_NOFILE,
                    errors::RIE_SEVERE,
                    format!("RiBegin: {path}: {e}"),
                )
            })?),
        };
        let mut ri = Ri::new();
        backend.configure(&mut ri);
        Ok(Session {
            backend,
            ri,
            next_handle: 1,
            calls: 0,
            pending: Vec::new(),
        })
    }

    /// A fresh light or object handle (RIB 3.2 sequence numbers).
    pub fn new_handle(&mut self) -> i32 {
        let h = self.next_handle;
        self.next_handle += 1;
        h
    }

    /// The declaration of a parameter token (inline or declared), for sizing its value array.
    pub fn declaration(&self, token: &str) -> Result<Declaration, String> {
        match Declaration::split_inline(token) {
            Ok((Some(d), _)) => Ok(d),
            Ok((None, name)) => self
                .ri
                .declarations()
                .get(name)
                .ok_or_else(|| format!("parameter `{name}` is not declared (RiDeclare it or write \"uniform float {name}\")")),
            Err(e) => Err(format!("parameter `{token}`: {e}")),
        }
    }

    /// Sends one call; problems are queued for [`Session::take_errors`].
    pub fn send(&mut self, call: Call) {
        self.pending.extend(call.problems.iter().cloned());
        self.send_rib(&call.name, &call.to_rib());
    }

    /// Sends RIB text (one call's line, or an `RiArchiveRecord` verbatim record).
    pub fn send_rib(&mut self, name: &str, text: &str) {
        self.calls += 1;
        let span = Span::new(Arc::from(format!("Ri{name}")), self.calls, 1, 0);
        let mut requests = Vec::new();
        for item in illume_rib::Parser::new(text.as_bytes(), &span.file) {
            match item {
                Ok(r) => requests.push(r.value),
                Err(d) => self.pending.push(RiError::from_rib(&d)),
            }
        }
        for value in requests {
            if let Request::Option { name, params } = &value {
                if name == "rib" {
                    let problems = self.backend.rib_option(params);
                    self.pending.extend(problems);
                    continue;
                }
            }
            if let Err(e) = self.backend.write(&value) {
                self.pending.push(e);
            }
            self.ri.request(Spanned {
                span: span.clone(),
                value,
            });
            self.hand_over();
        }
    }

    /// `RiPixelFilter` with a program's own function, tabulated on its support: the renderer
    /// filters with the table; the request (and so RIB output, with a warning) names the
    /// nearest standard kernel.
    pub fn user_pixel_filter(&mut self, xwidth: f32, ywidth: f32, table: FilterTable) {
        let name = nearest_standard(&table, xwidth, ywidth);
        if self.backend.writes_rib() {
            self.pending.push(RiError::new(
                errors::RIE_INCAPABLE,
                errors::RIE_WARNING,
                format!(
                    "RiPixelFilter: RIB can not hold a program's filter function; \
                     written as the nearest standard filter \"{name}\""
                ),
            ));
        }
        let mut call = Call::new("PixelFilter");
        call.args = vec![
            Arg::Str(name.to_string()),
            Arg::Float(xwidth),
            Arg::Float(ywidth),
        ];
        self.send(call);
        self.ri.set_filter_table(Some(Arc::new(table)));
    }

    /// The comment records of archive `name` (found as `ReadArchive` finds it: as given, then
    /// on the archive searchpath), in file order, as (structural `##`, text after the `#`s):
    /// what `RiReadArchive`'s callback is called with. ASCII, binary and gzip archives alike.
    pub fn archive_records(&self, name: &str) -> Result<Vec<(bool, String)>, RiError> {
        let given = Path::new(name);
        let path = std::iter::once(given.to_path_buf())
            .chain(
                self.ri
                    .options()
                    .archive_path
                    .iter()
                    .map(|d| Path::new(d).join(name)),
            )
            .find(|p| p.is_file())
            .ok_or_else(|| {
                RiError::new(
                    errors::RIE_NOFILE,
                    errors::RIE_ERROR,
                    format!(
                        "RiReadArchive: can not find \"{name}\" (searched the archive searchpath)"
                    ),
                )
            })?;
        let bad = |e: std::io::Error| {
            RiError::new(
                errors::RIE_BADFILE,
                errors::RIE_ERROR,
                format!("RiReadArchive: {}: {e}", path.display()),
            )
        };
        let mut parser = illume_rib::open(&path).map_err(bad)?.keep_comments();
        // Requests and their problems are `ReadArchive`'s business; only the records are kept.
        for _ in parser.by_ref() {}
        Ok(parser.take_comments())
    }

    /// `RiArchiveRecord(RI_COMMENT, …)`: a comment line for the RIB writer (the renderer has
    /// nothing to do with it). `RI_STRUCTURE` and `RI_VERBATIM` records go through [`Session::send_rib`].
    pub fn comment(&mut self, text: &str) {
        if let Err(e) = self.backend.comment(text) {
            self.pending.push(e);
        }
    }

    /// Records a problem found before a request could be made (bad token list, NULL pointer).
    pub fn report(&mut self, e: RiError) {
        self.pending.push(e);
    }

    fn hand_over(&mut self) {
        for d in self.ri.drain_diagnostics() {
            self.pending.push(RiError::from_ri(&d));
        }
        for frame in self.ri.take_frames() {
            self.pending.extend(self.backend.frame(frame));
        }
    }

    /// `RiEnd`: closes open blocks (an error each), renders what is left, flushes the file.
    pub fn end(mut self) -> Vec<RiError> {
        self.ri.finish();
        self.hand_over();
        if let Err(e) = self.backend.finish() {
            self.pending.push(e);
        }
        self.pending
    }

    /// Problems since the last call, in order, for the error handler.
    pub fn take_errors(&mut self) -> Vec<RiError> {
        std::mem::take(&mut self.pending)
    }

    /// `RiTransformPoints`: maps points from one named space to another (`None` when either
    /// space is unknown, as the spec's NULL return).
    pub fn transform_points(&self, from: &str, to: &str, points: &mut [[f32; 3]]) -> Option<()> {
        let from_m = self.ri.named_space(from)?;
        let to_m = self.ri.named_space(to)?;
        let m: DMat4 = to_m.inverse() * from_m;
        for p in points.iter_mut() {
            let q = m.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            *p = [q.x as f32, q.y as f32, q.z as f32];
        }
        Some(())
    }
}
