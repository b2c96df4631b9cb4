#!/usr/bin/env python3
"""benchmarks/make_paths.py — writes the camera paths over the default scene
(assets/N47E009.hgt.gz, SRTM 3", 1201 x 1201, lon 9-10 E, lat 47-48 N) into assets/:
  default-path.cam  the default camera (platform/scene.c scene_default_view, 60 deg)
                    moving 20 m a frame towards its target, 300 frames;
  lake-path.cam     55 m over Lake Constance (surface 395 m), from off Meersburg
                    towards Lindau, 20 m a frame, 300 frames;
  alps-path.cam     over the Alpstein (Saentis, 2502 m) 400 m above the highest
                    ground within 1 km ahead, 20 m a frame, 300 frames;
and two over ../shared/data/dem/hgt/N50E008.hgt (the Taunus, 62 .. 885 m) into
benchmarks/, for comparing one tile with the merged N50E008-N50E010 (3601 x 1201: its
west third is N50E008, so the same positions fly over the same ground):
  n50-steep.cam     3000 m up, 47 degrees down to the east-north-east (all the ground
                    in view lies inside N50E008), 20 m a frame, 300 frames;
  n50-horizon.cam   the same, 5 degrees down (the horizon in view: the merged tiles
                    show three times the ground of one tile).
Positions in the scene's frame (x east from the west edge, y north from the south
edge, metres).  Usage: python3 benchmarks/make_paths.py (from the repository root)."""
import gzip, math, struct

N = 1201
DX, DY = 62.786282, 92.650490          # bitrain info assets/N47E009.hgt.gz
z = struct.unpack('>%dh' % (N * N), gzip.open('assets/N47E009.hgt.gz').read())

def ground(x, y):                       # nearest sample, metres
    c = min(max(int(round(x / DX)), 0), N - 1)
    r = min(max(int(round((N - 1) - y / DY)), 0), N - 1)
    return z[r * N + c]

def xy(lon, lat):
    return (lon - 9.0) / (1 / 1200.0) * DX, (N - 1 - (48.0 - lat) / (1 / 1200.0)) * DY

def write(name, head, frames):
    with open('assets/' + name, 'w') as f:
        f.write(head)
        for e, t in frames:
            f.write('%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n' % (e + t))

W, H = (N - 1) * DX, (N - 1) * DY
zmin, zmax = min(z), max(z)
R = 0.5 * math.sqrt(W * W + H * H + (zmax - zmin) ** 2)
d = 0.75 * R / math.sin(math.radians(30)); el = math.radians(35)
tgt = (0.5 * W, 0.5 * H, 0.5 * (zmin + zmax))
eye = (tgt[0] - d * math.cos(el) * 0.7071, tgt[1] - d * math.cos(el) * 0.7071, tgt[2] + d * math.sin(el))
v = [t - e for t, e in zip(tgt, eye)]; L = math.sqrt(sum(c * c for c in v)); v = [c / L for c in v]
write('default-path.cam', '# The default camera of N47E009 moving 20 m a frame towards its target (benchmarks/make_paths.py)\n',
      [(tuple(e + 20 * i * c for e, c in zip(eye, v)), tuple(t + 20 * i * c for t, c in zip(tgt, v))) for i in range(300)])

def fly(name, head, a, b, height):
    (x0, y0), (x1, y1) = xy(*a), xy(*b)
    L = math.hypot(x1 - x0, y1 - y0); ux, uy = (x1 - x0) / L, (y1 - y0) / L
    out = []
    for i in range(300):
        x, y = x0 + 20 * i * ux, y0 + 20 * i * uy
        h = height(x, y, ux, uy)
        out.append(((x, y, h), (x + 3000 * ux, y + 3000 * uy, h - 300)))
    write(name, head, out)

fly('lake-path.cam', '# 55 m over Lake Constance, off Meersburg towards Lindau, 20 m a frame (benchmarks/make_paths.py)\n',
    (9.28, 47.69), (9.55, 47.57), lambda x, y, ux, uy: 395 + 55 + max(0, ground(x, y) - 395))
fly('alps-path.cam', '# Over the Alpstein (Saentis), 400 m above the highest ground 1 km ahead, 20 m a frame (benchmarks/make_paths.py)\n',
    (9.25, 47.26), (9.45, 47.23),
    lambda x, y, ux, uy: 400 + max(ground(x + k * ux, y + k * uy) for k in range(0, 1001, 50)))

def n50(name, head, ahead):                  # N50E008: 3" x 3" is 59.12 x 92.70 m
    w, h = 1200 * 59.124512, 1200 * 92.698903
    ux, uy = math.cos(math.radians(20)), math.sin(math.radians(20))
    e0 = (0.5 * w, 0.3 * h, 3000.0)
    out = [((e0[0] + 20 * i * ux, e0[1] + 20 * i * uy, e0[2]),
            (e0[0] + (20 * i + ahead) * ux, e0[1] + (20 * i + ahead) * uy, 300.0)) for i in range(300)]
    with open('benchmarks/' + name, 'w') as f:
        f.write(head)
        for e, t in out:
            f.write('%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n' % (e + t))

n50('n50-steep.cam', '# 3000 m over N50E008 (Taunus), 47 degrees down to the east-north-east, 20 m a frame (benchmarks/make_paths.py)\n', 2500)
n50('n50-horizon.cam', '# 3000 m over N50E008 (Taunus), 5 degrees down to the east-north-east, 20 m a frame (benchmarks/make_paths.py)\n', 30000)
