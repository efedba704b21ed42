# Builds the three glTF test scenes of scenes/gltf/ in Blender and writes them with Blender's own
# glTF exporter (glTF Separate: NAME.gltf, NAME.bin and the textures beside them), so that
# Candela reads files as a Blender user's would be. Run by Blender, never by Candela or its CI:
#   blender -b --factory-startup -P scripts/blender_gltf_scenes.py -- OUT_DIR
# The scenes (docs/import.md):
#   interior     a 4 × 3 × 2.7 m room with a glazed window, a ceiling point light and a spot on the
#                back wall, a table (KHR_lights_punctual, KHR_materials_transmission)
#   textured     a sphere with a checker base-colour texture and a gold torus on a ground plane
#                under the sun (a directional light; the sky is the including scene's,
#                scenes/gltf/textured-sky.json)
#   still-life   a glass sphere, a brushed metal cube and a copper cylinder on a table against a
#                wall, lit by a point light and a spot (KHR_materials_ior, metallic-roughness)
# Lights are given in Blender's watts; the exporter writes W/(4π) × 683 cd (points and spots) and
# W/m² × 683 lx (the sun), its "Standard" lighting mode.
import math
import os
import sys

import bpy

out_dir = sys.argv[sys.argv.index("--") + 1]


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)


def material(name, color, metallic=0.0, roughness=0.5, transmission=0.0, ior=1.5, texture=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    principled = m.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (*color, 1)
    principled.inputs["Metallic"].default_value = metallic
    principled.inputs["Roughness"].default_value = roughness
    principled.inputs["Transmission"].default_value = transmission
    principled.inputs["IOR"].default_value = ior
    principled.inputs["Specular"].default_value = 0.5  # F0 = 0.04, glTF's dielectric
    if texture:
        image = m.node_tree.nodes.new("ShaderNodeTexImage")
        image.image = texture
        m.node_tree.links.new(image.outputs["Color"], principled.inputs["Base Color"])
    return m


def box(name, size, location, mat, rotation=(0, 0, 0)):
    bpy.ops.mesh.primitive_cube_add(size=1, location=location, rotation=rotation)
    obj = bpy.context.object
    obj.name = name
    obj.scale = size
    obj.data.materials.append(mat)
    return obj


def plane(name, size, location, rotation, mat):
    bpy.ops.mesh.primitive_plane_add(size=1, location=location, rotation=rotation)
    obj = bpy.context.object
    obj.name = name
    obj.scale = (size[0], size[1], 1)
    obj.data.materials.append(mat)
    return obj


def light(name, kind, watts, location, rotation=(0, 0, 0), spot_size=None, spot_blend=0.15):
    data = bpy.data.lights.new(name, kind)
    data.energy = watts
    data.shadow_soft_size = 0  # a point: glTF's punctual lights have no size
    if kind == "SUN":
        data.angle = 0
    if spot_size is not None:
        data.spot_size = spot_size
        data.spot_blend = spot_blend
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def camera(name, location, rotation, lens=28):
    data = bpy.data.cameras.new(name)
    data.lens = lens
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    bpy.context.scene.render.resolution_x = 320
    bpy.context.scene.render.resolution_y = 240
    return obj


def export(name):
    folder = os.path.join(out_dir, name)
    os.makedirs(folder, exist_ok=True)
    bpy.ops.export_scene.gltf(filepath=os.path.join(folder, name + ".gltf"), export_format="GLTF_SEPARATE",
                              export_cameras=True, export_lights=True, export_apply=True,
                              export_image_format="AUTO")


def checker_image(size=64, cells=8):
    image = bpy.data.images.new("checker", size, size)
    pixels = []
    for y in range(size):
        for x in range(size):
            on = ((x * cells // size) + (y * cells // size)) % 2 == 0
            pixels += [0.9, 0.9, 0.85, 1] if on else [0.1, 0.25, 0.6, 1]
    image.pixels = pixels
    image.filepath_raw = os.path.join(out_dir, "checker.png")
    image.file_format = "PNG"
    image.save()
    return image


# Blender is z-up; the exporter turns it into glTF's y-up.
reset()
white = material("wall", (0.7, 0.7, 0.7), roughness=0.9)
floor = material("floor", (0.45, 0.3, 0.2), roughness=0.6)
glass = material("glass", (1, 1, 1), roughness=0.0, transmission=1.0, ior=1.5)
wood = material("table", (0.5, 0.35, 0.2), roughness=0.5)
plane("floor", (4, 3), (0, 0, 0), (0, 0, 0), floor)
plane("ceiling", (4, 3), (0, 0, 2.7), (math.pi, 0, 0), white)
plane("back", (4, 2.7), (0, 1.5, 1.35), (math.pi / 2, 0, 0), white)
plane("front", (4, 2.7), (0, -1.5, 1.35), (-math.pi / 2, 0, 0), white)
# A plane turned about y faces ±x with its local x along ∓z (height) and y along y (depth).
plane("left", (2.7, 3), (-2, 0, 1.35), (0, math.pi / 2, 0), white)
# The right wall around a 1.2 × 1 m window, 1 m above the floor, glazed.
plane("right-below", (1, 3), (2, 0, 0.5), (0, -math.pi / 2, 0), white)
plane("right-above", (0.7, 3), (2, 0, 2.35), (0, -math.pi / 2, 0), white)
plane("right-side-a", (1, 0.9), (2, -1.05, 1.5), (0, -math.pi / 2, 0), white)
plane("right-side-b", (1, 0.9), (2, 1.05, 1.5), (0, -math.pi / 2, 0), white)
plane("pane", (1, 1.2), (2, 0, 1.5), (0, -math.pi / 2, 0), glass)
box("table", (1.2, 0.8, 0.05), (-0.3, 0.3, 0.72), wood)
box("table-leg", (0.08, 0.08, 0.7), (-0.8, 0.6, 0.35), wood)
box("table-leg-2", (0.08, 0.08, 0.7), (0.2, 0.0, 0.35), wood)
light("ceiling-light", "POINT", 40, (0, 0, 2.5))
light("wall-spot", "SPOT", 25, (-1.5, -1.2, 2.4), (math.radians(60), 0, math.radians(-35)), math.radians(50))
camera("view", (-1.8, -1.3, 1.6), (math.radians(80), 0, math.radians(-50)), lens=18)
export("interior")

reset()
ground = material("ground", (0.5, 0.5, 0.5), roughness=0.8)
checker = checker_image()
painted = material("checker", (1, 1, 1), roughness=0.4, texture=checker)
gold = material("gold", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3)
plane("ground", (10, 10), (0, 0, 0), (0, 0, 0), ground)
bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.6, location=(-0.5, 0, 0.6))
sphere = bpy.context.object
sphere.name = "sphere"
bpy.ops.object.shade_smooth()
sphere.data.materials.append(painted)
bpy.ops.mesh.primitive_torus_add(major_radius=0.4, minor_radius=0.15, location=(0.8, -0.3, 0.15))
torus = bpy.context.object
torus.name = "torus"
bpy.ops.object.shade_smooth()
torus.data.materials.append(gold)
light("sun", "SUN", 3, (0, 0, 5), (math.radians(40), 0, math.radians(30)))
camera("view", (0.3, -3.5, 1.5), (math.radians(72), 0, math.radians(4)), lens=35)
export("textured")

reset()
table = material("table", (0.35, 0.35, 0.38), roughness=0.7)
backdrop = material("backdrop", (0.75, 0.72, 0.65), roughness=0.9)
glass = material("glass", (1, 1, 1), roughness=0.0, transmission=1.0, ior=1.5)
steel = material("brushed-steel", (0.8, 0.8, 0.82), metallic=1.0, roughness=0.35)
copper = material("copper", (0.95, 0.64, 0.54), metallic=1.0, roughness=0.25)
plane("table", (4, 3), (0, 0, 0), (0, 0, 0), table)
plane("wall", (4, 2.5), (0, 1.0, 1.25), (math.pi / 2, 0, 0), backdrop)
bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.3, location=(-0.5, -0.2, 0.3))
ball = bpy.context.object
ball.name = "glass-ball"
bpy.ops.object.shade_smooth()
ball.data.materials.append(glass)
box("steel-cube", (0.4, 0.4, 0.4), (0.3, 0.25, 0.2), steel, (0, 0, math.radians(25)))
bpy.ops.mesh.primitive_cylinder_add(vertices=48, radius=0.15, depth=0.5, location=(0.75, -0.3, 0.25))
can = bpy.context.object
can.name = "copper-can"
bpy.ops.object.shade_smooth()
can.data.materials.append(copper)
light("key", "POINT", 40, (-1.2, -1.5, 2.0))
light("rim", "SPOT", 25, (1.5, -0.8, 1.8), (math.radians(55), 0, math.radians(60)), math.radians(45))
camera("view", (0, -2.6, 1.1), (math.radians(75), 0, 0), lens=32)
export("still-life")
