#!/usr/bin/python3
"""Writes the EXIF fixtures of io/exif_test.cpp byte by byte (no EXIF library, so the test checks
libexif's reading against an independent writer of the TIFF/EXIF 2.32 layout):

  capture.jpg  big-endian EXIF in a JPEG APP1 segment (no image data): Make, Model,
               DateTimeOriginal 2024:06:21 15:00:00, OffsetTimeOriginal +02:00, FocalLength 8 mm,
               FocalPlaneXResolution 300 per cm (unit 3), PixelXDimension 4000,
               GPS 48 deg 8' 0" N, 11 deg 34' 30" E, 520 m above sea level
  capture.tif  little-endian TIFF (no image data): DateTimeOriginal 2023:12:01 08:30:00 without
               an offset, FocalLength 4.5 mm, FocalPlaneXResolution 5080 per inch (default unit),
               GPS 33 deg 51' 36" S, 151 deg 12' 36" W

Run from this folder: /usr/bin/python3 make_fixtures.py
"""
import struct

ASCII, SHORT, LONG, RATIONAL = 2, 3, 4, 5


def tiff(order, ifd0, exif, gps):
    """A TIFF structure (header, IFD0 -> EXIF IFD, GPS IFD); entries (tag, type, values)."""
    e = order

    def pack_ifd(entries, offset, pointers):
        # entries sorted by tag; values longer than 4 bytes follow the IFD.
        entries = sorted(entries + pointers, key=lambda t: t[0])
        head = struct.pack(e + "H", len(entries))
        data = b""
        data_offset = offset + 2 + 12 * len(entries) + 4
        body = b""
        for tag, typ, values in entries:
            if typ == ASCII:
                raw = values.encode() + b"\0"
                count = len(raw)
            elif typ == SHORT:
                raw = b"".join(struct.pack(e + "H", v) for v in values)
                count = len(values)
            elif typ == LONG:
                raw = b"".join(struct.pack(e + "I", v) for v in values)
                count = len(values)
            else:
                raw = b"".join(struct.pack(e + "II", n, d) for n, d in values)
                count = len(values)
            if len(raw) <= 4:
                field = raw.ljust(4, b"\0")
            else:
                field = struct.pack(e + "I", data_offset + len(data))
                data += raw
                if len(data) % 2:
                    data += b"\0"
            body += struct.pack(e + "HHI", tag, typ, count) + field
        return head + body + struct.pack(e + "I", 0) + data

    def size(entries, pointers):
        return len(pack_ifd(entries, 0, pointers))

    header = (b"MM" if e == ">" else b"II") + struct.pack(e + "HI", 42, 8)
    ptr0 = [(0x8769, LONG, [0]), (0x8825, LONG, [0])]
    off0 = 8
    off_exif = off0 + size(ifd0, ptr0)
    off_gps = off_exif + size(exif, [])
    ptr0 = [(0x8769, LONG, [off_exif]), (0x8825, LONG, [off_gps])]
    return (header + pack_ifd(ifd0, off0, ptr0) + pack_ifd(exif, off_exif, []) +
            pack_ifd(gps, off_gps, []))


jpeg_tiff = tiff(
    ">",
    [(0x010F, ASCII, "SkylightTest"), (0x0110, ASCII, "Fisheye 8mm")],
    [(0x9003, ASCII, "2024:06:21 15:00:00"), (0x9011, ASCII, "+02:00"),
     (0x920A, RATIONAL, [(8, 1)]), (0xA20E, RATIONAL, [(300, 1)]), (0xA210, SHORT, [3]),
     (0xA002, LONG, [4000])],
    [(0x0001, ASCII, "N"), (0x0002, RATIONAL, [(48, 1), (8, 1), (0, 1)]),
     (0x0003, ASCII, "E"), (0x0004, RATIONAL, [(11, 1), (34, 1), (30, 1)]),
     (0x0006, RATIONAL, [(520, 1)])])
app1 = b"Exif\0\0" + jpeg_tiff
with open("capture.jpg", "wb") as f:
    f.write(b"\xff\xd8" + b"\xff\xe1" + struct.pack(">H", len(app1) + 2) + app1 + b"\xff\xd9")

tif = tiff(
    "<",
    [(0x010F, ASCII, "SkylightTest"), (0x0110, ASCII, "Compact")],
    [(0x9003, ASCII, "2023:12:01 08:30:00"), (0x920A, RATIONAL, [(45, 10)]),
     (0xA20E, RATIONAL, [(5080, 1)])],
    [(0x0001, ASCII, "S"), (0x0002, RATIONAL, [(33, 1), (51, 1), (36, 1)]),
     (0x0003, ASCII, "W"), (0x0004, RATIONAL, [(151, 1), (12, 1), (36, 1)])])
with open("capture.tif", "wb") as f:
    f.write(tif)
