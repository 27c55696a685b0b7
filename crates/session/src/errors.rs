//! RI error codes and severities (RI Spec 3.2 Appendix C, `ri.h`), and the mapping from the
//! `ri` state machine's messages to them.
use illume_ri::{Diagnostic, Severity};

pub const RIE_NOERROR: i32 = 0;
pub const RIE_SYSTEM: i32 = 2;
pub const RIE_NOFILE: i32 = 3;
pub const RIE_BADFILE: i32 = 4;
pub const RIE_UNIMPLEMENT: i32 = 12;
pub const RIE_BUG: i32 = 14;
pub const RIE_NOTSTARTED: i32 = 23;
pub const RIE_NESTING: i32 = 24;
pub const RIE_NOTOPTIONS: i32 = 25;
pub const RIE_NOTPRIMS: i32 = 27;
pub const RIE_ILLSTATE: i32 = 28;
pub const RIE_BADTOKEN: i32 = 41;
pub const RIE_RANGE: i32 = 42;
pub const RIE_CONSISTENCY: i32 = 43;
pub const RIE_BADHANDLE: i32 = 44;
pub const RIE_MISSINGDATA: i32 = 46;
pub const RIE_SYNTAX: i32 = 47;

pub const RIE_INFO: i32 = 0;
pub const RIE_WARNING: i32 = 1;
pub const RIE_ERROR: i32 = 2;
pub const RIE_SEVERE: i32 = 3;

/// Every code above with its `ri.h` name (the C header's values are tested against these).
pub const ERRORS: &[(&str, i32)] = &[
    ("RIE_NOERROR", RIE_NOERROR),
    ("RIE_NOFILE", RIE_NOFILE),
    ("RIE_BADFILE", RIE_BADFILE),
    ("RIE_UNIMPLEMENT", RIE_UNIMPLEMENT),
    ("RIE_BUG", RIE_BUG),
    ("RIE_NOTSTARTED", RIE_NOTSTARTED),
    ("RIE_NESTING", RIE_NESTING),
    ("RIE_NOTOPTIONS", RIE_NOTOPTIONS),
    ("RIE_NOTPRIMS", RIE_NOTPRIMS),
    ("RIE_ILLSTATE", RIE_ILLSTATE),
    ("RIE_BADTOKEN", RIE_BADTOKEN),
    ("RIE_RANGE", RIE_RANGE),
    ("RIE_CONSISTENCY", RIE_CONSISTENCY),
    ("RIE_BADHANDLE", RIE_BADHANDLE),
    ("RIE_MISSINGDATA", RIE_MISSINGDATA),
    ("RIE_SYNTAX", RIE_SYNTAX),
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

    /// A message from the `ri` state machine; its code is read off the message (the state
    /// machine words each kind of problem one way).
    pub fn from_ri(d: &Diagnostic) -> RiError {
        let m = d.message.as_str();
        let code = if m.contains("only valid inside") || m.contains("outside") {
            RIE_NOTPRIMS
        } else if m.contains("options can not change") {
            RIE_NOTOPTIONS
        } else if m.contains("never closed") || m.contains("without") || m.contains("nest") {
            RIE_NESTING
        } else if m.contains("not declared") || m.contains("unknown parameter") {
            RIE_BADTOKEN
        } else if m.contains("handle") {
            RIE_BADHANDLE
        } else if m.contains("cannot open") || m.contains("No such file") {
            RIE_NOFILE
        } else if d.severity == Severity::Warning {
            RIE_UNIMPLEMENT
        } else {
            RIE_CONSISTENCY
        };
        let severity = match d.severity {
            Severity::Warning => RIE_WARNING,
            Severity::Error => RIE_ERROR,
        };
        RiError::new(code, severity, d.to_string())
    }

    /// A parse problem of a call's RIB line: the binding passed something RIB cannot say.
    pub fn from_rib(d: &illume_rib::Diagnostic) -> RiError {
        let severity = if d.is_error() { RIE_ERROR } else { RIE_WARNING };
        RiError::new(RIE_SYNTAX, severity, d.to_string())
    }
}
