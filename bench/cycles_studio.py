# Blender Cycles' side of docs/benchmarks.md's "Image-based lighting" table: the studio-lit
# sphere drape (assets/scenes/sphere_drape.json at rest, gallery/README.md) rendered by Cycles
# on the CPU, for the time Cycles needs for a picture as close to its own high-sample reference
# as weft's is to weft's. Blender is not one of weft's dependencies (install it only to measure:
# `apt-get install blender`, Debian 12: 3.4.1). Run:
#
#   blender -b --factory-startup -P bench/cycles_studio.py -- MESH.obj HDR OUT.png WxH SAMPLES \
#       [--denoise] [--threads N]
#
# The scene as weft draws it (render.* of sphere_drape.json): the cloth mesh weft exported
# (`weft run … --last --export-meshes obj --up z`, weft's own z-up coordinates), the sphere
# (r 25 cm at (0, 0, 0.6)) and a 10 m ground square at z = 0, Lambertian with reflectance
# colour^2.2 (front (0.80, 0.25, 0.20), back (0.25, 0.45, 0.80), sphere (0.70, 0.74, 0.80),
# ground (0.60, 0.60, 0.58)); the camera at (1.5, −1.8, 1.35) looking at (0, 0, 0.5), 30°
# vertical field of view; the map as the only light, intensity 1.5, as the background too.
# Cycles' equirectangular mapping (u = 0.5 − atan2(y, x)/2π, v from the zenith) is weft's
# (render/environment.h), so the map needs no turn. Direct light only (max_bounces 0), as weft's
# default (bounces 0); a "Standard" view transform and gamma 2.2-like sRGB output, 8-bit PNG.
# Not drawn: weft's sheen lobe and the ground's grid lines. The PNG's pixels are compared with
# Cycles' own reference (many samples), never with weft's. Prints "cycles_render_s S" (Blender's
# own render time of the frame, wall) at the end; CPU time is the process's (/usr/bin/time).

import sys

import bpy


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:]
    mesh, hdr, out, size, samples = argv[:5]
    width, height = (int(v) for v in size.split("x"))
    denoise = "--denoise" in argv
    threads = int(argv[argv.index("--threads") + 1]) if "--threads" in argv else 0
    return mesh, hdr, out, width, height, int(samples), denoise, threads


def material(name, colour, two_sided_back=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    rho = tuple(c ** 2.2 for c in colour) + (1.0,)
    front = nodes.new("ShaderNodeBsdfDiffuse")
    front.inputs["Color"].default_value = rho
    if two_sided_back is None:
        links.new(front.outputs[0], out.inputs["Surface"])
        return m
    back = nodes.new("ShaderNodeBsdfDiffuse")
    back.inputs["Color"].default_value = tuple(c ** 2.2 for c in two_sided_back) + (1.0,)
    geometry = nodes.new("ShaderNodeNewGeometry")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    links.new(front.outputs[0], mix.inputs[1])
    links.new(back.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], out.inputs["Surface"])
    return m


def main():
    mesh, hdr, out, width, height, samples, denoise, threads = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    bpy.ops.import_scene.obj(filepath=mesh, axis_forward="Y", axis_up="Z")
    cloth = bpy.context.selected_objects[0]
    cloth.data.materials.append(material("cloth", (0.80, 0.25, 0.20), (0.25, 0.45, 0.80)))
    for polygon in cloth.data.polygons:
        polygon.use_smooth = True

    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=0.25,
                                         location=(0, 0, 0.6))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(material("sphere", (0.70, 0.74, 0.80)))
    bpy.ops.mesh.primitive_plane_add(size=10.0, location=(0, 0, 0))
    bpy.context.object.data.materials.append(material("ground", (0.60, 0.60, 0.58)))

    bpy.ops.object.camera_add(location=(1.5, -1.8, 1.35))
    camera = bpy.context.object
    target = bpy.data.objects.new("target", None)
    target.location = (0, 0, 0.5)
    scene.collection.objects.link(target)
    track = camera.constraints.new("TRACK_TO")
    track.target, track.track_axis, track.up_axis = target, "TRACK_NEGATIVE_Z", "UP_Y"
    camera.data.sensor_fit = "VERTICAL"
    camera.data.angle_y = 30.0 * 3.141592653589793 / 180.0
    camera.data.clip_start, camera.data.clip_end = 0.05, 100.0
    scene.camera = camera

    world = bpy.data.worlds.new("studio")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    environment = nodes.new("ShaderNodeTexEnvironment")
    environment.image = bpy.data.images.load(hdr)
    environment.interpolation = "Closest"  # weft reads the nearest texel
    background = nodes["Background"]
    background.inputs["Strength"].default_value = 1.5
    links.new(environment.outputs["Color"], background.inputs["Color"])
    scene.world = world

    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = samples
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = denoise
    cycles.max_bounces = 0
    cycles.seed = 1
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    world.cycles.sampling_method = "AUTOMATIC"  # the map's importance sampling
    scene.render.threads_mode = "FIXED" if threads > 0 else "AUTO"
    if threads > 0:
        scene.render.threads = threads
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_depth = "8"
    scene.render.filepath = out

    import time
    start = time.time()
    bpy.ops.render.render(write_still=True)
    print("cycles_render_s %.3f" % (time.time() - start))


main()
