#!/usr/bin/env python3
"""Writes scenes/sphere-field-10584.json: 10,584 spheres (21 x 21 x 24, jittered), the object
count of the uniform-subdivision example in seed 000 §5.7.2 (15 minutes against 40 days).
Deterministic: a fixed linear congruential generator, so the file is reproducible."""
import json
import sys

def main(path="scenes/sphere-field-10584.json"):
    state = 12345
    def uniform():
        nonlocal state
        state = (1103515245 * state + 12345) % 2**31
        return state / 2**31
    shapes = [{"type": "plane", "name": "floor", "point": [0, -0.6, 0], "normal": [0, 1, 0], "material": "floor"}]
    names = ["red", "green", "blue", "white"]
    for i in range(21):
        for j in range(24):
            for k in range(21):
                center = [round(i - 10 + 0.6 * (uniform() - 0.5), 3),
                          round(j * 0.9 + 0.6 * (uniform() - 0.5), 3),
                          round(-k * 1.0 + 0.6 * (uniform() - 0.5), 3)]
                shapes.append({"type": "sphere", "center": center, "radius": round(0.15 + 0.2 * uniform(), 3),
                               "material": names[(i + j + k) % 4]})
    assert len(shapes) == 10584 + 1
    scene = {
        "format": "candela/1",
        "camera": {"eye": [14, 26, 14], "target": [0, 9, -10], "fov": 60, "width": 640, "height": 480},
        "ambient": 0.15,
        "lights": [{"type": "point", "position": [20, 40, 20], "intensity": 0.8},
                   {"type": "directional", "direction": [-0.3, -1, -0.4], "intensity": 0.4}],
        "materials": {"red": {"kd": [0.7, 0.15, 0.1], "ks": 0.4, "n": 40},
                      "green": {"kd": [0.15, 0.6, 0.2], "ks": 0.4, "n": 40},
                      "blue": {"kd": [0.15, 0.25, 0.7], "kr": 0.3, "ks": 0.5, "n": 60},
                      "white": {"kd": 0.7},
                      "floor": {"kd": {"type": "checkerboard", "even": 0.7, "odd": 0.2, "size": 2}}},
        "shapes": shapes,
        "render": {"accelerator": "bvh"},
        "whitted": {"max_depth": 3},
    }
    with open(path, "w") as out:
        out.write("// 10,584 spheres: the object count of 000 §5.7.2. Made by scripts/make-sphere-field.py.\n")
        out.write(json.dumps(scene, separators=(",", ":")).replace('},{"type"', '},\n{"type"'))
        out.write("\n")

if __name__ == "__main__":
    main(*sys.argv[1:])
