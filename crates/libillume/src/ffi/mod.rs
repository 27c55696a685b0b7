//! The `extern "C"` side the C half calls: every pointer the program passed is read here, once,
//! into owned Rust values. This is the crate's only `unsafe` code.
#![allow(unsafe_code)]

use crate::state::{with, State};
use illume_session::{errors, Arg, Call, Counts, ParamData, RiError, Session};
use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

extern "C" {
    /// Defined in csrc/ri.c: sets `RiLastError` and calls the program's `RiErrorHandler`.
    fn illume_dispatch_error(code: c_int, severity: c_int, message: *const c_char);
}

/// Runs `f` on the state, then hands queued errors to the C handler with the lock released
/// (the handler may call Ri again). A panic (a bug) becomes `RIE_BUG`, never an unwind into C.
fn with_state<R: Default>(f: impl FnOnce(&mut State) -> R) -> R {
    let result = catch_unwind(AssertUnwindSafe(|| with(f)));
    let (value, bug) = match result {
        Ok(v) => (v, None),
        Err(_) => (
            R::default(),
            Some(RiError::new(
                errors::RIE_BUG,
                errors::RIE_SEVERE,
                "internal error (panic) in libillume",
            )),
        ),
    };
    let mut queued = with(State::take_errors);
    queued.extend(bug);
    for e in queued {
        let msg = CString::new(e.message.replace('\0', " ")).unwrap_or_default();
        // SAFETY: `msg` is a valid NUL-terminated string that outlives the call; the handler is
        // the program's (or a built-in) function taking (int, int, char *).
        unsafe { illume_dispatch_error(e.code, e.severity, msg.as_ptr()) };
    }
    value
}

/// Reads a C string; `None` for NULL. Invalid UTF-8 is replaced, not rejected.
///
/// SAFETY (caller): `p` is NULL or a NUL-terminated string valid for reads.
unsafe fn string(p: *const c_char) -> Option<String> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-null and NUL-terminated per the caller's contract.
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
}

/// Copies `n` elements from a C array; empty for NULL or n <= 0.
///
/// SAFETY (caller): `p` is NULL or points to at least `n` initialised `T`s.
unsafe fn slice<T: Copy>(p: *const T, n: c_int) -> Option<Vec<T>> {
    if n <= 0 {
        return Some(Vec::new());
    }
    if p.is_null() {
        return None;
    }
    // SAFETY: non-null, `n` > 0 elements readable per the caller's contract.
    Some(unsafe { std::slice::from_raw_parts(p, n as usize) }.to_vec())
}

/// SAFETY (caller): `p` is NULL or points to `n` pointers that are NULL or C strings.
unsafe fn strings(p: *const *const c_char, n: c_int) -> Option<Vec<String>> {
    // SAFETY: forwarded contract.
    let ptrs = unsafe { slice(p, n) }?;
    // SAFETY: each element is NULL or a C string per the contract.
    Some(
        ptrs.into_iter()
            .map(|s| unsafe { string(s) }.unwrap_or_default())
            .collect(),
    )
}

fn call_mut(st: &mut State) -> &mut Call {
    st.call.get_or_insert_with(|| Call::new("?"))
}

fn missing(st: &mut State, what: &str) {
    let name = call_mut(st).name.clone();
    call_mut(st).problems.push(RiError::new(
        errors::RIE_MISSINGDATA,
        errors::RIE_ERROR,
        format!("Ri{name}: {what} is NULL"),
    ));
}

/// `RiBegin(name)`: NULL renders in-process unless `ILLUME_RIBOUT` names a RIB file.
#[no_mangle]
pub extern "C" fn illume_begin(name: *const c_char) {
    // SAFETY: `name` is RI_NULL or a C string (ri.h contract).
    let name = unsafe { string(name) };
    with_state(|st| {
        if st.session.is_some() {
            st.report(RiError::new(
                errors::RIE_NESTING,
                errors::RIE_ERROR,
                "RiBegin: a session is already open (ignored)",
            ));
            return;
        }
        match Session::begin(illume_session::target_for(name.as_deref()).as_deref()) {
            Ok(s) => st.session = Some(s),
            Err(e) => st.report(e),
        }
    })
}

#[no_mangle]
pub extern "C" fn illume_end() {
    with_state(|st| match st.session.take() {
        Some(s) => st.orphan.extend(s.end()),
        None => st.report(not_started("End")),
    })
}

fn not_started(name: &str) -> RiError {
    RiError::new(
        errors::RIE_NOTSTARTED,
        errors::RIE_ERROR,
        format!("Ri{name}: called before RiBegin (ignored)"),
    )
}

/// Starts building the call to request `name` (as RIB spells it).
#[no_mangle]
pub extern "C" fn illume_call(name: *const c_char) {
    // SAFETY: the C half passes string literals.
    let name = unsafe { string(name) }.unwrap_or_default();
    with(|st| st.call = Some(Call::new(&name)));
}

#[no_mangle]
pub extern "C" fn illume_float(f: f32) {
    with(|st| call_mut(st).args.push(Arg::Float(f)));
}

#[no_mangle]
pub extern "C" fn illume_int(i: c_int) {
    with(|st| call_mut(st).args.push(Arg::Int(i)));
}

#[no_mangle]
pub extern "C" fn illume_string(s: *const c_char) {
    // SAFETY: the program's string argument: NULL or a C string.
    let s = unsafe { string(s) };
    with(|st| match s {
        Some(s) => call_mut(st).args.push(Arg::Str(s)),
        None => {
            missing(st, "a string argument");
            call_mut(st).args.push(Arg::Str(String::new()));
        }
    })
}

#[no_mangle]
pub extern "C" fn illume_floats(n: c_int, p: *const f32) {
    // SAFETY: the C half passes the program's array with the length the RI spec gives it.
    let v = unsafe { slice(p, n) };
    with(|st| match v {
        Some(v) => call_mut(st).args.push(Arg::Floats(v)),
        None => {
            missing(st, "a float array");
            call_mut(st).args.push(Arg::Floats(Vec::new()));
        }
    })
}

#[no_mangle]
pub extern "C" fn illume_ints(n: c_int, p: *const c_int) {
    // SAFETY: as `illume_floats`.
    let v = unsafe { slice(p, n) };
    with(|st| match v {
        Some(v) => call_mut(st).args.push(Arg::Ints(v)),
        None => {
            missing(st, "an integer array");
            call_mut(st).args.push(Arg::Ints(Vec::new()));
        }
    })
}

#[no_mangle]
pub extern "C" fn illume_strings(n: c_int, p: *const *const c_char) {
    // SAFETY: as `illume_floats`, elements are C strings.
    let v = unsafe { strings(p, n) };
    with(|st| match v {
        Some(v) => call_mut(st).args.push(Arg::Strings(v)),
        None => {
            missing(st, "a string array");
            call_mut(st).args.push(Arg::Strings(Vec::new()));
        }
    })
}

/// The token/value list, sized per token by its declaration and the primitive's class counts.
#[no_mangle]
pub extern "C" fn illume_params(
    n: c_int,
    tokens: *const *const c_char,
    parms: *const *const c_void,
    uniform: c_int,
    varying: c_int,
    vertex: c_int,
    facevarying: c_int,
) {
    let counts = Counts {
        uniform: uniform.max(0) as usize,
        varying: varying.max(0) as usize,
        vertex: vertex.max(0) as usize,
        facevarying: facevarying.max(0) as usize,
    };
    with(|st| params(st, n, tokens, parms, counts))
}

/// The body of [`illume_params`].
fn params(
    st: &mut State,
    n: c_int,
    tokens: *const *const c_char,
    parms: *const *const c_void,
    counts: Counts,
) {
    let name = call_mut(st).name.clone();
    if n > 0 && (tokens.is_null() || parms.is_null()) {
        let e = RiError::new(
            errors::RIE_MISSINGDATA,
            errors::RIE_ERROR,
            format!("Ri{name}: {n} parameters but a NULL token or value list (parameters ignored)"),
        );
        call_mut(st).problems.push(e);
        return;
    }
    // SAFETY: ri.h contract: `n` tokens and `n` value pointers.
    let (toks, vals) = unsafe {
        (
            slice(tokens, n).unwrap_or_default(),
            slice(parms, n).unwrap_or_default(),
        )
    };
    for (tok, val) in toks.into_iter().zip(vals) {
        // SAFETY: each token is NULL or a C string.
        let Some(token) = (unsafe { string(tok) }) else {
            let e = RiError::new(
                errors::RIE_BADTOKEN,
                errors::RIE_ERROR,
                format!("Ri{name}: NULL parameter token (skipped)"),
            );
            call_mut(st).problems.push(e);
            continue;
        };
        let decl = match st.session.as_ref().map(|s| s.declaration(&token)) {
            Some(Ok(d)) => d,
            Some(Err(m)) => {
                let e = RiError::new(
                    errors::RIE_BADTOKEN,
                    errors::RIE_ERROR,
                    format!("Ri{name}: {m} (skipped)"),
                );
                call_mut(st).problems.push(e);
                continue;
            }
            None => continue,
        };
        if val.is_null() {
            let e = RiError::new(
                errors::RIE_MISSINGDATA,
                errors::RIE_ERROR,
                format!("Ri{name}: parameter `{token}` has a NULL value (skipped)"),
            );
            call_mut(st).problems.push(e);
            continue;
        }
        let len = (counts.of(decl.class) * decl.element_size()).min(i32::MAX as usize) as c_int;
        // SAFETY: the RI contract sizes the value array by the declaration and class counts.
        let data = unsafe {
            match decl.ty {
                illume_session::Type::Integer => {
                    ParamData::Ints(slice(val as *const c_int, len).unwrap_or_default())
                }
                illume_session::Type::String => ParamData::Strings(
                    strings(val as *const *const c_char, len).unwrap_or_default(),
                ),
                _ => ParamData::Floats(slice(val as *const f32, len).unwrap_or_default()),
            }
        };
        call_mut(st).params.push((token, data));
    }
}

/// Sends the call built since `illume_call`.
#[no_mangle]
pub extern "C" fn illume_send() {
    with_state(|st| {
        let call = st.call.take().unwrap_or_else(|| Call::new("?"));
        match &mut st.session {
            Some(s) => s.send(call),
            None => st.orphan.push(not_started(&call.name)),
        }
    })
}

/// A new light or object handle (0 without a session: the C half returns NULL).
#[no_mangle]
pub extern "C" fn illume_handle() -> c_int {
    with_state(|st| st.session.as_mut().map_or(0, |s| s.new_handle()))
}

/// `RiArchiveRecord(RI_COMMENT, …)`: a `#` comment line in RIB output.
#[no_mangle]
pub extern "C" fn illume_comment(text: *const c_char) {
    // SAFETY: the C half passes its formatted buffer.
    let text = unsafe { string(text) }.unwrap_or_default();
    with_state(|st| match &mut st.session {
        Some(s) => s.comment(&text),
        None => st.orphan.push(not_started("ArchiveRecord")),
    })
}

/// An error the C half found (bad arguments it checks itself).
#[no_mangle]
pub extern "C" fn illume_report(code: c_int, severity: c_int, message: *const c_char) {
    // SAFETY: the C half passes its formatted buffer.
    let message = unsafe { string(message) }.unwrap_or_default();
    with_state(|st| st.report(RiError::new(code, severity, message)))
}

/// `RiTransformPoints`: 1 when done in place, 0 (the spec's NULL) when a space is unknown.
#[no_mangle]
pub extern "C" fn illume_transform_points(
    from: *const c_char,
    to: *const c_char,
    n: c_int,
    points: *mut f32,
) -> c_int {
    // SAFETY: names are C strings or NULL.
    let (Some(from), Some(to)) = (unsafe { string(from) }, unsafe { string(to) }) else {
        return 0;
    };
    if n <= 0 || points.is_null() {
        return i32::from(n == 0);
    }
    // SAFETY: `points` is the program's RtPoint[n]: 3n contiguous floats, writable.
    let pts = unsafe { std::slice::from_raw_parts_mut(points as *mut [f32; 3], n as usize) };
    with_state(|st| {
        st.session
            .as_ref()
            .and_then(|s| s.transform_points(&from, &to, pts))
            .map_or(0, |()| 1)
    })
}

/// `RiArchiveRecord(RI_STRUCTURE | RI_VERBATIM, …)`: RIB text sent as if read from a file.
#[no_mangle]
pub extern "C" fn illume_verbatim(text: *const c_char) {
    // SAFETY: the C half passes its formatted buffer.
    let text = unsafe { string(text) }.unwrap_or_default();
    with_state(|st| match &mut st.session {
        Some(s) => s.send_rib("ArchiveRecord", &text),
        None => st.orphan.push(not_started("ArchiveRecord")),
    })
}

/// A program's own filter function: `RtFilterFunc` of ri.h.
type FilterFunc = extern "C" fn(f32, f32, f32, f32) -> f32;

/// Cells per axis of a program's tabulated pixel filter.
const FILTER_TABLE_SIZE: usize = 64;

/// `RiPixelFilter(myfilter, xwidth, ywidth)`: calls the program's function once per table
/// cell, here on the program's thread, so the renderer never calls foreign code.
#[no_mangle]
pub extern "C" fn illume_user_pixel_filter(f: FilterFunc, xwidth: f32, ywidth: f32) {
    if !(xwidth > 0.0 && ywidth > 0.0) {
        // The request itself reports the bad widths.
        let mut call = Call::new("PixelFilter");
        call.args = vec![
            Arg::Str("box".into()),
            Arg::Float(xwidth),
            Arg::Float(ywidth),
        ];
        return with_state(|st| match &mut st.session {
            Some(s) => s.send(call),
            None => st.orphan.push(not_started("PixelFilter")),
        });
    }
    let table = illume_session::FilterTable::tabulate(FILTER_TABLE_SIZE, xwidth, ywidth, |x, y| {
        f(x, y, xwidth, ywidth)
    });
    with_state(|st| match &mut st.session {
        Some(s) => s.user_pixel_filter(xwidth, ywidth, table),
        None => st.orphan.push(not_started("PixelFilter")),
    })
}

/// Called once per comment record by [`illume_archive_records`]: (context, structural, text).
type RecordFunc = extern "C" fn(*mut c_void, c_int, *const c_char);

/// `RiReadArchive`'s callback: hands each comment record of the archive to `record` (the C
/// half turns it into the program's `RtArchiveCallback(type, "%s", text)`). The session is not
/// borrowed while the program's callback runs (it may call Ri).
#[no_mangle]
pub extern "C" fn illume_archive_records(
    name: *const c_char,
    record: RecordFunc,
    context: *mut c_void,
) {
    // SAFETY: the program's archive name: NULL or a C string.
    let Some(name) = (unsafe { string(name) }) else {
        return;
    };
    // A missing or unreadable archive is reported by the `ReadArchive` request itself.
    let records: Vec<(bool, String)> = with_state(|st| {
        st.session
            .as_ref()
            .and_then(|s| s.archive_records(&name).ok())
            .unwrap_or_default()
    });
    for (structural, text) in records {
        let text = CString::new(text.replace('\0', " ")).unwrap_or_default();
        record(context, c_int::from(structural), text.as_ptr());
    }
}
