"""Pictures that notebooks show: the RGBA arrays Renderer.render returns are NumPy arrays of
this subclass, whose _repr_png_ gives Jupyter (and any IPython display) an 8-bit sRGB PNG,
encoded as `lantern.write_image` writes .png files: straight alpha, sRGB transfer, an sRGB
chunk."""
import struct as _struct
import zlib as _zlib

import numpy as _np


def _chunk(kind, data):
    body = kind + data
    return _struct.pack(">I", len(data)) + body + _struct.pack(">I", _zlib.crc32(body) & 0xFFFFFFFF)


def png_bytes(rgba):
    """An 8-bit sRGB PNG (straight alpha) of a (height, width, 4) or (height, width, 3) array of
    linear values (premultiplied when it has alpha), as bytes."""
    a = _np.asarray(rgba, dtype=_np.float32)
    if a.ndim != 3 or a.shape[2] not in (3, 4) or a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"a picture is (height, width, 3 or 4), not {a.shape}")
    a = _np.nan_to_num(a, nan=0.0, posinf=1.0, neginf=0.0)
    if a.shape[2] == 3:
        a = _np.concatenate([a, _np.ones(a.shape[:2] + (1,), _np.float32)], axis=2)
    alpha = _np.clip(a[..., 3:4], 0.0, 1.0)
    with _np.errstate(divide="ignore", invalid="ignore"):
        rgb = _np.where(alpha > 0.0, a[..., :3] / _np.maximum(alpha, 1e-30), 0.0)
    rgb = _np.clip(rgb, 0.0, 1.0)
    srgb = _np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * _np.power(rgb, 1.0 / 2.4) - 0.055)
    pixels = _np.concatenate([srgb, alpha], axis=2)
    data = _np.round(pixels * 255.0).astype(_np.uint8)
    h, w = data.shape[:2]
    rows = _np.concatenate([_np.zeros((h, 1), _np.uint8), data.reshape(h, w * 4)], axis=1)
    return (b"\x89PNG\r\n\x1a\n"
            + _chunk(b"IHDR", _struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + _chunk(b"sRGB", b"\x00")
            + _chunk(b"IDAT", _zlib.compress(rows.tobytes(), 6))
            + _chunk(b"IEND", b""))


class Picture(_np.ndarray):
    """A rendered picture: a NumPy array (height, width, 4) of linear, premultiplied float32
    RGBA, shown by notebooks as a PNG (_repr_png_). Everything NumPy does with it works as with
    the plain array; np.asarray(picture) is the plain array, without a copy."""

    def _repr_png_(self):
        """The picture as PNG bytes (8-bit sRGB, straight alpha); None when the array is not a
        picture's shape (a slice of one, say), so that the display falls back to repr."""
        if self.ndim != 3 or self.shape[2] not in (3, 4) or self.size == 0:
            return None
        return png_bytes(_np.asarray(self))


def as_picture(array):
    """`array` seen as a Picture (no copy); anything that is not a float array passes through."""
    if isinstance(array, _np.ndarray) and array.dtype == _np.float32 and array.ndim == 3:
        return array.view(Picture)
    return array
