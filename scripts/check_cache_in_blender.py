# Checks weft's --export-cache files in Blender by hand (not part of CI: Blender is large).
#   weft run SCENE --export-cache pc2,mdd,gltf --out DIR
#   blender -b --factory-startup --python scripts/check_cache_in_blender.py -- DIR
# Imports DIR/cloth.obj with Blender's defaults, plays DIR/cloth.pc2 and DIR/cloth.mdd through a
# Mesh Cache modifier with its defaults, imports DIR/cloth.gltf, and prints, at Blender frames 1,
# a middle one and the last, the largest distance between Blender's world coordinates and weft's
# frame of the same number (z up), read from the .pc2 (sample k is weft's frame k). A middle
# frame tells an offset of one frame apart; the last alone cannot (the cache clamps there).
# Exits 1 when a distance passes 1e-5 m.
import bpy, struct, sys, numpy
numpy.bool = bool  # Debian 12: Blender 3.4 glTF importer uses numpy.bool, gone in numpy 1.24
d = sys.argv[sys.argv.index('--') + 1].rstrip('/') + '/'
bpy.ops.wm.read_factory_settings(use_empty=True)
raw = open(d + 'cloth.pc2', 'rb').read()
_, ver, npts, start, rate, nsamp = struct.unpack('<12siiffi', raw[:32])
def pc2_frame(k):
    """weft's frame k (sample k), y up, back to weft's z up."""
    off = 32 + k * npts * 12
    v = struct.unpack('<%df' % (3 * npts), raw[off:off + 12 * npts])
    return [(v[3*i], -v[3*i+2], v[3*i+1]) for i in range(npts)]
frames = sorted({1, nsamp // 2, nsamp - 1})
worst = 0.0
def check(obj, label):
    global worst
    for k in frames:
        bpy.context.scene.frame_set(k)
        dg = bpy.context.evaluated_depsgraph_get()
        ev = obj.evaluated_get(dg)
        me = ev.to_mesh()
        want = pc2_frame(k)
        err = max(max(abs(a - b) for a, b in zip(ev.matrix_world @ v.co, w)) for v, w in zip(me.vertices, want))
        print(label, 'Blender frame', k, 'max |world - weft frame %d| =' % k, err)
        worst = max(worst, err)
        ev.to_mesh_clear()
bpy.ops.wm.obj_import(filepath=d + 'cloth.obj')
obj = bpy.context.selected_objects[0]
print('OBJ object rotation', tuple(obj.rotation_euler), 'verts', len(obj.data.vertices), 'pc2 points', npts,
      'samples', nsamp, 'material', [m.name for m in obj.data.materials])
for fmt in ('PC2', 'MDD'):
    m = obj.modifiers.new('cache', 'MESH_CACHE')  # every setting on its default
    m.cache_format = fmt
    m.filepath = d + ('cloth.pc2' if fmt == 'PC2' else 'cloth.mdd')
    check(obj, fmt)
    obj.modifiers.remove(obj.modifiers['cache'])
bpy.ops.import_scene.gltf(filepath=d + 'cloth.gltf')
g = [o for o in bpy.context.selected_objects if o.type == 'MESH'][0]
keys = g.data.shape_keys.key_blocks
print('glTF shape keys', len(keys), keys[1].name, 'action',
      g.data.shape_keys.animation_data.action.frame_range[:] if g.data.shape_keys.animation_data else None,
      'material', [m.name for m in g.data.materials])
check(g, 'glTF')
print('worst', worst)
sys.exit(0 if worst < 1e-5 else 1)
