"""The Python module against the RIB path: same scene through Ri() and through RIB text."""
import os
import subprocess

import numpy as np
import pytest

import illume

SCENE_RIB = """Format 48 32 1
PixelSamples 2 2
Display "py.tif" "file" "rgba"
Projection "perspective" "fov" [40.0]
Translate 0 0 5
WorldBegin
LightSource "distantlight" 1 "intensity" [1.2]
Surface "plastic" "Ks" [0.5] "uniform float roughness" [0.1]
Color [1 0.3 0.2]
Sphere 1 -1 1 360
Polygon "P" [-2.0 -1.0 1.0 2.0 -1.0 1.0 2.0 -1.0 -1.0 -2.0 -1.0 -1.0] "N" [0.0 1.0 0.0 0.0 1.0 0.0 0.0 1.0 0.0 0.0 1.0 0.0]
WorldEnd
"""


def scene(ri):
    ri.Format(48, 32, 1)
    ri.PixelSamples(2, 2)
    ri.Display("py.tif", "file", "rgba")
    ri.Projection("perspective", {"fov": 40.0})
    ri.Translate(0, 0, 5)
    ri.WorldBegin()
    light = ri.LightSource("distantlight", {"intensity": 1.2})
    assert light == 1
    ri.Surface("plastic", {"Ks": 0.5, "uniform float roughness": 0.1})
    ri.Color([1.0, 0.3, 0.2])
    ri.Sphere(1, -1, 1, 360)
    p = np.array([[-2, -1, 1], [2, -1, 1], [2, -1, -1], [-2, -1, -1]], dtype=np.float32)
    n = np.tile(np.array([0, 1, 0], dtype=np.float32), (4, 1))
    ri.Polygon(4, {"P": p, "N": n})
    ri.WorldEnd()


def test_rib_output_is_the_canonical_form_of_the_calls(tmp_path):
    ri = illume.Ri()
    out = tmp_path / "py.rib"
    ri.Begin(str(out))
    scene(ri)
    ri.End()
    assert out.read_text() == "##RenderMan RIB\n" + SCENE_RIB
    assert ri.errors == []


def test_in_process_render_equals_render_of_the_rib(tmp_path):
    os.chdir(tmp_path)
    ri = illume.Ri()
    ri.Begin("__render")
    scene(ri)
    ri.End()
    written = (tmp_path / "py.tif").read_bytes()
    assert len(written) > 1000
    image = illume.render(SCENE_RIB)
    assert image.shape == (32, 48, 4) and image.dtype == np.float32
    # The sphere covers the centre: opaque and lit.
    assert image[16, 24, 3] == pytest.approx(1.0)
    assert image[16, 24, 0] > 0.2
    # Rendering the same RIB twice gives the same bits (determinism).
    assert np.array_equal(image, illume.render(SCENE_RIB))
    # The Ri() path's file is bit-identical to `render`'s file for the same RIB.
    (tmp_path / "py.tif").unlink()
    illume.render(SCENE_RIB)  # framebuffer only: writes no display
    assert not (tmp_path / "py.tif").exists()
    (tmp_path / "scene.rib").write_text(SCENE_RIB)
    subprocess.run([os.environ["RENDER"], "-q", "scene.rib"], check=True)
    assert (tmp_path / "py.tif").read_bytes() == written


def test_bad_calls_reach_the_error_handler():
    seen = []
    ri = illume.Ri()
    ri.ErrorHandler(lambda code, severity, msg: seen.append((code, severity)))
    ri.End()  # before Begin: RIE_NOTSTARTED
    ri.Begin("__render")
    ri.Sphere(1, -1, 1, 360)  # outside WorldBegin: RIE_NOTPRIMS
    ri.WorldBegin()
    ri.Surface("plastic", {"nosuch": 1.0})  # undeclared: RIE_BADTOKEN
    ri.WorldEnd()
    ri.End()
    assert seen[:3] == [(23, 2), (27, 2), (41, 2)]
