"""Old PIL's `ImageDraw`: Pillow's, with old PIL's bitmap font as the default (see README.md)."""
from PIL import ImageFont
from PIL.ImageDraw import ImageDraw as _PillowImageDraw


class ImageDraw(_PillowImageDraw):
    def text(self, xy, text, fill=None, font=None, *args, **kw):
        if font is None:
            font = ImageFont.load_default_imagefont()
        return super().text(xy, text, fill=fill, font=font, *args, **kw)


def Draw(im, mode=None):
    return ImageDraw(im, mode)
