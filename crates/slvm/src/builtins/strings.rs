//! §15.5 string built-ins: `concat`, `format`, `printf`, `match`. Strings are uniform in
//! practice; a varying argument is read at the first grid point.
use super::{st, Args};
use crate::exec::Exec;
use crate::value::Value;
use illume_sl::ast::BuiltinId as B;

impl Exec<'_> {
    /// The string family; `None` for an overload the executor does not implement.
    pub(super) fn strings(&mut self, c: &Args) -> Option<Value> {
        let a = c.a;
        Some(match (c.id, a.len()) {
            (B::Concat, _) => Value::string(&a.iter().map(st).collect::<String>()),
            (B::Format | B::Printf, k) if k >= 1 => {
                let s = format_sl(&st(&a[0]), &a[1..]);
                if c.id == B::Printf {
                    eprint!("{s}");
                    Value::Void
                } else {
                    Value::string(&s)
                }
            }
            (B::Match, 2) => {
                let (pat, subject) = (st(&a[0]), st(&a[1]));
                Value::float(subject.contains(pat.as_str()) as u8 as f32)
            }
            _ => return None,
        })
    }
}

/// SL `format`/`printf`: `%f`, `%d`, `%s`, `%p`/`%c` (triples), `%m` (matrix), `%%`, read at
/// the first grid point (uniform use is what scenes do).
fn format_sl(fmt: &str, args: &[Value]) -> String {
    let mut out = String::new();
    let mut it = args.iter();
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        // Skip width/precision flags.
        while chars
            .peek()
            .is_some_and(|c| c.is_ascii_digit() || *c == '.' || *c == '-')
        {
            chars.next();
        }
        match chars.next() {
            Some('%') => out.push('%'),
            Some(_) => match it.next() {
                Some(Value::Float(s)) => out.push_str(&format!("{}", s.at(0))),
                Some(Value::Triple(s)) => {
                    let p = s.at(0);
                    out.push_str(&format!("{} {} {}", p.x, p.y, p.z))
                }
                Some(Value::String(s)) => out.push_str(s.at(0)),
                Some(Value::Matrix(s)) => out.push_str(&format!("{:?}", s.at(0).to_cols_array())),
                _ => {}
            },
            None => out.push('%'),
        }
    }
    out
}
