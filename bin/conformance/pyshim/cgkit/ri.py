"""The subset of cgkit.ri used by the suite's RunProgram helpers, writing RIB to stdout.

cgkit's RiBegin(RI_NULL) streams RIB to standard output; so does this module. Output goes
through sys.stdout.buffer encoded as Latin-1 so that RiArchiveRecord(RI_COMMENT, "\\377")
emits the single byte 0xFF that ends a RunProgram reply.
"""
import sys

RI_NULL = None
RI_COMMENT = "comment"
RI_VERBATIM = "verbatim"
RI_BILINEAR = "bilinear"
RI_BICUBIC = "bicubic"
RI_P = "P"
RI_N = "N"
RI_CS = "Cs"
RI_ST = "st"


def _out(text):
    sys.stdout.flush()
    sys.stdout.buffer.write(text.encode("latin-1"))


def _value(v):
    if isinstance(v, str):
        return '"%s"' % v
    if isinstance(v, (list, tuple)):
        return "[" + " ".join(_scalar(x) for x in v) + "]"
    return "[" + _scalar(v) + "]"


def _scalar(x):
    if isinstance(x, str):
        return '"%s"' % x
    return repr(float(x)) if isinstance(x, float) else str(x)


def _params(args, kw):
    pairs = list(zip(args[0::2], args[1::2])) + list(kw.items())
    return "".join(" %s %s" % (_value(k), _value(v)) for k, v in pairs)


def RiBegin(name=RI_NULL):
    pass


def RiEnd():
    sys.stdout.flush()


def RiSphere(radius, zmin, zmax, thetamax, *args, **kw):
    _out("Sphere %s %s %s %s%s\n" % (radius, zmin, zmax, thetamax, _params(args, kw)))


def RiSurface(name, *args, **kw):
    _out("Surface %s%s\n" % (_value(name), _params(args, kw)))


def RiPatch(kind, *args, **kw):
    _out("Patch %s%s\n" % (_value(kind), _params(args, kw)))


def RiArchiveRecord(kind, fmt, *args):
    text = fmt % args if args else fmt
    _out(("#" if kind == RI_COMMENT else "") + text + "\n")
