"""cycles_bake.py -- the peer of `lightmap` in bench/lightmap_peer.sh: Blender
Cycles (3.4) bakes a gibake scene's indirect irradiance E (W/m^2, linear
RGB, without the albedo) into the same atlas, from the glTF binary that
`lightmap --glb` wrote (the atlas UVs are its TEXCOORD_1).

usage: blender -b --factory-startup -t 2 --python-exit-code 1 \
           -P bench/cycles_bake.py -- [options] SCENE NAME.glb -o OUT.exr

What the glb lacks is added from SCENE (formats/FORMATS.md, "Scene file";
units as common/brdf.h defines them): each `light point` (intensity I,
W/sr) as a Cycles point light of radius 0 and power 4 pi I W (a Cycles
point light of power P sends P / (4 pi) W/sr), each `light directional`
(irradiance E on a surface facing it) as a sun of angle 0 and strength E
(a sun's strength is that irradiance), and `environment R G B` (a constant
radiance) as the world's background colour. A spot light or an
environment map is refused. The y-up scene becomes Blender's z-up as the
glTF importer turns it: (x, y, z) -> (x, -z, y) (checked against the glb's
bounds).

Materials as gibake shades them: each becomes a Lambertian Diffuse BSDF of
the importer's base colour (Kd, times the map_Kd texture), plus, for an
emitter, an Emission of its colour and strength from the front face only
(gibake's emitters are one-sided; Cycles' emission is two-sided unless
masked by Geometry > Backfacing). gibake's Phong lobe (Ks) is dropped: the
glb has no Ks (on the shared scenes, one Sponza material has Ks 0.034).

The bake: DIFFUSE without COLOR gives E / pi per texel (the light the
diffuse closure reflects, divided by its albedo). Cycles 3.4 with the pass
filter {INDIRECT} alone is far too dark (it turns light sampling off, issue
49), so the script bakes {DIRECT, INDIRECT} and {DIRECT} with the same
seed and writes pi (first - second), the indirect irradiance (--pass
direct: pi times the second only, for the unit check). Both bakes use the
TEXCOORD_1 UV map, an image of the atlas's size, margin --margin texels
(extend), every sample (no adaptive sampling, no denoising, no clamping,
no light threshold) and up to --bounces bounces.

Prints on stdout "bake_seconds_direct_indirect S" and "bake_seconds_direct
S", the process's CPU seconds (user + system, all threads) of each bake
call alone.

With --unwrap it bakes nothing: it gives the mesh lightmap UVs of Blender's
own (UV > Lightmap Pack, every face into one image of --size), what a
Blender user bakes into when a scene has none, and prints
"unwrap_seconds S", that call's CPU seconds: the peer of `atlas`.
"""
import argparse
import json
import math
import struct
import sys
import time

import bpy
import numpy
from mathutils import Vector

# Debian 12's Blender 3.4 glTF importer calls numpy.bool, which numpy 1.24
# (Debian 12's) no longer has.
if "bool" not in vars(numpy):
    numpy.bool = bool


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_bake.py")
    p.add_argument("scene", help="the .scene file (its light and environment lines)")
    p.add_argument("glb", help="lightmap --glb's output")
    p.add_argument("-o", "--output", help="the EXR to write")
    p.add_argument("--size", type=int, nargs=2, required=True, metavar=("W", "H"),
                   help="the atlas's size in texels")
    p.add_argument("--samples", type=int, default=64, help="samples per texel")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--margin", type=int, default=0, help="texels of gutter (the atlas padding)")
    p.add_argument("--bounces", type=int, default=64, help="most bounces of a path")
    p.add_argument("--pass", dest="which", choices=("indirect", "direct"), default="indirect")
    p.add_argument("--unwrap", action="store_true",
                   help="no bake: Blender's own lightmap UVs for the mesh instead (the peer "
                   "of `atlas`), their CPU seconds printed")
    a = p.parse_args(argv)
    if not a.unwrap and not a.output:
        p.error("-o is required (but with --unwrap)")
    return a


def fail(message):
    print("cycles_bake.py: " + message, file=sys.stderr)
    sys.exit(1)


def numbers(words, key, count, where):
    """The count numbers after key in words."""
    if key not in words:
        fail("%s: no %s" % (where, key))
    i = words.index(key) + 1
    try:
        return [float(w) for w in words[i:i + count]]
    except ValueError:
        fail("%s: %s wants %d numbers" % (where, key, count))


def scene_lights(path):
    """The scene file's lights and environment: ([(kind, dict)], rgb)."""
    lights, environment = [], (0.0, 0.0, 0.0)
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            words = line.split("#", 1)[0].split()
            where = "%s:%d" % (path, number)
            if not words:
                continue
            if words[0] == "environment":
                environment = tuple(numbers(words, "environment", 3, where))
            elif words[0] == "environment-map":
                fail("%s: an environment map is not supported" % where)
            elif words[0] == "light" and len(words) > 1 and words[1] == "point":
                lights.append(("point", {"position": numbers(words, "position", 3, where),
                                         "intensity": numbers(words, "intensity", 3, where)}))
            elif words[0] == "light" and len(words) > 1 and words[1] == "directional":
                lights.append(("directional",
                               {"direction": numbers(words, "direction", 3, where),
                                "irradiance": numbers(words, "irradiance", 3, where)}))
            elif words[0] == "light":
                fail("%s: only point and directional lights are supported" % where)
    return lights, environment


def to_blender(v):
    """gibake's y-up (x, y, z) as the glTF importer turns it."""
    return Vector((v[0], -v[2], v[1]))


def glb_position_bounds(path):
    """Min and max of every POSITION accessor of the glb's JSON."""
    with open(path, "rb") as f:
        header = f.read(20)
        magic, _, _, length, kind = struct.unpack("<4sIII4s", header)
        if magic != b"glTF" or kind != b"JSON":
            fail("%s: not a glTF binary" % path)
        gltf = json.loads(f.read(length))
    low, high = [math.inf] * 3, [-math.inf] * 3
    for mesh in gltf["meshes"]:
        for primitive in mesh["primitives"]:
            accessor = gltf["accessors"][primitive["attributes"]["POSITION"]]
            low = [min(a, b) for a, b in zip(low, accessor["min"])]
            high = [max(a, b) for a, b in zip(high, accessor["max"])]
    return low, high


def import_mesh(path):
    """The glb's mesh object (its camera dropped), checked against the glb's
    bounds turned to z-up."""
    bpy.ops.import_scene.gltf(filepath=path)
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    for o in bpy.context.scene.objects:
        if o.type != "MESH":
            bpy.data.objects.remove(o, do_unlink=True)
    if len(meshes) != 1:
        fail("%s: %d mesh objects, not 1" % (path, len(meshes)))
    mesh = meshes[0]
    low, high = glb_position_bounds(path)
    corners = [mesh.matrix_world @ Vector(c) for c in mesh.bound_box]
    got_low = [min(c[k] for c in corners) for k in range(3)]
    got_high = [max(c[k] for c in corners) for k in range(3)]
    a, b = to_blender(low), to_blender(high)
    want_low = [min(a[k], b[k]) for k in range(3)]
    want_high = [max(a[k], b[k]) for k in range(3)]
    size = max(h - l for l, h in zip(want_low, want_high))
    if any(abs(g - w) > 1e-4 * size for g, w in zip(got_low + got_high, want_low + want_high)):
        fail("%s: imported bounds %s..%s, not the glb's %s..%s turned z-up"
             % (path, got_low, got_high, want_low, want_high))
    return mesh


def input_of(node, names):
    for name in names:
        if name in node.inputs:
            return node.inputs[name]
    return None


def lambertian(material, image):
    """material's node tree rebuilt as gibake shades it, with image the
    active node (the bake's target)."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
    if principled is None or output is None:
        fail("material %s: no Principled BSDF or output from the importer" % material.name)
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0   # Lambert
    base = principled.inputs["Base Color"]
    diffuse.inputs["Color"].default_value = base.default_value
    if base.is_linked:
        links.new(base.links[0].from_socket, diffuse.inputs["Color"])
    surface = diffuse.outputs["BSDF"]
    emission_in = input_of(principled, ("Emission", "Emission Color"))
    strength_in = input_of(principled, ("Emission Strength",))
    colour = list(emission_in.default_value)[:3] if emission_in is not None else [0, 0, 0]
    strength = strength_in.default_value if strength_in is not None else 1.0
    if emission_in is not None and emission_in.is_linked:
        fail("material %s: an emission texture is not supported" % material.name)
    if max(colour) * strength > 0.0:
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = colour + [1.0]
        emission.inputs["Strength"].default_value = strength
        both = nodes.new("ShaderNodeAddShader")
        links.new(diffuse.outputs["BSDF"], both.inputs[0])
        links.new(emission.outputs["Emission"], both.inputs[1])
        geometry = nodes.new("ShaderNodeNewGeometry")
        front = nodes.new("ShaderNodeMixShader")   # backfacing: the diffuse only
        links.new(geometry.outputs["Backfacing"], front.inputs["Fac"])
        links.new(both.outputs["Shader"], front.inputs[1])
        links.new(diffuse.outputs["BSDF"], front.inputs[2])
        surface = front.outputs["Shader"]
    links.new(surface, output.inputs["Surface"])
    target = nodes.new("ShaderNodeTexImage")
    target.image = image
    for n in nodes:
        n.select = False
    target.select = True
    nodes.active = target


def add_lights(lights, environment):
    scene = bpy.context.scene
    for number, (kind, light) in enumerate(lights):
        if kind == "point":
            rgb = light["intensity"]
            data = bpy.data.lights.new("gibake_point_%d" % number, "POINT")
            data.shadow_soft_size = 0.0
            data.energy = 4.0 * math.pi * max(rgb)
            where, rotation = to_blender(light["position"]), None
        else:
            rgb = light["irradiance"]
            data = bpy.data.lights.new("gibake_sun_%d" % number, "SUN")
            data.angle = 0.0
            data.energy = max(rgb)
            where = Vector((0.0, 0.0, 0.0))
            rotation = to_blender(light["direction"]).normalized().to_track_quat("-Z", "Y")
        top = max(rgb)
        data.color = [c / top for c in rgb] if top > 0.0 else [0.0, 0.0, 0.0]
        data.cycles.cast_shadow = True
        o = bpy.data.objects.new(data.name, data)
        o.location = where
        if rotation is not None:
            o.rotation_mode = "QUATERNION"
            o.rotation_quaternion = rotation
        scene.collection.objects.link(o)
    world = bpy.data.worlds.new("gibake_environment")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = list(environment) + [1.0]
    background.inputs["Strength"].default_value = 1.0
    scene.world = world


def set_cycles(a):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = a.seed
    c.use_animated_seed = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.max_bounces = a.bounces
    c.diffuse_bounces = a.bounces
    c.glossy_bounces = a.bounces
    c.transmission_bounces = a.bounces
    c.transparent_max_bounces = a.bounces
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.blur_glossy = 0.0
    scene.render.threads_mode = "AUTO"   # the command line's -t


def bake(mesh, uv_name, a, filter_):
    """One DIFFUSE bake without colour into the active images; its CPU seconds."""
    start = time.process_time()
    bpy.ops.object.bake(type="DIFFUSE", pass_filter=filter_, uv_layer=uv_name,
                        margin=a.margin, margin_type="EXTEND", use_clear=True,
                        target="IMAGE_TEXTURES", use_selected_to_active=False)
    return time.process_time() - start


def select_only(mesh):
    """The mesh selected and active, the operators' subject."""
    bpy.ops.object.select_all(action="DESELECT")
    mesh.select_set(True)
    bpy.context.view_layer.objects.active = mesh


def unwrap(mesh, a):
    """New lightmap UVs for the mesh, as a Blender user makes them to bake
    into (UV > Lightmap Pack of every face into one image of --size, its
    default margin); the call's CPU seconds."""
    select_only(mesh)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    start = time.process_time()
    bpy.ops.uv.lightmap_pack(PREF_CONTEXT="ALL_FACES", PREF_PACK_IN_ONE=True,
                             PREF_NEW_UVLAYER=True, PREF_IMG_PX_SIZE=max(a.size))
    seconds = time.process_time() - start
    bpy.ops.object.mode_set(mode="OBJECT")
    return seconds


def pixels(image):
    buffer = numpy.empty(len(image.pixels), dtype=numpy.float32)
    image.pixels.foreach_get(buffer)
    return buffer.reshape(-1, 4)


def main():
    a = arguments()
    lights, environment = scene_lights(a.scene)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    mesh = import_mesh(a.glb)
    if a.unwrap:
        print("unwrap_seconds %.3f" % unwrap(mesh, a))
        return
    if len(mesh.data.uv_layers) < 2:
        fail("%s: no TEXCOORD_1 (the atlas UVs)" % a.glb)
    uv = mesh.data.uv_layers[1]
    mesh.data.uv_layers.active = uv
    width, height = a.size
    image = bpy.data.images.new("gibake_bake", width, height, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    for slot in mesh.material_slots:
        if slot.material is not None:
            lambertian(slot.material, image)
    add_lights(lights, environment)
    set_cycles(a)
    select_only(mesh)

    rgb = numpy.zeros((width * height, 3), dtype=numpy.float64)
    if a.which == "indirect":
        seconds = bake(mesh, uv.name, a, {"DIRECT", "INDIRECT"})
        print("bake_seconds_direct_indirect %.3f" % seconds)
        rgb += pixels(image)[:, :3]
    seconds = bake(mesh, uv.name, a, {"DIRECT"})
    print("bake_seconds_direct %.3f" % seconds)
    rgb -= pixels(image)[:, :3]
    if a.which == "direct":
        rgb = -rgb
    out = numpy.ones((width * height, 4), dtype=numpy.float32)
    out[:, :3] = math.pi * rgb
    result = bpy.data.images.new("gibake_result", width, height, alpha=True, float_buffer=True)
    result.colorspace_settings.name = "Non-Color"
    result.pixels.foreach_set(out.ravel())
    result.filepath_raw = a.output
    result.file_format = "OPEN_EXR"
    result.use_half_precision = False
    result.save()


main()
