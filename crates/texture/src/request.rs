//! The RIB texture-making requests (RI Spec 3.2 §8: `MakeTexture`, `MakeBump`,
//! `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment`, `MakeShadow`) carried out with the same
//! builders as `txmake`, so a multi-frame RIB and a shell script of `txmake` calls make the same
//! files.
use crate::build::{
    make_cube_face_environment, make_latlong_environment, make_shadow, make_texture, MakeOptions,
};
use crate::filter::FilterKind;
use crate::wrapmode::WrapMode;
use crate::TextureError;
use illume_imageio::{read_image, read_zfile, Image, ImageError};
use illume_rib::Request;
use std::path::Path;

fn read(path: &str) -> Result<Image, TextureError> {
    read_image(Path::new(path)).map_err(|e| image_error(path, e))
}

fn image_error(path: &str, e: ImageError) -> TextureError {
    match e {
        ImageError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            TextureError::Missing {
                path: path.to_string(),
            }
        }
        ImageError::Io { path, source } => TextureError::Io { path, source },
        other => TextureError::Format {
            path: path.to_string(),
            message: other.to_string(),
        },
    }
}

/// Filter and widths as the request names them; an unknown filter name falls back to the
/// request's default (box) with a warning rather than failing the whole request.
fn options(filter: &str, swidth: f32, twidth: f32, warnings: &mut Vec<String>) -> MakeOptions {
    let filter = match FilterKind::parse(filter) {
        Some(f) => f,
        None => {
            warnings.push(format!("unknown filter \"{filter}\", using \"box\""));
            FilterKind::Box
        }
    };
    let width = |w: f32| (w.is_finite() && w > 0.0).then_some(w);
    MakeOptions {
        filter,
        swidth: width(swidth),
        twidth: width(twidth),
        ..MakeOptions::default()
    }
}

fn wrap(word: &str, warnings: &mut Vec<String>) -> WrapMode {
    WrapMode::parse(word).unwrap_or_else(|| {
        warnings.push(format!("unknown wrap mode \"{word}\", using \"black\""));
        WrapMode::Black
    })
}

/// Carries out one Make* request, returning its warnings. Any other request is a caller bug and
/// returns `Ok` with a warning. Relative paths are relative to the working directory, as in
/// PRMan. The output is written under a temporary name and renamed, so `MakeShadow "x" "x"`
/// (output named like the input) works: the input is read whole first.
pub fn make_from_request(request: &Request) -> Result<Vec<String>, TextureError> {
    let mut warnings = Vec::new();
    match request {
        Request::MakeTexture {
            picture,
            texture,
            swrap,
            twrap,
            filter,
            swidth,
            twidth,
            ..
        }
        | Request::MakeBump {
            picture,
            texture,
            swrap,
            twrap,
            filter,
            swidth,
            twidth,
            ..
        } => {
            if matches!(request, Request::MakeBump { .. }) {
                warnings.push("MakeBump is deprecated: making a plain texture instead".to_string());
            }
            let mut opts = options(filter, *swidth, *twidth, &mut warnings);
            opts.wrap = [wrap(swrap, &mut warnings), wrap(twrap, &mut warnings)];
            opts.source = picture.clone();
            make_texture(&read(picture)?, Path::new(texture), &opts)?;
        }
        Request::MakeLatLongEnvironment {
            picture,
            texture,
            filter,
            swidth,
            twidth,
            ..
        } => {
            let mut opts = options(filter, *swidth, *twidth, &mut warnings);
            opts.source = picture.clone();
            make_latlong_environment(&read(picture)?, Path::new(texture), &opts)?;
        }
        Request::MakeCubeFaceEnvironment {
            faces,
            texture,
            fov,
            filter,
            swidth,
            twidth,
            ..
        } => {
            let mut opts = options(filter, *swidth, *twidth, &mut warnings);
            opts.fov = if fov.is_finite() && *fov >= 90.0 {
                *fov
            } else {
                90.0
            };
            opts.source = faces.join(",");
            let images = faces
                .iter()
                .map(|f| read(f))
                .collect::<Result<Vec<_>, _>>()?;
            let refs = [
                &images[0], &images[1], &images[2], &images[3], &images[4], &images[5],
            ];
            make_cube_face_environment(refs, Path::new(texture), &opts)?;
        }
        Request::MakeShadow {
            picture, texture, ..
        } => {
            let (depth, matrices) =
                read_zfile(Path::new(picture)).map_err(|e| image_error(picture, e))?;
            let opts = MakeOptions {
                source: picture.clone(),
                ..MakeOptions::default()
            };
            make_shadow(&depth, &matrices, Path::new(texture), &opts)?;
        }
        other => warnings.push(format!("{} is not a texture-making request", other.name())),
    }
    Ok(warnings)
}
