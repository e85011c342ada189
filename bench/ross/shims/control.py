"""Import-only stand-in for `python-control`: ROSS imports it (and reads
`TransferFunction.s` at import time); the benchmark never calls it."""


class TransferFunction:
    s = None  # read at ROSS's import, never used by the benchmark

    def __init__(self, *args, **kwargs):
        raise NotImplementedError("python-control is not installed (bench/ross shim)")


def __getattr__(name):
    raise AttributeError(f"control.{name}: python-control is not installed (bench/ross shim)")
