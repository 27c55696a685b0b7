//! Frames in file order (issue 7): each frame renders the moment its `FrameEnd` (or the
//! `WorldEnd` of a frameless file) is read, before the next request runs, so a `MakeTexture`,
//! `MakeShadow`, `MakeCubeFaceEnvironment` or `MakeLatLongEnvironment` between frames sees the
//! files earlier frames wrote. That is what lets one multi-frame RIB hold a whole multipass
//! pipeline (depth pass, `MakeShadow`, beauty pass), as PRMan and Aqsis allow.
//!
//! This lives in `illume-render` because the driver knows both halves of the loop:
//! the RI state machine that produces frames and the hider that turns them into images. `render`
//! and the integration tests call it, so the order the tests check is the order users get.
use illume_ri::{from_rib_diagnostic, Diagnostic, Frame, Ri, TextureMaker};
use illume_rib::{Request, Spanned};

/// Feeds `requests` to `ri`, calling `on_frame` with each finished frame as soon as it is
/// complete (before the next request is processed) and `on_diagnostic` with every parse and RI
/// diagnostic in the order they arise. Closes blocks left open at the end of the input
/// ([`Ri::finish`]) and hands over any frame that closing completes.
pub fn render_frames_in_order<I>(
    ri: &mut Ri,
    requests: I,
    mut on_diagnostic: impl FnMut(Diagnostic),
    mut on_frame: impl FnMut(Frame),
) where
    I: IntoIterator<Item = Result<Spanned<Request>, illume_rib::Diagnostic>>,
{
    let mut hand_over = |ri: &mut Ri| {
        for d in ri.drain_diagnostics() {
            on_diagnostic(d);
        }
        for frame in ri.take_frames() {
            on_frame(frame);
        }
    };
    for item in requests {
        match item {
            Ok(req) => ri.request(req),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
        hand_over(ri);
    }
    ri.finish();
    hand_over(ri);
}

/// The `Make*` builder `render` plugs into [`Ri::set_texture_maker`]: `illume-texture` builds
/// the file; its warnings (e.g. a deprecated `MakeBump`) go to `on_warning` with the request's
/// name, errors become the request's RI error.
pub fn texture_maker(mut on_warning: impl FnMut(&str, String) + 'static) -> TextureMaker {
    Box::new(move |req, options| {
        let req = &inputs_on_searchpath(req, &options.texture_path);
        let warnings = illume_texture::make_from_request(req).map_err(|e| e.to_string())?;
        for w in warnings {
            on_warning(req.name(), w);
        }
        Ok(())
    })
}

/// A `Make*` request whose input pictures are found on `Option "searchpath" "texture"` (as
/// Aqsis does; real scenes keep their source images in a shared `maps` folder). Inputs that are
/// not on the path stay as written, relative to the working directory.
fn inputs_on_searchpath(req: &Request, texture_path: &[String]) -> Request {
    let find = |name: &String| illume_core::searchpath::resolve(name, texture_path);
    let mut req = req.clone();
    match &mut req {
        Request::MakeTexture { picture, .. }
        | Request::MakeBump { picture, .. }
        | Request::MakeLatLongEnvironment { picture, .. }
        | Request::MakeShadow { picture, .. } => *picture = find(picture),
        Request::MakeCubeFaceEnvironment { faces, .. } => {
            for face in faces.iter_mut() {
                *face = find(face);
            }
        }
        _ => {}
    }
    req
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(rib: &str) -> illume_rib::Parser<std::io::Cursor<Vec<u8>>> {
        illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "t.rib")
    }

    #[test]
    fn each_frame_is_handed_over_before_the_next_request_runs() {
        // The texture maker records how many frames were handed over when MakeTexture ran: the
        // first frame must already be out, the second not yet.
        let frames_seen = std::rc::Rc::new(std::cell::Cell::new(0usize));
        let at_make = std::rc::Rc::new(std::cell::Cell::new(usize::MAX));
        let mut ri = Ri::new();
        let (seen, at) = (frames_seen.clone(), at_make.clone());
        ri.set_texture_maker(Box::new(move |_req, _options| {
            at.set(seen.get());
            Ok(())
        }));
        let rib = "FrameBegin 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n\
                   MakeTexture \"a.tif\" \"a.tx\" \"periodic\" \"periodic\" \"box\" 1 1\n\
                   FrameBegin 2\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
        let mut numbers = Vec::new();
        render_frames_in_order(
            &mut ri,
            parse(rib),
            |d| panic!("unexpected diagnostic {d}"),
            |f| {
                numbers.push(f.number);
                frames_seen.set(frames_seen.get() + 1);
            },
        );
        assert_eq!(numbers, vec![Some(1), Some(2)]);
        assert_eq!(at_make.get(), 1);
    }

    #[test]
    fn a_truncated_file_still_hands_over_its_frame_and_reports_the_open_block() {
        let mut ri = Ri::new();
        let mut errors = 0;
        let mut frames = 0;
        render_frames_in_order(
            &mut ri,
            parse("WorldBegin\nSphere 1 -1 1 360\n"),
            |d| errors += usize::from(d.severity == illume_ri::Severity::Error),
            |_| frames += 1,
        );
        assert_eq!((frames, errors), (1, 1));
    }
}
