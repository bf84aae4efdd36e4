"""The process's C allocator: freed memory kept for reuse (glibc's ``M_TOP_PAD``).

numpy allocates each temporary of an expression with ``malloc``.  glibc gives freed memory at
the top of its heap back to the system once more than 128 KiB of it is free, so the next
expression's temporaries fault their pages in again: evaluating a ``.bsdf`` file's map (7,392
directions, temporaries of 60–180 KB) faulted 673 pages a call, and on a virtual machine, as a
remote lab machine often is, those faults took half of its 3.3 ms (1.6 ms with the memory
kept; ``MALLOC_TOP_PAD_=16777216`` measured the same).  Every command calls
:func:`keep_freed_memory` once before it runs (the library, imported by someone else's
program, leaves their allocator alone).
"""

from __future__ import annotations

import sys

#: ``M_TOP_PAD`` of glibc's ``<malloc.h>``: the bytes of free memory a heap keeps at its top
#: when it trims (for the main heap and each thread's), and adds when it grows
M_TOP_PAD = -2
#: what each heap keeps: a frame's temporaries, a few MB, with room to spare; at most this
#: much more resident memory per heap (the viewer has two or three: its loop and its frame
#: threads)
KEEP_BYTES = 16 << 20


def keep_freed_memory() -> bool:
    """Ask glibc to keep :data:`KEEP_BYTES` of freed memory per heap; whether it took it
    (False elsewhere: macOS, Windows and musl keep their own policies)."""
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    try:
        mallopt = ctypes.CDLL(None).mallopt  # the process's own C library
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return mallopt(M_TOP_PAD, KEEP_BYTES) == 1  # glibc: 1 on success
