//! The `Declare` table, seeded with the variables RI Spec 3.2 predeclares (§ "Primitive
//! variables" and the standard shaders' and options' parameters), so parameter lists that use
//! bare names (`"Kd"`, `"from"`, `"bucketsize"`) resolve without a `Declare`.
use illume_rib::Declaration;
use std::collections::HashMap;

const PREDECLARED: &[(&str, &str)] = &[
    ("P", "vertex point"),
    ("Pz", "vertex float"),
    ("Pw", "vertex hpoint"),
    ("N", "varying normal"),
    ("Np", "uniform normal"),
    ("Cs", "varying color"),
    ("Os", "varying color"),
    ("s", "varying float"),
    ("t", "varying float"),
    ("st", "varying float[2]"),
    ("width", "varying float"),
    ("constantwidth", "constant float"),
    // standard shader parameters
    ("Ka", "uniform float"),
    ("Kd", "uniform float"),
    ("Ks", "uniform float"),
    ("Kr", "uniform float"),
    ("roughness", "uniform float"),
    ("specularcolor", "uniform color"),
    ("intensity", "uniform float"),
    ("lightcolor", "uniform color"),
    ("from", "uniform point"),
    ("to", "uniform point"),
    ("coneangle", "uniform float"),
    ("conedeltaangle", "uniform float"),
    ("beamdistribution", "uniform float"),
    ("texturename", "uniform string"),
    ("mindistance", "uniform float"),
    ("maxdistance", "uniform float"),
    ("background", "uniform color"),
    ("distance", "uniform float"),
    ("amplitude", "uniform float"),
    ("fov", "uniform float"),
    // options and attributes
    ("bucketsize", "uniform integer[2]"),
    ("gridsize", "uniform integer"),
    ("eyesplits", "uniform integer"),
    ("texturememory", "uniform integer"),
    ("shader", "uniform string"),
    ("texture", "uniform string"),
    ("archive", "uniform string"),
    ("resource", "uniform string"),
    ("procedural", "uniform string"),
    ("display", "uniform string"),
    ("jitter", "uniform integer"),
    ("depthfilter", "uniform string"),
    ("name", "uniform string"),
    ("sphere", "uniform float"),
    ("coordinatesystem", "uniform string"),
    ("binary", "uniform integer"),
    ("bias", "uniform float"),
    ("bias0", "uniform float"),
    ("bias1", "uniform float"),
    ("origin", "uniform integer[2]"),
];

#[derive(Clone, Debug)]
pub struct Declarations {
    table: HashMap<String, Declaration>,
}

impl Default for Declarations {
    fn default() -> Self {
        let table = PREDECLARED
            .iter()
            .map(|(name, decl)| {
                let d = Declaration::parse(decl).expect("predeclared types parse");
                (name.to_string(), d)
            })
            .collect();
        Declarations { table }
    }
}

impl Declarations {
    pub fn get(&self, name: &str) -> Option<Declaration> {
        self.table.get(name).cloned()
    }

    pub fn declare(&mut self, name: &str, declaration: Declaration) {
        self.table.insert(name.to_string(), declaration);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_rib::{Class, Type};

    #[test]
    fn st_is_predeclared_as_two_varying_floats() {
        let d = Declarations::default().get("st").unwrap();
        assert_eq!(
            (d.class, d.ty, d.array_len),
            (Class::Varying, Type::Float, 2)
        );
        assert_eq!(
            Declarations::default().get("P").unwrap().class,
            Class::Vertex
        );
    }
}
