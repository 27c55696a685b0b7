#!/usr/bin/env python3
"""Writes the big scenes of issue 23 (part 4) to stdout or a file, streaming (never in memory).

    big_scenes.py spheres N [out.rib]          N unique spheres on a square grid
    big_scenes.py instances K M [out.rib]      K instances of an object of M spheres (K*M spheres)
    big_scenes.py mesh MEGABYTES [out.rib]     PointsPolygons meshes until the file has MEGABYTES

Every scene is one 1024x1024 frame seen from above (orthographic), the spheres tiny (about a
pixel each at 10^6), so the render is dominated by the per-primitive costs the measurements are
about. The generated files are not committed: the README's "Big scenes" paragraph gives the
commands and the numbers.
"""
import math
import sys

HEADER = """##RenderMan RIB
version 3.03
Option "limits" "vertices" [100000000]
Format 1024 1024 1
PixelSamples 2 2
ShadingRate 1
Display "{name}" "file" "rgba"
Projection "orthographic"
ScreenWindow -1 1 -1 1
Translate 0 0 10
WorldBegin
LightSource "distantlight" 1 "from" [0 0 -1] "to" [0 0 0]
Surface "matte"
"""


def header(out, name):
    out.write(HEADER.format(name=name))


def grid(n):
    """Side of the smallest square grid with n cells, and the cell size on a [-1, 1] square."""
    side = max(1, math.isqrt(n - 1) + 1)
    return side, 2.0 / side


def spheres(out, n):
    header(out, "big_spheres.tif")
    side, cell = grid(n)
    r = cell * 0.45
    for i in range(n):
        x = -1 + (i % side + 0.5) * cell
        y = -1 + (i // side + 0.5) * cell
        out.write(f"TransformBegin Translate {x:.6g} {y:.6g} 0 "
                  f"Sphere {r:.6g} {-r:.6g} {r:.6g} 360 TransformEnd\n")
    out.write("WorldEnd\n")


def instances(out, k, m):
    header(out, "big_instances.tif")
    # The object: m spheres on a grid filling [-0.5, 0.5]^2 of its own space.
    side, cell = grid(m)
    r = cell * 0.45
    out.write("ObjectBegin 1\n")
    for i in range(m):
        x = -1 + (i % side + 0.5) * cell
        y = -1 + (i // side + 0.5) * cell
        out.write(f"TransformBegin Translate {x / 2:.6g} {y / 2:.6g} 0 "
                  f"Sphere {r / 2:.6g} {-r / 2:.6g} {r / 2:.6g} 360 TransformEnd\n")
    out.write("ObjectEnd\n")
    kside, kcell = grid(k)
    for i in range(k):
        x = -1 + (i % kside + 0.5) * kcell
        y = -1 + (i // kside + 0.5) * kcell
        out.write(f"TransformBegin Translate {x:.6g} {y:.6g} 0 Scale {kcell:.6g} {kcell:.6g} {kcell:.6g} "
                  "ObjectInstance 1 TransformEnd\n")
    out.write("WorldEnd\n")


def mesh(out, megabytes):
    """32x32-quad PointsPolygons with per-vertex Cs, tiled over the image until the size."""
    header(out, "big_mesh.tif")
    q = 32
    verts = " ".join(f"{j * (q + 1) + i} {j * (q + 1) + i + 1} {(j + 1) * (q + 1) + i + 1} {(j + 1) * (q + 1) + i}"
                     for j in range(q) for i in range(q))
    nverts = " ".join("4" for _ in range(q * q))
    limit = megabytes << 20
    written = 0
    k = 0
    while written < limit:
        # Meshes are laid on a 64x64 tiling of the screen, later ones over earlier ones.
        tx = -1 + (k % 64) / 32
        ty = -1 + (k // 64 % 64) / 32
        z = (k // 4096) * 0.001
        p = []
        cs = []
        for j in range(q + 1):
            for i in range(q + 1):
                x = tx + i / q / 32
                y = ty + j / q / 32
                p.append(f"{x:.6f} {y:.6f} {z + 0.01 * math.sin(7 * x + 5 * y):.6f}")
                cs.append(f"{(i / q):.4f} {(j / q):.4f} {((k % 17) / 16):.4f}")
        line = (f"PointsPolygons [{nverts}] [{verts}] \"P\" [{' '.join(p)}] "
                f"\"Cs\" [{' '.join(cs)}]\n")
        out.write(line)
        written += len(line)
        k += 1
    out.write("WorldEnd\n")


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    kind = argv[0]
    try:
        numbers = [int(float(a)) for a in argv[1:3] if not a.endswith(".rib")]
    except ValueError:
        sys.exit(__doc__)
    path = next((a for a in argv[1:] if a.endswith(".rib")), None)
    out = open(path, "w", buffering=1 << 20) if path else sys.stdout
    with out:
        if kind == "spheres" and len(numbers) == 1:
            spheres(out, numbers[0])
        elif kind == "instances" and len(numbers) == 2:
            instances(out, numbers[0], numbers[1])
        elif kind == "mesh" and len(numbers) == 1:
            mesh(out, numbers[0])
        else:
            sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
