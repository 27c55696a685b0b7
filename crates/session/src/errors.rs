//! RI error codes and severities (RI Spec 3.2 Appendix C, `ri.h`), and the conversion of the
//! `ri` state machine's diagnostics (which carry their [`illume_ri::ErrorKind`]) to them.
use illume_ri::{Diagnostic, Severity};

pub const RIE_NOERROR: i32 = 0;
pub const RIE_NOMEM: i32 = 1;
pub const RIE_SYSTEM: i32 = 2;
pub const RIE_NOFILE: i32 = 3;
pub const RIE_BADFILE: i32 = 4;
pub const RIE_VERSION: i32 = 5;
pub const RIE_DISKFULL: i32 = 6;
pub const RIE_INCAPABLE: i32 = 11;
pub const RIE_UNIMPLEMENT: i32 = 12;
pub const RIE_LIMIT: i32 = 13;
pub const RIE_BUG: i32 = 14;
pub const RIE_NOTSTARTED: i32 = 23;
pub const RIE_NESTING: i32 = 24;
pub const RIE_NOTOPTIONS: i32 = 25;
pub const RIE_NOTATTRIBS: i32 = 26;
pub const RIE_NOTPRIMS: i32 = 27;
pub const RIE_ILLSTATE: i32 = 28;
pub const RIE_BADMOTION: i32 = 29;
pub const RIE_BADSOLID: i32 = 30;
pub const RIE_BADTOKEN: i32 = 41;
pub const RIE_RANGE: i32 = 42;
pub const RIE_CONSISTENCY: i32 = 43;
pub const RIE_BADHANDLE: i32 = 44;
pub const RIE_NOSHADER: i32 = 45;
pub const RIE_MISSINGDATA: i32 = 46;
pub const RIE_SYNTAX: i32 = 47;
pub const RIE_MATH: i32 = 61;

pub const RIE_INFO: i32 = 0;
pub const RIE_WARNING: i32 = 1;
pub const RIE_ERROR: i32 = 2;
pub const RIE_SEVERE: i32 = 3;

/// Every code above with its `ri.h` name (the C header's values are tested against these).
pub const ERRORS: &[(&str, i32)] = &[
    ("RIE_NOERROR", RIE_NOERROR),
    ("RIE_NOMEM", RIE_NOMEM),
    ("RIE_SYSTEM", RIE_SYSTEM),
    ("RIE_NOFILE", RIE_NOFILE),
    ("RIE_BADFILE", RIE_BADFILE),
    ("RIE_VERSION", RIE_VERSION),
    ("RIE_DISKFULL", RIE_DISKFULL),
    ("RIE_INCAPABLE", RIE_INCAPABLE),
    ("RIE_UNIMPLEMENT", RIE_UNIMPLEMENT),
    ("RIE_LIMIT", RIE_LIMIT),
    ("RIE_BUG", RIE_BUG),
    ("RIE_NOTSTARTED", RIE_NOTSTARTED),
    ("RIE_NESTING", RIE_NESTING),
    ("RIE_NOTOPTIONS", RIE_NOTOPTIONS),
    ("RIE_NOTATTRIBS", RIE_NOTATTRIBS),
    ("RIE_NOTPRIMS", RIE_NOTPRIMS),
    ("RIE_ILLSTATE", RIE_ILLSTATE),
    ("RIE_BADMOTION", RIE_BADMOTION),
    ("RIE_BADSOLID", RIE_BADSOLID),
    ("RIE_BADTOKEN", RIE_BADTOKEN),
    ("RIE_RANGE", RIE_RANGE),
    ("RIE_CONSISTENCY", RIE_CONSISTENCY),
    ("RIE_BADHANDLE", RIE_BADHANDLE),
    ("RIE_NOSHADER", RIE_NOSHADER),
    ("RIE_MISSINGDATA", RIE_MISSINGDATA),
    ("RIE_SYNTAX", RIE_SYNTAX),
    ("RIE_MATH", RIE_MATH),
];

pub const SEVERITIES: &[(&str, i32)] = &[
    ("RIE_INFO", RIE_INFO),
    ("RIE_WARNING", RIE_WARNING),
    ("RIE_ERROR", RIE_ERROR),
    ("RIE_SEVERE", RIE_SEVERE),
];

/// One problem for `RiErrorHandler`: code, severity and the `file:line:col` message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RiError {
    pub code: i32,
    pub severity: i32,
    pub message: String,
}

impl RiError {
    pub fn new(code: i32, severity: i32, message: impl Into<String>) -> RiError {
        RiError {
            code,
            severity,
            message: message.into(),
        }
    }

    /// A message from the `ri` state machine (or the renderer): its code is the kind the
    /// report site gave it ([`illume_ri::ErrorKind`]), its severity the diagnostic's.
    pub fn from_ri(d: &Diagnostic) -> RiError {
        let severity = match d.severity {
            Severity::Warning => RIE_WARNING,
            Severity::Error => RIE_ERROR,
        };
        RiError::new(d.code(), severity, d.to_string())
    }

    /// A parse problem of a call's RIB line: the binding passed something RIB cannot say.
    pub fn from_rib(d: &illume_rib::Diagnostic) -> RiError {
        let severity = if d.is_error() { RIE_ERROR } else { RIE_WARNING };
        RiError::new(RIE_SYNTAX, severity, d.to_string())
    }
}
