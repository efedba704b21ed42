#!/usr/bin/env python3
"""Texture and environment assets for scenes/, with the standard library only.

  make_textures.py images DIR          tiles.png, random-squares.png, uv-grid.png, sky.exr
  make_textures.py png IN.pfm OUT.png  a render (linear floats) as an 8-bit sRGB PNG
  make_textures.py compare A.pfm B.pfm mean and largest channel difference of two renders

Everything is deterministic: the random colors and the noise come from an integer hash, not
from the random module, so the files are the same bytes on every run and every machine.

The cube-map faces are rendered by candela itself (scripts/make-textures.sh): in the cube map's
default "inside" layout (src/shading/environment.h) a face is exactly what a 90° camera at the
centre sees, so a render is a face as it is.
"""

import colorsys
import math
import struct
import sys
import zlib

# --- files ------------------------------------------------------------------------------------


def _png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def write_png(path, width, height, rows):
    """rows: `height` bytes objects of width*3 (8-bit RGB, sRGB-encoded), top row first. Each row
    gets the PNG filter with the smallest sum of absolute values (the usual heuristic)."""
    stride = width * 3
    previous = bytes(stride)
    raw = bytearray()
    for row in rows:
        assert len(row) == stride
        candidates = []
        for kind in range(5):
            out = bytearray(stride)
            for i in range(stride):
                a = row[i - 3] if i >= 3 else 0
                b = previous[i]
                c = previous[i - 3] if i >= 3 else 0
                predictor = (0, a, b, (a + b) // 2, _paeth(a, b, c))[kind]
                out[i] = (row[i] - predictor) & 0xFF
            candidates.append((sum(v if v < 128 else 256 - v for v in out), kind, out))
        _, kind, out = min(candidates)
        raw.append(kind)
        raw += out
        previous = row
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(_png_chunk(b"IHDR", header))
        f.write(_png_chunk(b"sRGB", b"\x00"))
        f.write(_png_chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        f.write(_png_chunk(b"IEND", b""))


def read_pfm(path):
    """(width, height, pixels) with pixels[y][x] = (r, g, b) and y = 0 the TOP row."""
    with open(path, "rb") as f:
        data = f.read()
    tokens, position = [], 0
    while len(tokens) < 4:  # "PF", width, height, scale
        while data[position : position + 1].isspace():
            position += 1
        start = position
        while not data[position : position + 1].isspace():
            position += 1
        tokens.append(data[start:position].decode())
    position += 1  # the single whitespace after the scale
    if tokens[0] != "PF":
        raise ValueError(f"{path}: not a color PFM")
    width, height, scale = int(tokens[1]), int(tokens[2]), float(tokens[3])
    order = "<" if scale < 0 else ">"
    values = struct.unpack_from(f"{order}{width * height * 3}f", data, position)
    rows = []
    for y in range(height):  # stored bottom row first
        base = (height - 1 - y) * width * 3
        rows.append([tuple(values[base + 3 * x : base + 3 * x + 3]) for x in range(width)])
    return width, height, rows


def write_exr(path, width, height, pixel):
    """A scanline OpenEXR file, half-float R, G, B, ZIP compression (16 rows a chunk).
    pixel(x, y) -> (r, g, b) linear, y = 0 the top row."""

    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (
        b"\x76\x2f\x31\x01"
        + struct.pack("<i", 2)
        + attribute("channels", "chlist", channels)
        + attribute("compression", "compression", b"\x03")
        + attribute("dataWindow", "box2i", box)
        + attribute("displayWindow", "box2i", box)
        + attribute("lineOrder", "lineOrder", b"\x00")
        + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
        + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
        + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
        + b"\0"
    )
    rows_per_chunk = 16
    chunks = []
    for first in range(0, height, rows_per_chunk):
        raw = bytearray()
        for y in range(first, min(first + rows_per_chunk, height)):
            line = [pixel(x, y) for x in range(width)]
            for channel in (2, 1, 0):  # B, G, R: alphabetical
                raw += struct.pack(f"<{width}e", *(min(65504.0, p[channel]) for p in line))
        # OpenEXR's ZIP pre-processing: even bytes then odd bytes, then a byte-wise delta.
        interleaved = bytearray(raw[0::2] + raw[1::2])
        predicted = bytearray(interleaved)
        for i in range(1, len(interleaved)):
            predicted[i] = (interleaved[i] - interleaved[i - 1] + 128) & 0xFF
        packed = zlib.compress(bytes(predicted), 9)
        chunks.append((first, packed if len(packed) < len(raw) else bytes(raw)))
    offset = len(header) + 8 * len(chunks)
    table = b""
    for _, data in chunks:
        table += struct.pack("<Q", offset)
        offset += 8 + len(data)
    with open(path, "wb") as f:
        f.write(header + table)
        for first, data in chunks:
            f.write(struct.pack("<ii", first, len(data)) + data)


def srgb_encode(linear):
    linear = min(1.0, max(0.0, linear))
    encoded = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return int(encoded * 255 + 0.5)


def to_bytes(color):
    """Linear RGB to 8-bit sRGB."""
    return bytes(srgb_encode(c) for c in color)


def display_bytes(color):
    """A color already in display (sRGB-encoded) values in [0, 1] to 8 bits."""
    return bytes(int(min(1.0, max(0.0, c)) * 255 + 0.5) for c in color)


# --- deterministic randomness and noise --------------------------------------------------------


def hash_unit(*values):
    """A number in [0, 1) from integers (a 32-bit integer hash, the same on every machine)."""
    h = 0x9E3779B9
    for v in values:
        h ^= (v & 0xFFFFFFFF) + 0x7F4A7C15 + ((h << 6) & 0xFFFFFFFF) + (h >> 2)
        h &= 0xFFFFFFFF
        h ^= h >> 16
        h = (h * 0x7FEB352D) & 0xFFFFFFFF
        h ^= h >> 15
        h = (h * 0x846CA68B) & 0xFFFFFFFF
        h ^= h >> 16
    return h / 2**32


def value_noise(x, y, period, seed):
    """Smooth value noise of lattice spacing 1, periodic with `period` lattice cells."""
    ix, iy = math.floor(x), math.floor(y)
    fx, fy = x - ix, y - iy
    sx, sy = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy)

    def lattice(i, j):
        return hash_unit(i % period, j % period, seed)

    top = lattice(ix, iy) + sx * (lattice(ix + 1, iy) - lattice(ix, iy))
    bottom = lattice(ix, iy + 1) + sx * (lattice(ix + 1, iy + 1) - lattice(ix, iy + 1))
    return top + sy * (bottom - top)


def fbm(x, y, period, seed, octaves=4):
    """Sum of octaves of value_noise in [0, 1], periodic with `period` at the first octave."""
    total, amplitude, norm = 0.0, 1.0, 0.0
    for octave in range(octaves):
        total += amplitude * value_noise(x, y, period, seed + octave)
        norm += amplitude
        x, y, period, amplitude = x * 2, y * 2, period * 2, amplitude * 0.5
    return total / norm


def mix(a, b, t):
    return tuple(a[i] + (b[i] - a[i]) * t for i in range(3))


# --- the images ---------------------------------------------------------------------------------


def tiles(path, size=256, count=4):
    """Stone floor tiles with grout, `count`×`count` tiles; repeats seamlessly. Colors here and
    in the other images are picked as display (sRGB-encoded) values."""
    cell = size // count
    grout_half = 2.5
    stones = [(0.66, 0.60, 0.52), (0.74, 0.70, 0.63), (0.56, 0.53, 0.50), (0.72, 0.62, 0.50), (0.62, 0.62, 0.60)]
    grout = (0.30, 0.28, 0.26)
    rows = []
    for y in range(size):
        row = bytearray()
        for x in range(size):
            tx, ty = x // cell, y // cell
            # distance (in pixels) from the pixel centre to the nearest tile edge
            dx = min((x % cell) + 0.5, cell - (x % cell) - 0.5)
            dy = min((y % cell) + 0.5, cell - (y % cell) - 0.5)
            edge = min(dx, dy)
            grain = fbm(x / 16, y / 16, size // 16, 7)
            speckle = hash_unit(x, y, 3)
            if edge < grout_half:
                color = tuple(c * (0.8 + 0.4 * grain) for c in grout)
            else:
                base = stones[int(hash_unit(tx % count, ty % count, 11) * len(stones))]
                cloud = fbm(x / 24 + tx * 3.7, y / 24 + ty * 1.3, 1000, 19)
                shade = 0.75 + 0.45 * cloud + 0.08 * (speckle - 0.5)
                bevel = min(1.0, (edge - grout_half) / 4)  # darker towards the grout
                color = tuple(c * shade * (0.7 + 0.3 * bevel) for c in base)
            row += display_bytes(color)
        rows.append(bytes(row))
    write_png(path, size, size, rows)


def random_squares(path, columns=16, lines=8, cell=16):
    """000 Figure 21: an array of randomly colored squares (2:1, for the sphere mapping)."""
    rows = []
    for y in range(lines * cell):
        row = bytearray()
        for x in range(columns * cell):
            i, j = x // cell, y // cell
            hue = hash_unit(i, j, 1)
            saturation = 0.45 + 0.55 * hash_unit(i, j, 2)
            value = 0.55 + 0.45 * hash_unit(i, j, 3)
            row += display_bytes(colorsys.hsv_to_rgb(hue, saturation, value))
        rows.append(bytes(row))
    write_png(path, columns * cell, lines * cell, rows)


def uv_grid(path, width=256, height=128, step=16):
    """A grid for showing mappings: the hue follows u (so the u = 0/1 seam is a jump from violet
    to red), the brightness v (dark at v = 0, the bottom row), black lines every 1/16 in u and
    1/8 in v, a thick white line at u = 0.5."""
    rows = []
    for y in range(height):
        v = 1 - (y + 0.5) / height  # images count v from the bottom row
        row = bytearray()
        for x in range(width):
            u = (x + 0.5) / width
            color = colorsys.hsv_to_rgb(0.85 * u, 0.75, 0.35 + 0.6 * v)
            if x % step == 0 or y % step == 0:
                color = (0.02, 0.02, 0.02)
            if abs(x - width / 2) < 1.5:
                color = (1.0, 1.0, 1.0)
            row += display_bytes(color)
        rows.append(bytes(row))
    write_png(path, width, height, rows)


SUN = (math.cos(math.radians(25)) * math.sin(math.radians(-40)), math.sin(math.radians(25)),
       -math.cos(math.radians(25)) * math.cos(math.radians(-40)))


def sky_radiance(d):
    """An outdoor panorama, y up: a sky gradient, a sun 25° high (towards −z, 40° to the
    left), a ground of large checker fields fading into haze at the horizon."""
    x, y, z = d
    horizon = (0.85, 0.88, 0.92)
    if y >= 0:
        zenith = (0.12, 0.30, 0.75)
        color = mix(horizon, zenith, y ** 0.45)
        cos_sun = x * SUN[0] + y * SUN[1] + z * SUN[2]
        angle = math.degrees(math.acos(max(-1.0, min(1.0, cos_sun))))
        glow = 0.8 * math.exp(-angle / 3) + 0.12 * math.exp(-angle / 20)
        color = tuple(c + glow * s for c, s in zip(color, (1.0, 0.85, 0.6)))
        if angle < 2.5:
            color = (60.0, 55.0, 45.0)
        return color
    # the ground plane 1.6 units below the eye, in fields of 4 units
    t = 1.6 / -y
    gx, gz = x * t, z * t
    field = (math.floor(gx / 4) + math.floor(gz / 4)) % 2
    ground = (0.20, 0.32, 0.10) if field else (0.33, 0.30, 0.16)
    haze = math.exp(-t / 120)
    return mix(horizon, ground, haze)


def sky(path, width=512, height=256, supersample=3):
    """sky.exr: the equirectangular panorama of src/shading/environment.h (forward = −z at the
    image centre, up the top row, right (+x) at u = 0.75), linear half floats."""

    def pixel(px, py):
        total = [0.0, 0.0, 0.0]
        for i in range(supersample):
            for j in range(supersample):
                u = (px + (i + 0.5) / supersample) / width
                v = (py + (j + 0.5) / supersample) / height
                longitude = (u - 0.5) * 2 * math.pi  # atan2(d·right, d·forward)
                polar = v * math.pi                  # acos(d·up)
                s = math.sin(polar)
                # forward = −z, right = forward × up = +x, up = +y
                d = (s * math.sin(longitude), math.cos(polar), -s * math.cos(longitude))
                c = sky_radiance(d)
                for k in range(3):
                    total[k] += c[k]
        n = supersample * supersample
        return tuple(t / n for t in total)

    write_exr(path, width, height, pixel)


def pfm_to_png(pfm_path, png_path):
    width, height, rows = read_pfm(pfm_path)
    write_png(png_path, width, height, [b"".join(to_bytes(p) for p in row) for row in rows])


def compare(a_path, b_path):
    wa, ha, a = read_pfm(a_path)
    wb, hb, b = read_pfm(b_path)
    if (wa, ha) != (wb, hb):
        raise SystemExit(f"sizes differ: {wa}x{ha} and {wb}x{hb}")
    largest, total = 0.0, 0.0
    for y in range(ha):
        for x in range(wa):
            for c in range(3):
                difference = abs(min(1.0, a[y][x][c]) - min(1.0, b[y][x][c]))
                largest = max(largest, difference)
                total += difference
    print(f"mean difference {total / (wa * ha * 3):.4f}, largest {largest:.4f}")


def main(arguments):
    if len(arguments) == 2 and arguments[0] == "images":
        directory = arguments[1]
        tiles(f"{directory}/tiles.png")
        random_squares(f"{directory}/random-squares.png")
        uv_grid(f"{directory}/uv-grid.png")
        sky(f"{directory}/sky.exr")
    elif len(arguments) == 3 and arguments[0] == "png":
        pfm_to_png(arguments[1], arguments[2])
    elif len(arguments) == 3 and arguments[0] == "compare":
        compare(arguments[1], arguments[2])
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
