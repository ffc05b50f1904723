"""Blender reads a plate's glTF (ctest gltf_plate_blender, through consumers.py; docs/gltf.md, A plate's run).

Run by Blender itself: blender -b --factory-startup --python-exit-code 1 --python blender_plate_check.py --
FILE.glb OUT.png ROOTS FRAMES, ROOTS the plate's root names joined by commas (roots/ of the run). Checks
that Blender's glTF importer reads the file; that every root is a group object of its name holding its
snapshot objects "NAME frame NNNN, ..."; that at frames 0, the middle and the last every root whose first
snapshot is at or before the frame shows exactly that frame's snapshot and no other; then renders the last
frame with Cycles through the file's top camera, narrowed to the first root, and checks that the picture
is not blank and shows both stripes' colours. Any failure raises, and Blender exits 1.
"""
import sys

import bpy
import numpy as np

if not hasattr(np, "bool"):
    np.bool = bool  # Debian's numpy dropped the alias that Blender 3.4's glTF importer still uses

from mathutils import Vector  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
glb, out_png, roots, frames = args[0], args[1], args[2].split(","), int(args[3])


def fail(msg):
    raise RuntimeError("FAIL: " + msg)


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
if bpy.ops.import_scene.gltf(filepath=glb) != {"FINISHED"}:
    fail("the importer failed")
objs = bpy.data.objects
for name in ("plate", "grid", "top view"):
    if name not in objs:
        fail("no object %r" % name)
snapshots = {}
for name in roots:
    if name not in objs:
        fail("no group object %r among %s" % (name, sorted(objs.keys())))
    kids = sorted((o for o in objs[name].children if o.name.startswith(name + " frame ")), key=lambda o: o.name)
    if not kids:
        fail("group %r holds no snapshot objects" % name)
    snapshots[name] = kids
print("imported %d objects: %d roots, %d snapshot objects" % (len(objs), len(roots), sum(len(v) for v in snapshots.values())))


def frame_of(o):
    return int(o.name.split(" frame ")[1][:4])


for f in sorted({0, frames // 2, frames - 1}):
    scene.frame_set(f)
    for name, kids in snapshots.items():
        shown = [o.name for o in kids if o.matrix_world.to_scale().length > 1e-9]
        want = [o.name for o in kids if frame_of(o) == f]
        if shown != want:
            fail("at frame %d root %s shows %s, expected %s" % (f, name, shown, want))
print("the animation shows one snapshot per emerged root at frames 0, %d and %d" % (frames // 2, frames - 1))

# the last frame through the top camera, narrowed to the first root's last snapshot (the plate's roots
# are a pixel wide in a picture of the whole plate; every root's presence is checked above)
scene.frame_set(frames - 1)
last = snapshots[roots[0]][-1]
corners = [last.matrix_world @ Vector(c) for c in last.bound_box]
xs, ys = [c.x for c in corners], [c.y for c in corners]
camera = objs["top view"]
margin = 0.3e-3  # [m]
camera.location.x, camera.location.y = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
w, h = max(xs) - min(xs) + 2 * margin, max(ys) - min(ys) + 2 * margin
camera.data.ortho_scale = max(w, h)
scene.render.resolution_x = max(16, round(480 * min(1.0, w / h)))
scene.render.resolution_y = max(16, round(480 * min(1.0, h / w)))
scene.render.resolution_percentage = 100
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3.0
sun.rotation_euler = (0.35, -0.25, 0.0)
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.color = (0.3, 0.3, 0.3)
scene.world = world
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = out_png
bpy.ops.render.render(write_still=True)
img = bpy.data.images.load(out_png)
W, H = img.size
px = np.array(img.pixels[:], dtype=np.float32).reshape(H, W, 4)[::-1, :, :3]
lum = px.mean(axis=2)
print("render %dx%d: luminance min %.3f max %.3f std %.3f" % (W, H, lum.min(), lum.max(), lum.std()))
if lum.std() < 0.02 or lum.max() - lum.min() < 0.2:
    fail("the render is blank")
r, g, b = px[..., 0], px[..., 1], px[..., 2]
pink = int(((r > g + 0.25) & (b > g + 0.08) & (r > b)).sum())
orange = int(((r > b + 0.35) & (g > b + 0.12) & (r > g + 0.1)).sum())
print("pink (+d1) pixels %d, orange (-d1) pixels %d" % (pink, orange))
if pink < 20 or orange < 20:
    fail("the stripes do not show (pink %d, orange %d pixels)" % (pink, orange))
print("blender plate check passed")
