# A glTF scene rendered by Blender's Cycles after Blender's own glTF importer has read it, for
# scripts/gltf-vs-cycles.sh (docs/import.md). Run by Blender, never by Candela or its CI:
#   blender -b --factory-startup -P scripts/cycles_gltf.py -- SCENE.gltf WIDTH HEIGHT SPP THREADS SKY OUT.exr
# The importer turns KHR_lights_punctual back into Blender watts (cd × 4π / 683, lx / 683) and the
# materials into Principled BSDFs. SKY is a uniform world radiance in Blender's W/(sr m²) (0: black).
# Box pixel filter of one pixel, no denoising, no adaptive sampling, no clamping, 64 bounces, a fixed
# seed, the "Standard" view transform (the EXR holds the linear values). Prints the render's seconds.
import sys
import time

import bpy
import numpy

# Blender 3.4's glTF importer still says numpy.bool, which NumPy 1.24 (Debian 12's) removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

arguments = sys.argv[sys.argv.index("--") + 1:]
path, width, height, spp, threads, sky, output = (arguments[0], int(arguments[1]), int(arguments[2]),
                                                  int(arguments[3]), int(arguments[4]), float(arguments[5]),
                                                  arguments[6])

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
scene = bpy.context.scene
cameras = [o for o in scene.objects if o.type == "CAMERA"]
scene.camera = cameras[0]
# Blender's importer sets the sensor fit from the file's aspect ratio; the image is WIDTH × HEIGHT.
scene.render.engine = "CYCLES"
cycles = scene.cycles
cycles.device = "CPU"
cycles.samples = spp
cycles.use_adaptive_sampling = False
cycles.use_denoising = False
cycles.seed = 1
cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = 64
cycles.transmission_bounces = cycles.volume_bounces = cycles.transparent_max_bounces = 64
cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0
cycles.blur_glossy = 0
cycles.caustics_reflective = cycles.caustics_refractive = True
cycles.pixel_filter_type = "BOX"
cycles.filter_width = 1.0
scene.render.threads_mode = "FIXED"
scene.render.threads = threads
scene.render.resolution_x = width
scene.render.resolution_y = height
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.world = bpy.data.worlds.new("sky")
scene.world.use_nodes = True
background = scene.world.node_tree.nodes["Background"]
background.inputs["Color"].default_value = (1, 1, 1, 1)
background.inputs["Strength"].default_value = sky
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "NONE"
scene.view_settings.view_transform = "Standard"
scene.render.filepath = output
start = time.time()
bpy.ops.render.render(write_still=True)
print(f"cycles-seconds {time.time() - start:.3f}")
