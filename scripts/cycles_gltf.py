# A glTF scene rendered by Blender's Cycles after Blender's own glTF importer has read it, for
# scripts/gltf-vs-cycles.sh (docs/import.md). Run by Blender, never by Candela or its CI:
#   blender -b --factory-startup -P scripts/cycles_gltf.py -- SCENE.gltf WIDTH HEIGHT SPP THREADS SKY OUT.exr
# The importer turns KHR_lights_punctual back into Blender watts (cd × 4π / 683, lx / 683) and the
# materials into Principled BSDFs. SKY is a uniform world radiance in Blender's W/(sr m²) (0: black).
# The Cycles settings of scripts/cycles_settings.py. Prints the render's seconds.
import os
import sys
import time

import bpy
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_settings import configure_cycles  # noqa: E402

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
configure_cycles(scene, spp, threads, width, height, sky)
scene.render.filepath = output
start = time.time()
bpy.ops.render.render(write_still=True)
print(f"cycles-seconds {time.time() - start:.3f}")
