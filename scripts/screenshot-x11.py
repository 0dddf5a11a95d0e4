#!/usr/bin/env python3
"""Saves the screen of an X display ($DISPLAY) as a PNG, optionally after resizing a window to fill it,
scaled down by an integer factor (the mean of each block), with Python's standard library and libX11.

Usage: screenshot-x11.py OUT.png [--window ID] [--settle SECONDS] [--scale N]"""

import argparse
import ctypes
import struct
import sys
import time
import zlib


class XImage(ctypes.Structure):
    # the leading fields of Xlib's XImage, up to the colour masks
    _fields_ = [(name, ctypes.c_int) for name in ("width", "height", "xoffset", "format")] + [
        ("data", ctypes.c_void_p)] + [(name, ctypes.c_int) for name in (
            "byte_order", "bitmap_unit", "bitmap_bit_order", "bitmap_pad", "depth",
            "bytes_per_line", "bits_per_pixel")] + [
        (name, ctypes.c_ulong) for name in ("red_mask", "green_mask", "blue_mask")]


def grab(xlib, display, width, height):
    """RGB rows of the top-left width x height pixels of the default screen's root window."""
    xlib.XDefaultRootWindow.restype = ctypes.c_ulong
    xlib.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    xlib.XGetImage.restype = ctypes.POINTER(XImage)
    xlib.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                               ctypes.c_uint, ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
    all_planes, z_pixmap = ctypes.c_ulong(-1).value, 2
    image = xlib.XGetImage(display, xlib.XDefaultRootWindow(display), 0, 0, width, height,
                           all_planes, z_pixmap)
    if not image:
        sys.exit("screenshot-x11: XGetImage failed")
    im = image.contents
    if im.bits_per_pixel != 32 or (im.red_mask, im.green_mask, im.blue_mask) != (
            0xFF0000, 0xFF00, 0xFF):
        sys.exit("screenshot-x11: only 24-bit true colour screens (32 bits per pixel) are read")
    data = ctypes.string_at(im.data, im.bytes_per_line * height)
    rows = []
    for r in range(height):
        pixels = data[r * im.bytes_per_line:r * im.bytes_per_line + 4 * width]
        rgb = bytearray(3 * width)
        # little-endian 0x00RRGGBB pixels: bytes B, G, R, unused
        rgb[0::3], rgb[1::3], rgb[2::3] = pixels[2::4], pixels[1::4], pixels[0::4]
        rows.append(bytes(rgb))
    return rows


def scale_down(rows, factor):
    """Each factor x factor block of RGB pixels replaced by its mean."""
    if factor == 1:
        return rows
    width = len(rows[0]) // 3 // factor
    out = []
    for r in range(0, len(rows) // factor * factor, factor):
        block = rows[r:r + factor]
        row = bytearray(3 * width)
        for c in range(3):
            sums = [0] * width
            for line in block:
                channel = line[c::3]
                for k in range(factor):
                    sums = [s + v for s, v in zip(sums, channel[k::factor][:width])]
            n = factor * factor
            row[c::3] = bytes((s + n // 2) // n for s in sums)
        out.append(bytes(row))
    return out


def write_png(path, rows):
    width, height = len(rows[0]) // 3, len(rows)

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    raw = b"".join(b"\x00" + row for row in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--window", help="id of a top-level window (e.g. 0x20000c, from "
                        "xwininfo) to move to the top-left corner and resize to the whole screen "
                        "first (there is no window manager to maximize it)")
    parser.add_argument("--ignore-bottom", type=int, default=40,
                        help="rows at the bottom not compared while waiting")
    parser.add_argument("--settle", type=float, default=120,
                        help="at most this many seconds to wait for the screen to stop changing")
    parser.add_argument("--scale", type=int, default=1, help="scale down by this integer factor")
    args = parser.parse_args()
    xlib = ctypes.cdll.LoadLibrary("libX11.so.6")
    xlib.XOpenDisplay.restype = ctypes.c_void_p
    xlib.XOpenDisplay.argtypes = [ctypes.c_char_p]
    xlib.XDisplayWidth.argtypes = xlib.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
    xlib.XMoveResizeWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int,
                                       ctypes.c_int, ctypes.c_uint, ctypes.c_uint]
    xlib.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
    display = xlib.XOpenDisplay(None)
    if not display:
        sys.exit("screenshot-x11: cannot open the X display")
    width, height = xlib.XDisplayWidth(display, 0), xlib.XDisplayHeight(display, 0)
    if args.window:
        xlib.XMoveResizeWindow(display, int(args.window, 16), 0, 0, width, height)
        xlib.XSync(display, 0)
    # a big scene keeps software OpenGL busy for a while: wait until the window covers the whole
    # screen (its bottom-right pixel is no longer the bare black root) and two grabs agree but
    # for the bottom rows (a status bar may count frames per second)
    rows, waited = grab(xlib, display, width, height), 0.0
    while waited < args.settle:
        time.sleep(2)
        waited += 2
        previous, rows = rows, grab(xlib, display, width, height)
        top = height - args.ignore_bottom
        if rows[:top] == previous[:top] and rows[-1][-3:] != b"\0\0\0":
            break
    else:
        sys.exit("screenshot-x11: the screen did not settle in %g s" % args.settle)
    write_png(args.out, scale_down(rows, args.scale))


if __name__ == "__main__":
    main()
