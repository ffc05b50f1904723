"""Blender reads rootsim's glTF (ctest gltf_blender, through consumers.py).

Run by Blender itself: blender -b --factory-startup --python-exit-code 1 --python blender_check.py --
FILE.glb OUT.png FRAMES. Checks that Blender's own glTF importer reads the file; that it made one object
per snapshot ("frame NNNN, ...") plus the plate, the grid and the top camera, with the materials
"root body", "stripe +d1" and "stripe -d1"; that the animation's keys span frames 0 .. FRAMES - 1 (24
snapshots a second, Blender's default rate) and show exactly one snapshot at each frame; then renders
the last frame with Cycles (CPU, 8 samples) through the file's top camera, narrowed to the root, and
checks that the picture is not blank and that it shows pink where the +d1 faces turn towards the camera
and orange where the -d1 faces do. Any failure raises, and Blender exits 1.
"""
import sys

import bpy
import numpy as np

if not hasattr(np, "bool"):
    np.bool = bool  # Debian's numpy dropped the alias that Blender 3.4's glTF importer still uses

from bpy_extras.object_utils import world_to_camera_view  # noqa: E402
from mathutils import Vector  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
glb, out_png, frames = args[0], args[1], int(args[2])


def fail(msg):
    raise RuntimeError("FAIL: " + msg)


# an empty scene (no default cube, light or camera), then the file
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
result = bpy.ops.import_scene.gltf(filepath=glb)
if result != {"FINISHED"}:
    fail("the importer returned %s" % result)

objs = bpy.data.objects
frame_objs = sorted((o for o in objs if o.name.startswith("frame ")), key=lambda o: o.name)
print("imported %d objects, %d snapshot objects, %d meshes, %d materials" %
      (len(objs), len(frame_objs), len(bpy.data.meshes), len(bpy.data.materials)))
if len(frame_objs) != frames:
    fail("%d snapshot objects, expected %d" % (len(frame_objs), frames))
for name in ("plate", "grid", "top view", "root"):
    if name not in objs:
        fail("no object %r among %s" % (name, sorted(objs.keys())))
for name in ("root body", "stripe +d1", "stripe -d1", "plate"):
    if name not in bpy.data.materials:
        fail("no material %r" % name)
camera = objs["top view"]
if camera.type != "CAMERA" or camera.data.type != "ORTHO":
    fail("'top view' is not an orthographic camera")

# the animation: every snapshot object keyed on its scale, keys from frame 0 to frames - 1
lo, hi = float("inf"), float("-inf")
for o in frame_objs:
    action = o.animation_data.action if o.animation_data else None
    if action is None:
        fail(o.name + " has no action")
    a, b = action.frame_range
    lo, hi = min(lo, a), max(hi, b)
print("animation keys span frames %g .. %g" % (lo, hi))
if frames > 1 and (abs(lo) > 1e-6 or abs(hi - (frames - 1)) > 1e-6):
    fail("the keys span %g .. %g, expected 0 .. %d" % (lo, hi, frames - 1))
for f in sorted({0, frames // 2, frames - 1}):
    scene.frame_set(f)
    shown = [o.name for o in frame_objs if o.matrix_world.to_scale().length > 1e-9]
    if shown != [frame_objs[f].name]:
        fail("at frame %d the snapshots shown are %s, expected %s" % (f, shown, frame_objs[f].name))

# the render: the last snapshot through the top camera, narrowed to it so the stripes get pixels
last = frame_objs[-1]
scene.frame_set(frames - 1)
corners = [last.matrix_world @ Vector(c) for c in last.bound_box]
xs, ys = [c.x for c in corners], [c.y for c in corners]
margin = 0.3e-3  # [m]
cx, cy = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
w, h = max(xs) - min(xs) + 2 * margin, max(ys) - min(ys) + 2 * margin
camera.location.x, camera.location.y = cx, cy
camera.data.ortho_scale = max(w, h)
long_side = 480
scene.render.resolution_x = max(16, round(long_side * min(1.0, w / h)))
scene.render.resolution_y = max(16, round(long_side * min(1.0, h / w)))
scene.render.resolution_percentage = 100
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3.0
sun.rotation_euler = (0.35, -0.25, 0.0)  # from above, a little off the camera's axis
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.color = (0.3, 0.3, 0.3)
scene.world = world
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.view_settings.view_transform = "Standard"  # the materials' colours as rootsim's pictures show them
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = out_png
bpy.ops.render.render(write_still=True)

img = bpy.data.images.load(out_png)
W, H = img.size
px = np.array(img.pixels[:], dtype=np.float32).reshape(H, W, 4)[::-1, :, :3]  # rows from the top
lum = px.mean(axis=2)
print("render %dx%d: luminance min %.3f max %.3f std %.3f" % (W, H, lum.min(), lum.max(), lum.std()))
if lum.std() < 0.02 or lum.max() - lum.min() < 0.2:
    fail("the render is blank")
r, g, b = px[..., 0], px[..., 1], px[..., 2]
pink = (r > g + 0.25) & (b > g + 0.08) & (r > b)
orange = (r > b + 0.35) & (g > b + 0.12) & (r > g + 0.1)

# where the stripes face the camera: the pixels of the last snapshot's +d1 / -d1 faces whose normals
# point up (towards the camera: the tube is convex)
depsgraph = bpy.context.evaluated_depsgraph_get()
mesh = last.evaluated_get(depsgraph).to_mesh()
normal_matrix = last.matrix_world.to_3x3().inverted().transposed()
expect = {name: np.zeros((H, W), dtype=bool) for name in ("stripe +d1", "stripe -d1")}
for poly in mesh.polygons:
    name = last.material_slots[poly.material_index].material.name if last.material_slots else ""
    if name not in expect or (normal_matrix @ poly.normal).normalized().z <= 0.0:
        continue
    # the face's box in pixels (faces are a few pixels long), widened by 2 px
    ps = [world_to_camera_view(scene, camera, last.matrix_world @ mesh.vertices[vi].co) for vi in poly.vertices]
    i0, i1 = int((1 - max(p.y for p in ps)) * H) - 2, int((1 - min(p.y for p in ps)) * H) + 3
    j0, j1 = int(min(p.x for p in ps) * W) - 2, int(max(p.x for p in ps) * W) + 3
    expect[name][max(0, i0):max(0, i1), max(0, j0):max(0, j1)] = True
for name, found in (("stripe +d1", pink), ("stripe -d1", orange)):
    n, inside = int(found.sum()), int((found & expect[name]).sum())
    print("%s: %d pixels of its colour, %d of them where its faces turn to the camera (%d such pixels)" %
          (name, n, inside, int(expect[name].sum())))
    if expect[name].sum() == 0:
        fail("no %s face turns towards the camera in this run: the check needs one" % name)
    if n < 20:
        fail("the render shows %d pixels of %s's colour" % (n, name))
    if inside < 0.9 * n:
        fail("%s's colour appears away from its faces (%d of %d pixels inside)" % (name, inside, n))
print("blender check passed")
