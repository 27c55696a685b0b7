//! Archives and object instances (RI Spec 3.2 §4.4, §5.6, appendix D.3): `ObjectBegin`/
//! `ArchiveBegin` record requests, `ObjectInstance` and `ReadArchive` replay them or read a
//! file. `ReadArchive` is textual inclusion; instances and procedurals run inside an attribute
//! block that closes whatever they left open (see [`Scope`]).
use crate::instance::SharedObject;
use crate::state::{BlockKind, Ri};
use illume_rib::{Handle, Request, Span, Spanned};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// How the requests of an archive, an object instance or a procedural relate to the graphics
/// state of the request that brought them in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scope {
    /// `ReadArchive`: textual inclusion, as if the archive's requests stood in its place
    /// (PRMan and Aqsis behave so). What it sets persists (a camera transform, `Format` or
    /// `Projection` before `WorldBegin`, attributes, lights), and blocks it opens stay open
    /// for the reader to close: exporters split one frame across archives that way.
    Inline,
    /// `ObjectInstance` and procedurals: inside an attribute block, so they can not leak
    /// state into their reader; blocks they leave open are closed (an error each).
    Block,
}

pub(crate) enum Recording {
    Object(Handle),
    Archive(String),
}

impl Ri {
    /// While inside `ObjectBegin`/`ArchiveBegin`, requests are stored, not executed.
    pub(crate) fn record(&mut self, req: &Spanned<Request>) -> bool {
        match (&req.value, &mut self.recording) {
            (Request::ObjectBegin(h), None) => {
                self.recording = Some((Recording::Object(h.clone()), req.span.clone(), vec![]));
                true
            }
            (Request::ArchiveBegin { name, .. }, None) => {
                self.recording = Some((Recording::Archive(name.clone()), req.span.clone(), vec![]));
                true
            }
            (Request::ObjectEnd, Some((Recording::Object(_), ..)))
            | (Request::ArchiveEnd, Some((Recording::Archive(_), ..))) => {
                let Some((rec, _, reqs)) = self.recording.take() else {
                    return true;
                };
                match rec {
                    Recording::Object(h) => {
                        let reqs = Arc::new(reqs);
                        match SharedObject::analyse(self, reqs.clone()) {
                            Some(shared) => self.shared_objects.insert(h.clone(), Arc::new(shared)),
                            None => self.shared_objects.remove(&h),
                        };
                        self.objects.insert(h, reqs);
                    }
                    Recording::Archive(n) => {
                        self.archives.insert(n, Arc::new(reqs));
                    }
                }
                true
            }
            (Request::ObjectBegin(_) | Request::ArchiveBegin { .. }, Some(_)) => {
                self.diagnostics.error_kind(
                    crate::ErrorKind::Nesting,
                    &req.span,
                    req.value.name(),
                    "definitions can not nest (ignored)",
                );
                true
            }
            (Request::ObjectEnd | Request::ArchiveEnd, Some((open, span, _))) => {
                let expected = match open {
                    Recording::Object(_) => "ObjectEnd",
                    Recording::Archive(_) => "ArchiveEnd",
                };
                let msg = format!("expected {expected} to close the definition at {span}");
                self.diagnostics.error(&req.span, req.value.name(), msg);
                self.recording = None;
                true
            }
            (_, Some((_, _, reqs))) => {
                reqs.push(req.clone());
                true
            }
            (_, None) => false,
        }
    }

    pub(crate) fn object_instance(&mut self, h: &Handle, span: &Span) {
        let Some(reqs) = self.objects.get(h).cloned() else {
            self.diagnostics.error_kind(
                crate::ErrorKind::BadHandle,
                span,
                "ObjectInstance",
                format!("no object with handle {h:?}"),
            );
            return;
        };
        if !self.share_instance(h, span) {
            self.replay(&reqs, span, "ObjectInstance", Scope::Block);
        }
    }

    /// Adds an instance of a shared object as one primitive (see `instance.rs`); false when it
    /// must be replayed: outside an active world, in motion, in a solid, under `DetailRange`,
    /// at the nesting limit or past a vertex limit (replaying reports what applies).
    fn share_instance(&mut self, h: &Handle, span: &Span) -> bool {
        let Some(object) = self.shared_objects.get(h).cloned() else {
            return false;
        };
        let plain = self.in_world()
            && self.world_active
            && self.motion.is_none()
            && self.ctm_motion.is_none()
            && self.open_solids.is_empty()
            && self.attributes.detail_range.is_none()
            && self.nesting < self.options.limits.nesting as usize
            && object.vertices <= self.options.limits.vertices;
        if !plain {
            return false;
        }
        // The instance itself is what the frame keeps; its primitives exist only while the
        // hider works on the buckets it covers.
        self.add_instance(&object, span);
        true
    }

    pub(crate) fn replay(
        &mut self,
        reqs: &[Spanned<Request>],
        span: &Span,
        what: &str,
        scope: Scope,
    ) {
        self.nested(span, what, scope, |ri| {
            for r in reqs {
                ri.request(r.clone());
            }
        });
    }

    /// Runs `body` (the requests of an archive, instance or procedural) one nesting level
    /// deeper, inside an attribute block unless it is inlined.
    fn nested(&mut self, span: &Span, what: &str, scope: Scope, body: impl FnOnce(&mut Ri)) {
        // Nested reads (an archive that reads itself) beyond the limit are an error, not a
        // stack overflow.
        let max = self.options.limits.nesting as usize;
        if self.nesting >= max {
            self.diagnostics.error_kind(
                crate::ErrorKind::Limit,
                span,
                what,
                format!(
                    "nested more than Option \"limits\" \"nesting\" {max} levels deep (recursive archive?); not read"
                ),
            );
            return;
        }
        self.nesting += 1;
        let depth = self.blocks.len();
        if scope == Scope::Block {
            self.push_block(BlockKind::Attribute, span);
        }
        body(self);
        if scope == Scope::Block {
            self.close_to(depth, span, what);
        }
        self.nesting -= 1;
    }

    /// Closes blocks an archive left open, so it can not leak state into its reader.
    pub(crate) fn close_to(&mut self, depth: usize, span: &Span, what: &str) {
        while self.blocks.len() > depth + 1 {
            let b = self.blocks.last().expect("len > depth + 1");
            let msg = format!("{} at {} left open; closed", b.kind.begin(), b.span);
            self.diagnostics.error(span, what, msg);
            self.pop_block();
        }
        if self.blocks.len() > depth {
            self.pop_block();
        }
    }

    pub(crate) fn resolve(&self, file: &str, span: &Span) -> Option<PathBuf> {
        let p = Path::new(file);
        if p.is_absolute() || p.exists() {
            return Some(p.to_path_buf());
        }
        let base = Path::new(&*span.file).parent().map(Path::to_path_buf);
        self.options
            .archive_path
            .iter()
            .map(|d| Path::new(d).join(file))
            .chain(base.map(|b| b.join(file)))
            .find(|c| c.exists())
    }

    pub(crate) fn read_archive(&mut self, file: &str, span: &Span, scope: Scope) {
        if let Some(reqs) = self.archives.get(file).cloned() {
            self.replay(&reqs, span, "ReadArchive", scope);
            return;
        }
        let Some(path) = self.resolve(file, span) else {
            self.diagnostics.error_kind(
                crate::ErrorKind::NoFile,
                span,
                "ReadArchive",
                format!("can not find \"{file}\" (searched the archive searchpath and the including file's directory)"),
            );
            return;
        };
        match std::fs::File::open(&path) {
            Ok(f) => self.read_stream(
                Box::new(std::io::BufReader::new(f)),
                &path.display().to_string(),
                span,
                "ReadArchive",
                scope,
            ),
            Err(e) => self.diagnostics.error_kind(
                crate::ErrorKind::BadFile,
                span,
                "ReadArchive",
                format!("{}: {e}", path.display()),
            ),
        }
    }

    pub(crate) fn read_stream(
        &mut self,
        reader: Box<dyn Read>,
        name: &str,
        span: &Span,
        what: &str,
        scope: Scope,
    ) {
        let Some(parser) = self.parser.as_ref() else {
            self.diagnostics
                .error(span, what, "no RIB parser is plugged in to read archives");
            return;
        };
        let source = parser(reader, name);
        self.nested(span, what, scope, |ri| ri.run(source));
    }
}
