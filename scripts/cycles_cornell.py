# The Cornell box of scenes/cornell-box.json in Blender's Cycles, for scripts/path-vs-cycles.sh
# (docs/benchmarks.md "Path tracing against Cycles"). Run by Blender, never by Candela
# or its CI:
#   blender -b --factory-startup -P scripts/cycles_cornell.py -- SCENE.json SIZE SPP THREADS OUT.exr
# Same quads, boxes, camera and albedos; Lambertian (Diffuse BSDF, roughness 0) surfaces; the lamp
# an Emission shader whose radiance is the scene's "emission" (Blender's manual: strength 1 shows
# the Color input as is); box pixel filter of one pixel; no denoising, no adaptive sampling, no
# clamping, no caustic filtering; 64 bounces of every kind; a fixed seed. Prints the render's
# seconds (the render call: scene sync, BVH and sampling, as Candela's "render" line counts them).
import json
import math
import os
import re
import sys
import time

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_settings import configure_cycles  # noqa: E402

arguments = sys.argv[sys.argv.index("--") + 1:]
scene_path, size, spp, threads, output = arguments[0], int(arguments[1]), int(arguments[2]), int(arguments[3]), arguments[4]
# The scene files have // comments (outside strings) before the JSON.
text = "\n".join(re.sub(r"^\s*//.*$", "", line) for line in open(scene_path).read().splitlines())
description = json.loads(text)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
configure_cycles(scene, spp, threads, size, size)


def material_of(name, description):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    emission = description.get("emission")
    if emission:
        shader = nodes.new("ShaderNodeEmission")
        shader.inputs["Color"].default_value = (*emission, 1)
        shader.inputs["Strength"].default_value = 1
    else:
        shader = nodes.new("ShaderNodeBsdfDiffuse")
        kd = description.get("kd", 0.8)
        kd = kd if isinstance(kd, list) else [kd] * 3
        shader.inputs["Color"].default_value = (*kd, 1)
        shader.inputs["Roughness"].default_value = 0
    material.node_tree.links.new(shader.outputs[0], out.inputs["Surface"])
    return material


materials = {name: material_of(name, m) for name, m in description["materials"].items()}


def add_mesh(name, vertices, faces, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([tuple(v) for v in vertices], [], faces)
    mesh.materials.append(materials[material])
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)


for index, shape in enumerate(description["shapes"]):
    name = shape.get("name", f"shape {index}")
    if shape["type"] == "quad":
        c, u, v = (Vector(shape[k]) for k in ("corner", "edge_u", "edge_v"))
        add_mesh(name, [c, c + u, c + u + v, c + v], [(0, 1, 2, 3)], shape["material"])
    elif shape["type"] == "box":
        lo, hi = shape["min"], shape["max"]
        corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
        faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
        add_mesh(name, corners, faces, shape["material"])
    else:
        raise SystemExit(f"cycles_cornell.py: shape type {shape['type']} is not translated")

view = description["camera"]
camera = bpy.data.cameras.new("camera")
camera.sensor_fit = "HORIZONTAL"  # Candela's fov is horizontal
camera.angle = math.radians(view["fov"])
camera_object = bpy.data.objects.new("camera", camera)
scene.collection.objects.link(camera_object)
eye, target = Vector(view["eye"]), Vector(view["target"])
camera_object.location = eye
camera_object.rotation_mode = "QUATERNION"
if view.get("up", [0, 1, 0]) != [0, 1, 0]:
    raise SystemExit("cycles_cornell.py: only the up vector [0, 1, 0] is translated")
camera_object.rotation_quaternion = (target - eye).to_track_quat("-Z", "Y")
scene.camera = camera_object

scene.render.filepath = output
start = time.perf_counter()
bpy.ops.render.render(write_still=True)
print(f"cycles-seconds {time.perf_counter() - start:.3f}")
