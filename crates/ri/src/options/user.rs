//! Implementation-specific options (RI Spec 3.2 §4.1.4, `Option`): the PRMan `limits`,
//! `searchpath`, `shadow` and `shading` options that real scenes rely on.
use crate::diagnostic::Diagnostics;
use crate::options::{expand_search_path, Options};
use crate::paramlist;
use illume_rib::{ParamList, Span};

impl Options {
    pub(crate) fn user_option(
        &mut self,
        name: &str,
        params: &ParamList,
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) {
        let o = self;
        for p in paramlist::names(params)
            .map(str::to_string)
            .collect::<Vec<_>>()
        {
            let f = paramlist::floats(params, &p).unwrap_or_default();
            let s = paramlist::string(params, &p);
            match (name, p.as_str()) {
                ("limits", "bucketsize") if f.len() == 2 && f[0] >= 1.0 && f[1] >= 1.0 => {
                    o.bucket_size = [f[0].min(1024.0) as u32, f[1].min(1024.0) as u32]
                }
                ("limits", "gridsize") if f.first().is_some_and(|&g| g >= 1.0) => {
                    o.grid_size = f[0] as u32
                }
                ("limits", "eyesplits") if f.first().is_some_and(|&g| g >= 0.0) => {
                    o.eye_splits = (f[0] as u32).min(32)
                }
                ("limits", "texturememory") if f.first().is_some_and(|&g| g >= 0.0) => {
                    o.texture_memory = f[0] as u32
                }
                ("limits", limit) if o.limits.set(limit, &f, span, diagnostics) => {}
                (
                    "searchpath",
                    kind @ ("shader" | "texture" | "archive" | "resource" | "procedural"),
                ) => {
                    let Some(value) = s else {
                        diagnostics.error(
                            span,
                            "Option",
                            format!("searchpath \"{kind}\" expects a string"),
                        );
                        continue;
                    };
                    let default = vec![".".to_string()];
                    let expand = |prev: &Vec<String>| expand_search_path(&value, prev, &default);
                    match kind {
                        "shader" => o.shader_path = expand(&o.shader_path),
                        "texture" => o.texture_path = expand(&o.texture_path),
                        "procedural" => o.procedural_path = expand(&o.procedural_path),
                        "archive" => o.archive_path = expand(&o.archive_path),
                        _ => {
                            // "resource" covers every kind at once.
                            o.shader_path = expand(&o.shader_path);
                            o.texture_path = expand(&o.texture_path);
                            o.archive_path = expand(&o.archive_path);
                        }
                    }
                }
                ("shadow", "bias0") if !f.is_empty() => o.shadow_bias[0] = f[0],
                ("shadow", "bias1") if !f.is_empty() => o.shadow_bias[1] = f[0],
                ("shadow", "bias") if !f.is_empty() => o.shadow_bias = [f[0], f[0]],
                ("shading", "specularmodel") if s.is_some() => {
                    o.specular_model = s.unwrap_or_default()
                }
                ("trace", "maxdepth") if !f.is_empty() => {
                    if f[0] >= 0.0 && f[0].is_finite() {
                        o.trace_max_depth = (f[0] as u32).min(64);
                    } else {
                        diagnostics.error(
                            span,
                            "Option",
                            "\"trace\" \"maxdepth\": expected a count >= 0",
                        );
                    }
                }
                (_, p) => diagnostics.warn(
                    span,
                    "Option",
                    format!("\"{name}\" \"{p}\" not supported or malformed (ignored)"),
                ),
            }
        }
    }
}
