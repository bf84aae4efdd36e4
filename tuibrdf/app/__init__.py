"""The interactive viewer (Textual): wiring only.  Its state is :mod:`tuibrdf.state`."""
