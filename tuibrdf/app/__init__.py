"""The interactive viewer (Textual).  ``state`` and ``presets`` are plain Python; only
``tuibrdf.app.app`` and ``tuibrdf.app.widgets`` import Textual."""
