# The Cycles settings every peer comparison uses (scripts/cycles_cornell.py, scripts/cycles_gltf.py):
# CPU, SPP samples, no adaptive sampling, no denoising, a fixed seed, 64 bounces of every kind, no
# clamping, no glossy blur, caustics on, a box pixel filter of one pixel, THREADS threads, a
# WIDTH × HEIGHT image, a world of uniform radiance `sky` (0: black), a 32-bit uncompressed EXR of
# the linear values (the "Standard" view transform). Imported by Blender's Python, never by Candela.
import bpy


def configure_cycles(scene, spp, threads, width, height, sky=0.0):
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
