"""Import-only stand-in for `ccp` (compressor package): ROSS imports it, the benchmark never calls it."""

Q_ = None


def __getattr__(name):
    raise AttributeError(f"ccp.{name}: ccp is not installed (bench/ross shim)")
