"""A preset of a BRDF Explorer model also saved as a ``.bparam`` file (BRDF Explorer's "save
parameters"), beside the preset: ``NAME.bparam`` for side A, ``NAME-B.bparam`` for side B in
compare mode, each referring to its ``.brdf`` file.  Sides of other models write nothing."""

from __future__ import annotations

from pathlib import Path

from tuibrdf.core.formats.bparam_write import source_brdf, write_bparam
from tuibrdf.core.formats.files import UserFileError
from tuibrdf.state.viewer import ViewerState


def save_bparams(state: ViewerState, preset: Path) -> str:
    """Write the ``.bparam`` files of ``state``'s BRDF Explorer sides beside the preset file
    ``preset``; the text a status line adds (`` + NAME.bparam``, or why not), empty when no
    side is from a ``.brdf`` file."""
    done, why = [], ""
    for i, side in enumerate(state.sides):
        try:
            if source_brdf(side.spec) is None:
                continue
            out = preset.with_name(preset.stem + ("-B" if i else "") + ".bparam")
            done.append(Path(write_bparam(side.spec, side.values, str(out))).name)
        except (UserFileError, OSError) as e:
            why = f" (.bparam not written: {e})"
    return "".join(f" + {n}" for n in done) + why
