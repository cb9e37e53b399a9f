# Blender's cloth on the scene of bench/inextensibility_sweep.cpp: a 1 m x 1 m sheet of n x n
# vertices, flat at z = 1.6 m, held by its two corners at v = 1, falling and swinging for
# `frames` frames at 24 fps. Run by bench/cloth_vs_blender.py; by hand:
#
#   blender -b --factory-startup -t 1 --python bench/blender_cloth_hang.py -- N FRAMES QUALITY \
#       [--self-collision DISTANCE_M] [--wool-mass]
#
# Prints one line: "weft-bench n=N frames=F quality=Q vertices=V cpu_s=... cpu_ms_per_frame=...
# lowest_z=... max_strain=..." where cpu_s is the process CPU time (all threads) of baking the
# frames (the point cache's bake, from the first frame to the last, the scene set-up left out),
# per frame over the frames - 1 steps; lowest_z (m) and max_strain (the longest warp/weft edge
# over its rest length, minus 1) describe the last frame.
#
# Blender's cloth settings are its defaults (0.3 kg per vertex, air damping 1, stiffness 15)
# except quality (solver steps per frame): what a user gets, and how the issue that asked for
# this comparison measured it. Blender's stiffnesses are not in weft's units, so its sheet
# stretches far more than weft's 1 % (max_strain says how much). --wool-mass gives Blender
# weft's wool instead, 0.19 kg/m^2 spread evenly over the vertices, with weft's air damping of
# 1/s (Blender's drag force is -0.01 * air_damping * v per vertex, not proportional to the
# mass: air_damping = 100 m per vertex gives the same deceleration). With --self-collision,
# self-collision at that distance (m).
import sys
import time

import bpy


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) < 3:
        raise SystemExit("usage: ... -- N FRAMES QUALITY [--self-collision DISTANCE_M] "
                         "[--wool-mass]")
    n, frames, quality = int(argv[0]), int(argv[1]), int(argv[2])
    self_distance = None
    if "--self-collision" in argv:
        self_distance = float(argv[argv.index("--self-collision") + 1])
    return n, frames, quality, self_distance, "--wool-mass" in argv


def make_sheet(n):
    # Vertex (i, j) at index j*n + i, at (-0.5 + i/(n-1), -0.5 + j/(n-1), 1.6): weft's grid.
    step = 1.0 / (n - 1)
    vertices = [(-0.5 + i * step, -0.5 + j * step, 1.6) for j in range(n) for i in range(n)]
    faces = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i)
             for j in range(n - 1) for i in range(n - 1)]
    mesh = bpy.data.meshes.new("sheet")
    mesh.from_pydata(vertices, [], faces)
    mesh.update()
    sheet = bpy.data.objects.new("sheet", mesh)
    bpy.context.scene.collection.objects.link(sheet)
    pins = sheet.vertex_groups.new(name="pins")
    pins.add([(n - 1) * n, n * n - 1], 1.0, "REPLACE")  # corners u0v1 and u1v1
    return sheet


def main():
    n, frames, quality, self_distance, wool_mass = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 24
    scene.frame_start = 1
    scene.frame_end = frames
    sheet = make_sheet(n)
    cloth = sheet.modifiers.new("cloth", "CLOTH")
    cloth.settings.quality = quality
    if wool_mass:
        vertex_mass_kg = 0.19 * 1.0 / (n * n)
        cloth.settings.mass = vertex_mass_kg
        cloth.settings.air_damping = 100.0 * vertex_mass_kg
    cloth.settings.vertex_group_mass = "pins"
    cloth.point_cache.frame_start = 1
    cloth.point_cache.frame_end = frames
    cloth.collision_settings.use_collision = False
    if self_distance is not None:
        cloth.collision_settings.use_self_collision = True
        cloth.collision_settings.self_distance_min = self_distance
    scene.frame_set(1)
    start = time.process_time()
    with bpy.context.temp_override(scene=scene, active_object=sheet, point_cache=cloth.point_cache):
        bpy.ops.ptcache.bake(bake=True)
    cpu_s = time.process_time() - start
    # The last frame's lowest point and longest warp/weft edge, to see that the sheet fell and
    # how far Blender's springs let it stretch.
    scene.frame_set(frames)
    evaluated = sheet.evaluated_get(bpy.context.evaluated_depsgraph_get()).data.vertices
    lowest = min(v.co.z for v in evaluated)
    rest = 1.0 / (n - 1)
    stretch = max((evaluated[j * n + i].co - evaluated[j * n + i + d].co).length / rest - 1.0
                  for j in range(n - 1) for i in range(n - 1) for d in (1, n))
    print("weft-bench n=%d frames=%d quality=%d vertices=%d cpu_s=%.3f cpu_ms_per_frame=%.2f "
          "lowest_z=%.3f max_strain=%.3f"
          % (n, frames, quality, len(sheet.data.vertices), cpu_s, 1e3 * cpu_s / max(1, frames - 1),
             lowest, stretch))


main()
