"""Stand-in for the `methodtools` package (not in Debian): only `lru_cache` as a method decorator.

ROSS decorates methods with ``@methodtools.lru_cache()``; the result is cached per instance, keyed
by the call's arguments. Arguments that cannot be hashed (arrays) bypass the cache.
"""
import functools


def lru_cache(*args, **kwargs):
    def decorate(method):
        attribute = "_shim_cache_" + method.__name__

        @functools.wraps(method)
        def cached(self, *call_args, **call_kwargs):
            key = (call_args, tuple(sorted(call_kwargs.items())))
            try:
                hash(key)
            except TypeError:
                return method(self, *call_args, **call_kwargs)
            store = self.__dict__.setdefault(attribute, {})
            if key not in store:
                store[key] = method(self, *call_args, **call_kwargs)
            return store[key]

        return cached

    # used both as @lru_cache and as @lru_cache(maxsize=...)
    if len(args) == 1 and callable(args[0]) and not kwargs:
        return decorate(args[0])
    return decorate
