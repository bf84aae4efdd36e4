"""The one error of the GLSL compiler: every stage (lexer, parser, compiler) raises
:class:`GlslError` with the line of the file it is about."""

from __future__ import annotations


class GlslError(ValueError):
    """A construct outside the supported subset, or a syntax/type error; ``line`` is the line
    in the file (1-based), ``construct`` the offending text."""

    def __init__(self, message: str, line: int):
        super().__init__(message)
        self.line = line
        self.message = message
