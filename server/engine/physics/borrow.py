"""Views of arrays that compiled code does not reference-count.

numba counts references to every array a compiled function is given or an inlined helper
is passed, with atomic increments and decrements: in the tick loop, which hands the same
dozen arrays to its inlined helpers on every sub-step, those counts were over a third of a
search's shot. A view made here has no owner (a null meminfo, which the counting skips),
so it costs nothing to pass around. It must not outlive the call that made it: the caller's
own reference keeps the memory alive only that long.
"""

from typing import TYPE_CHECKING

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

if TYPE_CHECKING:
    import numpy as np

    def borrowed(array: np.ndarray) -> np.ndarray:
        """`array` as an ownerless view (same data, shape and strides)."""

else:

    @intrinsic
    def borrowed(typingctx, array):  # noqa: ARG001 (numba's intrinsic signature)
        """`array` as an ownerless view (same data, shape and strides)."""
        if not isinstance(array, types.Array):
            return None
        return array(array), _ownerless_view


def _ownerless_view(context, builder, signature, args):
    """The view's struct: the source's fields with a null meminfo and parent."""
    array_type = signature.return_type
    source = context.make_array(array_type)(context, builder, value=args[0])
    view = context.make_array(array_type)(context, builder)
    view.meminfo = cgutils.get_null_value(view.meminfo.type)
    view.parent = cgutils.get_null_value(view.parent.type)
    view.nitems = source.nitems
    view.itemsize = source.itemsize
    view.data = source.data
    view.shape = source.shape
    view.strides = source.strides
    return view._getvalue()  # noqa: SLF001 (numba's own way to hand the struct back)
