//! §15.8 message passing and information: `lightsource()` inside `illuminance`, `surface()`,
//! `displacement()`, `atmosphere()` reading the primitive's other shaders ([`crate::Messages`]),
//! `incident()`/`opposite()` (no volumes run: "not found"), and the `attribute()`, `option()`,
//! `rendererinfo()`, `textureinfo()` queries. Each writes its output argument only when the
//! value is found and fits the variable, and returns 1 or 0.
use super::{st, Args};
use crate::exec::Exec;
use crate::geometric;
use crate::value::{Mask, Slot, Value};
use glam::Vec3;
use illume_sl::ast::{BuiltinId as B, Expr};

impl Exec<'_> {
    /// The message-passing family; `None` for an overload the executor does not implement.
    pub(super) fn message(&mut self, c: &Args) -> Option<Value> {
        let (a, exprs, mask) = (c.a, c.exprs, c.mask);
        Some(match (c.id, a.len()) {
            (B::LightSource, 2) => {
                let found = self
                    .current_light
                    .and_then(|k| self.lights.lights.get(k))
                    .and_then(|l| l.param(&st(&a[0])));
                self.answer_message(found, &a[1], &exprs[1], mask)
            }
            (B::Surface | B::Displacement | B::Atmosphere, 2) => {
                // The other shader's parameter values as the renderer handed them over (see
                // `Messages`); an unknown name or a type mismatch is "not found".
                let key = st(&a[0]);
                let list = match c.id {
                    B::Surface => &self.messages.surface,
                    B::Displacement => &self.messages.displacement,
                    _ => &self.messages.atmosphere,
                };
                let found = list.iter().find(|(k, _)| *k == key).map(|(_, v)| v.clone());
                self.answer_message(found, &a[1], &exprs[1], mask)
            }
            (B::Incident | B::Opposite, 2) => {
                // Volume shaders do not run, so there is no volume to ask: "not found".
                Value::float(0.0)
            }
            (B::Attribute | B::Option | B::RendererInfo, 2) => {
                let key = st(&a[0]);
                let found = match c.id {
                    B::Attribute => self.env.attributes.and_then(|t| t.get(&key)).cloned(),
                    B::Option => self.env.options.and_then(|t| t.get(&key)).cloned(),
                    _ => illume_shade::rendererinfo(&key),
                };
                self.answer_query(found, &a[1], &exprs[1], mask)
            }
            (B::TextureInfo, 3) => {
                let (map, key) = (st(&a[0]), st(&a[1]));
                let found = self.env.textures.and_then(|t| t.textureinfo(&map, &key));
                self.answer_query(found, &a[2], &exprs[2], mask)
            }
            _ => return None,
        })
    }

    /// Writes another shader's value into the output argument when it is of the variable's
    /// kind (float, triple, matrix, string, array): 1, else 0.
    fn answer_message(
        &mut self,
        found: Option<Value>,
        current: &Value,
        target: &Expr,
        mask: &Mask,
    ) -> Value {
        match found {
            Some(v) if std::mem::discriminant(&v) == std::mem::discriminant(current) => {
                self.write_back(target, &v, mask);
                Value::float(1.0)
            }
            _ => Value::float(0.0),
        }
    }

    /// Writes a queried value into the output argument when it fits the variable's type
    /// (float, triple, matrix, string, float array of the same length): 1, else 0 and the
    /// variable keeps its value (RI 3.2 §15.7).
    fn answer_query(
        &mut self,
        found: Option<illume_shade::InfoValue>,
        current: &Value,
        target: &Expr,
        mask: &Mask,
    ) -> Value {
        use illume_shade::InfoValue;
        let v = match (found, current) {
            (Some(InfoValue::String(s)), Value::String(_)) => Some(Value::string(&s)),
            (Some(InfoValue::Floats(f)), Value::Float(_)) if f.len() == 1 => {
                Some(Value::float(f[0]))
            }
            (Some(InfoValue::Floats(f)), Value::Triple(_)) if f.len() == 3 => {
                Some(Value::triple(Vec3::new(f[0], f[1], f[2])))
            }
            (Some(InfoValue::Floats(f)), Value::Matrix(_)) if f.len() == 16 => {
                let mut m = [0.0f64; 16];
                for (k, x) in f.iter().enumerate() {
                    m[k] = f64::from(*x);
                }
                Some(Value::Matrix(Slot::Uniform(geometric::matrix_from_rows(m))))
            }
            (Some(InfoValue::Floats(f)), Value::Array(e))
                if e.len() == f.len() && e.iter().all(|x| matches!(x, Value::Float(_))) =>
            {
                Some(Value::Array(f.iter().map(|&x| Value::float(x)).collect()))
            }
            _ => None,
        };
        match v {
            Some(v) => {
                self.write_back(target, &v, mask);
                Value::float(1.0)
            }
            None => Value::float(0.0),
        }
    }
}
